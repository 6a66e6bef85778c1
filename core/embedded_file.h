#pragma once
// A text file compiled into the binary (see cmake/EmbedFiles.cmake), and the
// lookups every module that embeds files needs.
#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace zenith {

struct EmbeddedFile {
  std::string_view name;      ///< logical name, e.g. "atmospheres/earth-standard.json"
  std::string_view contents;  ///< the file's bytes
};

namespace core {

/// The contents of the file called `name`, if `files` has it.
inline std::optional<std::string_view> find_embedded(std::span<const EmbeddedFile> files, std::string_view name) {
  for (const EmbeddedFile& f : files)
    if (f.name == name) return f.contents;
  return std::nullopt;
}

/// The names in `files` that start with `prefix` (all by default), sorted.
inline std::vector<std::string> embedded_names(std::span<const EmbeddedFile> files, std::string_view prefix = {}) {
  std::vector<std::string> names;
  for (const EmbeddedFile& f : files)
    if (f.name.substr(0, prefix.size()) == prefix) names.emplace_back(f.name);
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace core
}  // namespace zenith
