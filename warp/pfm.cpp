#include "warp/pfm.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "core/files.h"

namespace zenith::warp {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

/// A printable excerpt of a header token for error messages.
std::string shown(std::string_view token) {
  std::string out;
  for (char c : token.substr(0, 24)) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  if (token.size() > 24) out += "...";
  return out;
}

/// Walks the text header token by token.
class HeaderCursor {
 public:
  HeaderCursor(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(name_ + ": PFM: " + what); }

  /// The next whitespace-delimited token (leading whitespace skipped); empty at the end.
  std::string_view token() {
    while (pos_ < bytes_.size() && is_space(bytes_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_])) ++pos_;
    return bytes_.substr(start, pos_ - start);
  }

  int size_field(const char* field) {
    const std::string_view text = token();
    if (text.empty()) fail(std::string("bad header: missing ") + field);
    long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
      fail(std::string("bad header: ") + field + " '" + shown(text) + "' is not an integer");
    if (value < 1 || value > kMaxPfmSizePx)
      fail(std::string("bad header: ") + field + " " + std::to_string(value) + " must be in [1, " +
           std::to_string(kMaxPfmSizePx) + "]");
    return static_cast<int>(value);
  }

  double scale_field() {
    const std::string_view text = token();
    if (text.empty()) fail("bad header: missing scale");
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
      fail("bad header: scale '" + shown(text) + "' is not a number");
    if (value == 0.0 || !std::isfinite(value))
      fail("bad header: scale " + shown(text) + " must be a non-zero finite number (its sign gives the byte order)");
    return value;
  }

  /// After the scale: exactly one whitespace character, or "\r\n"; returns the
  /// offset of the first sample byte.
  std::size_t end_of_header() {
    if (pos_ >= bytes_.size()) fail("truncated: the header ends without sample data");
    if (bytes_[pos_] == '\r' && pos_ + 1 < bytes_.size() && bytes_[pos_ + 1] == '\n') return pos_ + 2;
    return pos_ + 1;  // the token loop stopped on a whitespace character
  }

 private:
  std::string_view bytes_;
  const std::string& name_;
  std::size_t pos_ = 0;
};

float decode_float(const char* bytes, bool little_endian) {
  std::uint32_t word = 0;
  std::memcpy(&word, bytes, sizeof word);
  const bool host_little = std::endian::native == std::endian::little;
  if (little_endian != host_little)
    word = ((word & 0xffu) << 24) | ((word & 0xff00u) << 8) | ((word >> 8) & 0xff00u) | (word >> 24);
  return std::bit_cast<float>(word);
}

}  // namespace

PfmImage parse_pfm(std::string_view bytes, const std::string& name, PfmRowOrder stored_rows) {
  HeaderCursor cursor(bytes, name);
  const std::string_view magic = cursor.token();
  PfmImage image;
  if (magic == "PF") {
    image.channels = 3;
  } else if (magic == "Pf") {
    image.channels = 1;
  } else {
    cursor.fail("bad header: expected 'PF' (3 channels) or 'Pf' (1 channel), found '" + shown(magic) + "'");
  }
  image.width = cursor.size_field("width");
  image.height = cursor.size_field("height");
  const bool little_endian = cursor.scale_field() < 0.0;
  const std::size_t data_offset = cursor.end_of_header();

  const std::size_t count = static_cast<std::size_t>(image.width) * image.height * image.channels;
  const std::size_t expected_bytes = count * sizeof(float);
  const std::size_t available_bytes = bytes.size() - data_offset;
  const std::string geometry = std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                               std::to_string(image.channels) + " floats";
  if (available_bytes < expected_bytes)
    cursor.fail("truncated: " + std::to_string(available_bytes) + " bytes of sample data, expected " +
                std::to_string(expected_bytes) + " (" + geometry + ")");
  if (available_bytes > expected_bytes)
    cursor.fail(std::to_string(available_bytes - expected_bytes) + " bytes after the sample data (" + geometry + ")");

  image.samples.resize(count);
  const std::size_t row_values = static_cast<std::size_t>(image.width) * image.channels;
  for (int stored = 0; stored < image.height; ++stored) {
    const int row = stored_rows == PfmRowOrder::top_to_bottom ? stored : image.height - 1 - stored;
    const char* source = bytes.data() + data_offset + static_cast<std::size_t>(stored) * row_values * sizeof(float);
    float* target = image.samples.data() + static_cast<std::size_t>(row) * row_values;
    for (std::size_t k = 0; k < row_values; ++k) target[k] = decode_float(source + k * sizeof(float), little_endian);
  }
  return image;
}

PfmImage read_pfm(const std::filesystem::path& path, PfmRowOrder stored_rows) {
  return parse_pfm(core::file_bytes(path), path.string(), stored_rows);
}

std::string encode_pfm(const PfmImage& image, PfmRowOrder stored_rows) {
  if (image.channels != 1 && image.channels != 3)
    throw std::invalid_argument("encode_pfm: " + std::to_string(image.channels) + " channels: must be 1 or 3");
  if (image.width < 1 || image.width > kMaxPfmSizePx || image.height < 1 || image.height > kMaxPfmSizePx)
    throw std::invalid_argument("encode_pfm: size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                ": each side must be in [1, " + std::to_string(kMaxPfmSizePx) + "]");
  const std::size_t row_values = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.channels);
  const std::size_t count = row_values * static_cast<std::size_t>(image.height);
  if (image.samples.size() != count)
    throw std::invalid_argument("encode_pfm: " + std::to_string(image.samples.size()) + " samples, expected " +
                                std::to_string(count));
  // Scale -1: little-endian samples.
  std::string bytes = std::string(image.channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(image.width) + " " +
                      std::to_string(image.height) + "\n-1\n";
  const std::size_t header = bytes.size();
  bytes.resize(header + count * sizeof(float));
  for (int stored = 0; stored < image.height; ++stored) {
    const int row = stored_rows == PfmRowOrder::top_to_bottom ? stored : image.height - 1 - stored;
    const float* source = image.samples.data() + static_cast<std::size_t>(row) * row_values;
    char* target = bytes.data() + header + static_cast<std::size_t>(stored) * row_values * sizeof(float);
    for (std::size_t k = 0; k < row_values; ++k) {
      const auto word = std::bit_cast<std::uint32_t>(source[k]);
      for (std::size_t b = 0; b < sizeof(float); ++b)
        target[k * sizeof(float) + b] = static_cast<char>((word >> (8 * b)) & 0xFFu);
    }
  }
  return bytes;
}

}  // namespace zenith::warp
