#include "apps/default_configs.h"

#include <spdlog/spdlog.h>

#include <fstream>
#include <span>
#include <stdexcept>
#include <system_error>

#include "atmosphere/lut/table_cache.h"
#include "core/embedded_file.h"
#include "core/sha256.h"
#include "core/strings.h"

namespace zenith::app {
namespace embedded_configs {
std::span<const zenith::EmbeddedFile> embedded_files();  // generated (apps/CMakeLists.txt)
}  // namespace embedded_configs

namespace {

namespace fs = std::filesystem;
using core::cat;

/// Writes `contents` to `path` unless it holds them already (temporary file + rename).
void write_if_different(const fs::path& path, std::string_view contents) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      const std::string existing((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (existing == contents) return;
    }
  }
  fs::create_directories(path.parent_path());
  fs::path partial = path;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    if (!out) throw std::runtime_error(cat("cannot write ", partial.string()));
  }
  fs::rename(partial, path);
}

}  // namespace

fs::path default_config(const std::string& name) {
  const fs::path local = fs::path("configs") / name;
  std::error_code ec;
  if (fs::is_regular_file(local, ec)) return local;

  // Every embedded file, in one folder named by their combined hash: a newer
  // binary with other defaults never reads an older copy.
  const auto files = embedded_configs::embedded_files();
  std::string all;
  for (const EmbeddedFile& f : files) all += cat(f.name, '\n', f.contents, '\n');
  if (!core::find_embedded(files, name))
    throw std::runtime_error(cat("no configuration ", local.string(), " here and none named ", name, " built in"));
  const fs::path folder = atmosphere::lut::default_cache_directory() / "embedded-configs" /
                          core::sha256_hex(all.data(), all.size()).substr(0, 16);
  for (const EmbeddedFile& f : files) write_if_different(folder / f.name, f.contents);
  spdlog::info("{} is not in this directory: using the built-in copy {}", local.string(), (folder / name).string());
  return folder / name;
}

}  // namespace zenith::app
