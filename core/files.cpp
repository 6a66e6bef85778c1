#include "core/files.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include "core/strings.h"

namespace zenith::core {

std::string unreadable_reason(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);  // follows links: what opening would read
  if (error || status.type() == fs::file_type::not_found) return {};
  switch (status.type()) {
    case fs::file_type::regular: break;
    case fs::file_type::directory: return "is a directory";
    case fs::file_type::fifo:
      return "is a FIFO (named pipe), not a regular file: refused (reading it could wait forever)";
    case fs::file_type::character: return "is a character device, not a regular file: refused";
    case fs::file_type::block: return "is a block device, not a regular file: refused";
    case fs::file_type::socket: return "is a socket, not a regular file: refused";
    default: return "is not a regular file: refused";
  }
  const std::uintmax_t size = fs::file_size(path, error);
  if (!error && size > max_bytes)
    return cat(size, " bytes, more than the ", max_bytes, "-byte limit of an input file: refused");
  return {};
}

std::string file_bytes(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  if (const std::string why = unreadable_reason(path, max_bytes); !why.empty())
    throw std::runtime_error(cat(path.string(), ": ", why));
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
