// Display-referred previews as 8-bit sRGB PNG: each linear value goes through
// the tone mapping operator and the sRGB transfer function and is rounded to a
// byte (display_byte, tone_mapping.h; SrgbQuantizer computes the same bytes
// without pow). Rows are streamed to libpng one at a time (png_write_row), so
// the writer holds one row of bytes.
//
// The file is deterministic: no tIME chunk, libpng's default zlib level and
// filter heuristics, attributes in the order given. It carries an sRGB chunk
// (perceptual intent) and one tEXt chunk per attribute (iTXt, UTF-8, where the
// value is not plain ASCII).
//
// 16-bit greyscale maps (write_png_grey16: blend masks and black-level maps for
// projectors, docs/warp-meshes.md) go through the same PngStream with a gAMA
// chunk stating their encoding instead of the sRGB chunk.
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/display_image_writer.h"
#include "image/image_writer.h"
#include "image/png_support.h"
#include "image/srgb_quantizer.h"
#include "image/writer_support.h"

namespace zenith::image {
namespace {

constexpr long long kMaxSide_px = 32768;       ///< as read_image accepts
constexpr std::size_t kMaxKeywordLength = 79;  ///< PNG specification, 11.3.4.2

/// A PNG text keyword: 1–79 printable ASCII characters (the specification allows
/// Latin-1; attribute names are UTF-8, so only ASCII means the same in both), no
/// leading, trailing or consecutive spaces.
void check_keyword(const std::filesystem::path& path, const std::string& key) {
  bool ok = !key.empty() && key.size() <= kMaxKeywordLength && key.front() != ' ' && key.back() != ' ';
  for (std::size_t i = 0; ok && i < key.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(key[i]);
    ok = c >= 32 && c <= 126 && !(c == ' ' && i > 0 && key[i - 1] == ' ');
  }
  if (!ok)
    throw std::invalid_argument(detail::prefix(path) + "attribute name '" + key +
                                "' is not a PNG keyword (1 to 79 printable ASCII characters, no leading, trailing "
                                "or double spaces)");
}

bool is_ascii(const std::string& text) {
  for (char c : text)
    if (static_cast<unsigned char>(c) > 127) return false;
  return true;
}

/// png_rw_ptr writing to the FILE*; a short write is a libpng error naming errno.
void write_to_file(png_structp png, png_bytep data, std::size_t length) {
  auto* file = static_cast<std::FILE*>(png_get_io_ptr(png));
  if (std::fwrite(data, 1, length, file) != length) {
    char message[160];
    std::snprintf(message, sizeof message, "write error: %s", std::strerror(errno));
    png_error(png, message);
  }
}

/// png_flush_ptr: a failed flush (a full disk shows here, not in fwrite) is a
/// libpng error naming errno.
void flush_file(png_structp png) {
  if (std::fflush(static_cast<std::FILE*>(png_get_io_ptr(png))) != 0) {
    char message[160];
    std::snprintf(message, sizeof message, "write error: %s", std::strerror(errno));
    png_error(png, message);
  }
}

/// One PNG file being written: the libpng state, the .partial file and its
/// publication. The header (size, bit depth, colour type, the colour chunk and
/// the attributes as text chunks) is written on construction; rows of encoded
/// bytes follow; finish() ends the file and renames it into place. Without
/// finish() (an exception, an abandoned writer) the partial file is removed.
class PngStream {
 public:
  /// `gamma`: 0 writes an sRGB chunk (perceptual intent); > 0 a gAMA chunk of
  /// 1 / gamma (stored values are linear values^(1 / gamma)).
  /// `compression_level`: -1 leaves libpng's defaults (zlib level 6, adaptive
  /// filters); 0–9 sets the zlib level, and levels 0–3 use the Sub filter alone
  /// (one filter tried per row instead of five: the fast setting).
  PngStream(const std::filesystem::path& path, int width, int height, int bit_depth, int colour_type, double gamma,
            const ImageAttributes& attributes, int compression_level = -1)
      : path_(path), partial_(detail::partial_path_for(path)) {
    for (const auto& [name, value] : attributes) {
      check_keyword(path_, name);
      if (value.find('\0') != std::string::npos)
        throw std::invalid_argument(detail::prefix(path_) + "attribute '" + name + "' holds a NUL character");
    }
    file_ = std::fopen(partial_.c_str(), "wb");
    if (!file_)
      throw std::runtime_error(detail::prefix(path_) + "cannot create " + partial_.string() + ": " +
                               std::strerror(errno));
    png_ = png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors_, detail::png_error_callback,
                                   detail::png_warning_callback);
    if (png_) info_ = png_create_info_struct(png_);
    if (!png_ || !info_) {
      abandon();
      throw std::runtime_error(detail::prefix(path_) + "libpng cannot allocate its state");
    }
    // libpng copies the text in png_set_text; the pointers only need to live until then.
    std::vector<png_text> text(attributes.size());
    for (std::size_t i = 0; i < attributes.size(); ++i) {
      const auto& [name, value] = attributes[i];
      text[i].compression = is_ascii(value) ? PNG_TEXT_COMPRESSION_NONE : PNG_ITXT_COMPRESSION_NONE;
      text[i].key = const_cast<char*>(name.c_str());
      text[i].text = const_cast<char*>(value.c_str());
      text[i].text_length = value.size();
    }
    png_structp png = png_;
    png_infop info = info_;
    std::FILE* file = file_;
    png_text* text_data = text.data();
    const int text_count = static_cast<int>(text.size());
    const bool ok = detail::png_guarded(png, [=] {
      png_set_write_fn(png, file, write_to_file, flush_file);
      png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), bit_depth, colour_type, PNG_INTERLACE_NONE,
                   PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
      if (compression_level >= 0) {
        png_set_compression_level(png, compression_level);
        if (compression_level <= 3) png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
      }
      if (gamma > 0.0)
        png_set_gAMA(png, info, 1.0 / gamma);
      else
        png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
      if (text_count > 0) png_set_text(png, info, text_data, text_count);
      png_write_info(png, info);
    });
    if (!ok) {
      const std::string reason = errors_.message;
      abandon();
      throw std::runtime_error(detail::prefix(path_) + "PNG: " + reason);
    }
  }
  PngStream(const PngStream&) = delete;
  PngStream& operator=(const PngStream&) = delete;

