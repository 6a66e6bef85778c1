#include "image/png_encoder.h"

#include <stdexcept>
#include <string>

#include "image/png_support.h"

namespace zenith::image {
namespace {

constexpr int kMaxSide_px = 32768;  ///< as the PNG writer and read_image accept

/// png_rw_ptr appending to the std::vector<std::uint8_t> of the io pointer.
void append_to_vector(png_structp png, png_bytep data, std::size_t length) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + length);
}

void flush_nothing(png_structp) {}

}  // namespace

std::vector<std::uint8_t> encode_png_rgb8(int width, int height, std::span<const std::uint8_t> rgb) {
  if (width < 1 || height < 1 || width > kMaxSide_px || height > kMaxSide_px)
    throw std::invalid_argument("PNG in memory: " + std::to_string(width) + "x" + std::to_string(height) +
                                " pixels, each side must be in [1, 32768]");
  const std::size_t row_bytes = static_cast<std::size_t>(width) * 3;
  if (rgb.size() != row_bytes * static_cast<std::size_t>(height))
    throw std::invalid_argument("PNG in memory: " + std::to_string(rgb.size()) + " bytes for " + std::to_string(width) +
                                "x" + std::to_string(height) + " RGB pixels, expected " +
                                std::to_string(row_bytes * static_cast<std::size_t>(height)));
  detail::PngErrorState errors;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, detail::png_error_callback, detail::png_warning_callback);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    if (png) png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("PNG in memory: libpng cannot allocate its state");
  }
  std::vector<std::uint8_t> out;
  std::vector<std::uint8_t>* sink = &out;
  const std::uint8_t* pixels = rgb.data();
  const bool ok = detail::png_guarded(png, [=] {
    png_set_write_fn(png, sink, append_to_vector, flush_nothing);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
      png_write_row(png, const_cast<png_bytep>(pixels + static_cast<std::size_t>(y) * row_bytes));
    png_write_end(png, info);
  });
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error(std::string("PNG in memory: ") + errors.message);
  return out;
}

}  // namespace zenith::image
