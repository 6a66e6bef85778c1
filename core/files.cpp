#include "core/files.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include "core/strings.h"

namespace zenith::core {

std::string file_bytes(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw std::runtime_error(cat(path.string(), ": is a directory"));
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw std::runtime_error(cat(path.string(), ": cannot open (", std::strerror(errno), ")"));
  std::string bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  if (stream.bad()) throw std::runtime_error(cat(path.string(), ": read error"));
  return bytes;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) return {};
  return std::string((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
}

}  // namespace zenith::core