  ~PngStream() {
    if (!finished_) abandon();
  }

  const std::filesystem::path& path() const { return path_; }
  bool open() const { return !finished_ && !failed_; }

  /// Rows given as RGBA (4 samples a pixel) whose alpha libpng drops, and
  /// 16-bit samples in this machine's byte order (swapped to PNG's big endian
  /// on little-endian machines): display textures as read back from the GPU.
  void take_rgba_native_rows() {
    png_structp png = png_;
    const bool ok = detail::png_guarded(png, [=] {
      png_set_filler(png, 0, PNG_FILLER_AFTER);
      if constexpr (std::endian::native == std::endian::little) png_set_swap(png);
    });
    if (!ok) fail();
  }

  /// One row of encoded bytes (16-bit samples big endian, as PNG stores them).
  void write_row(png_bytep row) {
    png_structp png = png_;
    if (!detail::png_guarded(png, [=] { png_write_row(png, row); })) fail();
  }

  void finish() {
    png_structp png = png_;
    png_infop info = info_;
    if (!detail::png_guarded(png, [=] { png_write_end(png, info); })) fail();
    png_destroy_write_struct(&png_, &info_);
    // Buffered bytes reach the disk at the flush or the close: a full disk
    // (ENOSPC) or a file-size limit shows there, and the message says which.
    errno = 0;
    const bool write_error = std::ferror(file_) != 0 || std::fflush(file_) != 0;
    const int write_errno = errno;
    const bool close_error = std::fclose(file_) != 0;
    const int cause = write_errno != 0 ? write_errno : errno;
    file_ = nullptr;
    if (write_error || close_error) {
      failed_ = true;
      throw std::runtime_error(detail::prefix(path_) + "error writing " + partial_.string() + ": " +
                               (cause != 0 ? std::strerror(cause) : "unknown cause"));
    }
    detail::publish(partial_, path_);
    finished_ = true;
  }

 private:
  [[noreturn]] void fail() {
    failed_ = true;
    throw std::runtime_error(detail::prefix(path_) + "PNG: " + errors_.message);
  }

  /// Releases libpng and the file and removes the partial file; never throws.
  void abandon() noexcept {
    if (png_) png_destroy_write_struct(&png_, info_ ? &info_ : nullptr);
    png_ = nullptr;
    info_ = nullptr;
    if (file_) std::fclose(file_);
    file_ = nullptr;
    detail::discard(partial_);
  }

  std::filesystem::path path_, partial_;
  detail::PngErrorState errors_;
  std::FILE* file_ = nullptr;
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
  bool finished_ = false, failed_ = false;
};

class PngWriter final : public ImageWriter {
 public:
  PngWriter(const std::filesystem::path& path, int width, int height, ToneMapping tone,
            const ImageAttributes& attributes)
      : ImageWriter(width, height),
        stream_(path, width, height, 8, PNG_COLOR_TYPE_RGB, 0.0, attributes),
        tone_(tone),
        row_(std::size_t(width) * 3) {}

