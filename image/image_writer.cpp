// The writer-independent part of image_writer.h: pixel-type names and the
// whole-image convenience functions. The writers are in exr_writer.cpp and
// png_writer.cpp.
#include "image/image_writer.h"

#include <stdexcept>

namespace zenith::image {

const char* to_string(ExrPixelType type) {
  switch (type) {
    case ExrPixelType::half: return "half";
    case ExrPixelType::float32: return "float";
  }
  return "?";
}

ExrPixelType parse_exr_pixel_type(const std::string& text) {
  if (text == "half") return ExrPixelType::half;
  if (text == "float") return ExrPixelType::float32;
  throw std::invalid_argument("unknown EXR pixel type '" + text + "': must be one of half, float");
}

void write_exr(const std::filesystem::path& path, int width, int height, std::span<const float> rgb, ExrPixelType type,
               const ImageAttributes& attributes) {
  const std::unique_ptr<ImageWriter> writer = open_exr_writer(path, width, height, type, attributes);
  writer->write_rows(height, rgb);
  writer->finish();
}

void write_png(const std::filesystem::path& path, int width, int height, std::span<const float> rgb, ToneMapping tone,
               const ImageAttributes& attributes) {
  const std::unique_ptr<ImageWriter> writer = open_png_writer(path, width, height, tone, attributes);
  writer->write_rows(height, rgb);
  writer->finish();
}

}  // namespace zenith::image
