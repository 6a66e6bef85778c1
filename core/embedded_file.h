#pragma once
// A text file compiled into the binary (see cmake/EmbedFiles.cmake).
#include <span>
#include <string_view>

namespace zenith {

struct EmbeddedFile {
  std::string_view name;      ///< logical name, e.g. "atmospheres/earth-standard.json"
  std::string_view contents;  ///< the file's bytes
};

}  // namespace zenith