  void write_rows(int row_count, std::span<const float> rgb) override {
    detail::check_row_block(stream_.path(), width(), height(), rows_written_, row_count, rgb.size(), stream_.open());
    const std::size_t row_values = std::size_t(width()) * 3;
    for (int r = 0; r < row_count; ++r) {
      const float* in = rgb.data() + std::size_t(r) * row_values;
      for (std::size_t k = 0; k < row_values; ++k) row_[k] = quantize_(tone_map(in[k], tone_));
      stream_.write_row(row_.data());
      ++rows_written_;
    }
  }

  void finish() override {
    detail::check_complete(stream_.path(), height(), rows_written_, stream_.open());
    stream_.finish();
  }

 private:
  PngStream stream_;
  ToneMapping tone_;
  SrgbQuantizer quantize_;
  std::vector<png_byte> row_;  ///< one row of 8-bit RGB
  int rows_written_ = 0;
};

}  // namespace

std::unique_ptr<ImageWriter> open_png_writer(const std::filesystem::path& path, int width, int height, ToneMapping tone,
                                             const ImageAttributes& attributes) {
  detail::check_dimensions(path, width, height, kMaxSide_px);
  detail::check_unique_names(path, attributes);
  return std::make_unique<PngWriter>(path, width, height, tone, attributes);
}

void write_png_grey16(const std::filesystem::path& path, int width, int height, std::span<const std::uint16_t> grey,
                      double gamma, const ImageAttributes& attributes) {
  detail::check_dimensions(path, width, height, kMaxSide_px);
  detail::check_unique_names(path, attributes);
  if (grey.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument(detail::prefix(path) + std::to_string(grey.size()) + " samples for a " +
                                std::to_string(width) + "x" + std::to_string(height) + " image");
  if (!(gamma > 0.0 && gamma <= 10.0))
    throw std::invalid_argument(detail::prefix(path) + "gamma " + std::to_string(gamma) + ": must be in (0, 10]");
  PngStream stream(path, width, height, 16, PNG_COLOR_TYPE_GRAY, gamma, attributes);
  std::vector<png_byte> row(std::size_t(width) * 2);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint16_t value = grey[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      row[std::size_t(x) * 2] = static_cast<png_byte>(value >> 8);  // PNG: big endian
      row[std::size_t(x) * 2 + 1] = static_cast<png_byte>(value & 0xFF);
    }
    stream.write_row(row.data());
  }
  stream.finish();
}

void write_png_display(const std::filesystem::path& path, int width, int height, int bits,
                       std::span<const std::byte> rgba, int compression_level, const ImageAttributes& attributes) {
  detail::check_dimensions(path, width, height, kMaxSide_px);
  detail::check_unique_names(path, attributes);
  if (bits != 8 && bits != 16)
    throw std::invalid_argument(detail::prefix(path) + std::to_string(bits) + " bits a sample: must be 8 or 16");
  if (compression_level < 0 || compression_level > 9)
    throw std::invalid_argument(detail::prefix(path) + "PNG compression level " + std::to_string(compression_level) +
                                ": must be in [0, 9]");
  const std::size_t row_bytes = std::size_t(width) * 4 * std::size_t(bits / 8);
  if (rgba.size() != row_bytes * std::size_t(height))
    throw std::invalid_argument(detail::prefix(path) + std::to_string(rgba.size()) + " bytes for a " +
                                std::to_string(width) + "x" + std::to_string(height) + " RGBA image of " +
                                std::to_string(bits) + "-bit samples");
  PngStream stream(path, width, height, bits, PNG_COLOR_TYPE_RGB, 0.0, attributes, compression_level);
  stream.take_rgba_native_rows();
  // libpng only reads the row (the filler and swap transforms work on a copy).
  auto* data = reinterpret_cast<png_bytep>(const_cast<std::byte*>(rgba.data()));
  for (int y = 0; y < height; ++y) stream.write_row(data + std::size_t(y) * row_bytes);
  stream.finish();
}

}  // namespace zenith::image

namespace zenith::image {

int parse_png_compression(const std::string& text) {
  if (text == "fast") return kFastPngCompression;
  if (text == "default") return kDefaultPngCompression;
  if (text == "best") return 9;
  if (text.size() == 1 && text[0] >= '0' && text[0] <= '9') return text[0] - '0';
  throw std::invalid_argument("--png-compression '" + text + "': must be fast, default, best or a level 0 to 9");
}

}  // namespace zenith::image
