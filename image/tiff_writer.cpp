// 16-bit RGB TIFF frames from display codes (image/display_image_writer.h),
// written with libtiff. Errors are collected per file through libtiff's
// per-file handlers (TIFFOpenOptions, libtiff ≥ 4.5), so threads writing
// frames at once never share an error buffer.
#include <tiffio.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/display_image_writer.h"
#include "image/writer_support.h"

namespace zenith::image {
namespace {

constexpr long long kMaxSide_px = 32768;
constexpr std::uint32_t kRowsPerStrip = 8;

struct TiffErrors {
  std::string message;
};

int collect_error(TIFF*, void* user_data, const char* module, const char* format, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  auto* errors = static_cast<TiffErrors*>(user_data);
  if (errors->message.empty()) errors->message = std::string(module ? module : "libtiff") + ": " + text;
  return 1;
}

int ignore_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

std::string description_of(const ImageAttributes& attributes) {
  std::string text;
  for (const auto& [name, value] : attributes) text += name + "=" + value + "\n";
  return text;
}

}  // namespace

const char* to_string(TiffCompression compression) {
  switch (compression) {
    case TiffCompression::none: return "none";
    case TiffCompression::deflate: return "deflate";
    case TiffCompression::lzw: return "lzw";
  }
  return "?";
}

TiffCompression parse_tiff_compression(const std::string& text) {
  if (text == "none") return TiffCompression::none;
  if (text == "deflate") return TiffCompression::deflate;
  if (text == "lzw") return TiffCompression::lzw;
  throw std::invalid_argument("--tiff-compression '" + text + "': must be none, deflate or lzw");
}

void write_tiff16_display(const std::filesystem::path& path, int width, int height, std::span<const std::uint16_t> rgba,
                          TiffCompression compression, const ImageAttributes& attributes) {
  detail::check_dimensions(path, width, height, kMaxSide_px);
  detail::check_unique_names(path, attributes);
  const std::size_t w = std::size_t(width);
  if (rgba.size() != w * std::size_t(height) * 4)
    throw std::invalid_argument(detail::prefix(path) + std::to_string(rgba.size()) + " samples for a " +
                                std::to_string(width) + "x" + std::to_string(height) + " RGBA image");
  const std::filesystem::path partial = detail::partial_path_for(path);
  TiffErrors errors;
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options, collect_error, &errors);
  TIFFOpenOptionsSetWarningHandlerExtR(options, ignore_warning, nullptr);
  errno = 0;
  TIFF* tiff = TIFFOpenExt(partial.c_str(), "w", options);
  TIFFOpenOptionsFree(options);
  if (tiff == nullptr)
    throw std::runtime_error(detail::prefix(path) + "cannot create " + partial.string() + ": " +
                             (errno != 0 ? std::strerror(errno) : errors.message));
  const auto fail = [&](const std::string& what) {
    const int error = errno;
    TIFFClose(tiff);
    detail::discard(partial);
    throw std::runtime_error(detail::prefix(path) + what + ": " + (error != 0 ? std::strerror(error) : errors.message));
  };
  const std::string description = description_of(attributes);
  TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, std::uint32_t(width));
  TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, std::uint32_t(height));
  TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, 3);
  TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, 16);
  TIFFSetField(tiff, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
  TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB);
  TIFFSetField(tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(tiff, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
  TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, kRowsPerStrip);
  TIFFSetField(tiff, TIFFTAG_SOFTWARE, "zenith");
  if (!description.empty()) TIFFSetField(tiff, TIFFTAG_IMAGEDESCRIPTION, description.c_str());
  switch (compression) {
    case TiffCompression::none: TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_NONE); break;
    case TiffCompression::deflate:
      TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
      TIFFSetField(tiff, TIFFTAG_ZIPQUALITY, 1);
      TIFFSetField(tiff, TIFFTAG_PREDICTOR, PREDICTOR_HORIZONTAL);
      break;
    case TiffCompression::lzw:
      TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_LZW);
      TIFFSetField(tiff, TIFFTAG_PREDICTOR, PREDICTOR_HORIZONTAL);
      break;
  }
  // A strip of RGB samples at a time (libtiff encodes the buffer in place).
  std::vector<std::uint16_t> strip(w * 3 * kRowsPerStrip);
  for (std::uint32_t first = 0, s = 0; first < std::uint32_t(height); first += kRowsPerStrip, ++s) {
    const std::uint32_t rows = std::min(kRowsPerStrip, std::uint32_t(height) - first);
    const std::uint16_t* in = rgba.data() + std::size_t(first) * w * 4;
    for (std::size_t i = 0; i < w * rows; ++i)
      for (std::size_t c = 0; c < 3; ++c) strip[3 * i + c] = in[4 * i + c];
    errno = 0;
    if (TIFFWriteEncodedStrip(tiff, s, strip.data(), tmsize_t(w * rows * 3 * sizeof(std::uint16_t))) < 0)
      fail("error writing " + partial.string());
  }
  errno = 0;
  if (!TIFFFlush(tiff)) fail("error writing " + partial.string());
  TIFFClose(tiff);
  detail::publish(partial, path);
}

}  // namespace zenith::image
