#include "warp/blend_map.h"

#include <png.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace zenith::warp {
namespace {

constexpr png_uint_32 kMaxSizePx = 16384;

// libpng reports errors through a callback that must not return; the way out is
// a longjmp to a setjmp point. No C++ object with a destructor may live in a
// frame the jump crosses, so every libpng call runs inside guarded() below,
// whose steps touch only plain data reached through pointers.

/// What the callbacks share: the input and the last error message.
struct PngSource {
  const unsigned char* data;
  std::size_t size;
  std::size_t offset;
  char message[256];
};

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
  auto* source = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(source->message, sizeof source->message, "%s", message ? message : "unknown libpng error");
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}  // e.g. a damaged ancillary chunk, which libpng skips

void on_read(png_structp png, png_bytep out, png_size_t count) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (source->size - source->offset < count) png_error(png, "truncated PNG data");
  std::memcpy(out, source->data + source->offset, count);
  source->offset += count;
}

/// The layout after the reader's transformations.
struct Layout {
  png_uint_32 width, height;
  int channels, bit_depth;
  std::size_t row_bytes;
};

/// Runs `step` under libpng's error jump; false if libpng reported an error.
template <class Step>
bool guarded(png_structp png, const Step& step) {
  if (setjmp(png_jmpbuf(png))) return false;
  step();
  return true;
}

/// Owns the libpng structures.
struct PngReader {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngReader() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

}  // namespace

BlendMap decode_png_map(std::string_view bytes, const std::string& name) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
    throw std::runtime_error(name + ": not a PNG file");
  PngSource source{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), 0, "unknown libpng error"};
  PngReader reader;
  reader.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, on_error, on_warning);
  if (!reader.png) throw std::runtime_error(name + ": cannot create a PNG reader");
  reader.info = png_create_info_struct(reader.png);
  if (!reader.info) throw std::runtime_error(name + ": cannot create a PNG reader");
  png_set_read_fn(reader.png, &source, on_read);
  png_set_user_limits(reader.png, kMaxSizePx, kMaxSizePx);

  Layout layout{};
  png_structp png = reader.png;
  png_infop info = reader.info;
  Layout* out = &layout;
  const bool header_ok = guarded(png, [png, info, out] {
    png_read_info(png, info);
    const int colour = png_get_color_type(png, info);
    if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (colour == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    png_set_strip_alpha(png);
    if (png_get_bit_depth(png, info) == 16 && std::endian::native == std::endian::little)
      png_set_swap(png);  // PNG stores 16-bit samples big endian
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    out->width = png_get_image_width(png, info);
    out->height = png_get_image_height(png, info);
    out->channels = png_get_channels(png, info);
    out->bit_depth = png_get_bit_depth(png, info);
    out->row_bytes = png_get_rowbytes(png, info);
  });
  if (!header_ok) throw std::runtime_error(name + ": " + source.message);
  if ((layout.channels != 1 && layout.channels != 3) || (layout.bit_depth != 8 && layout.bit_depth != 16))
    throw std::runtime_error(name + ": unsupported PNG layout (" + std::to_string(layout.channels) + " channels of " +
                             std::to_string(layout.bit_depth) + " bits after expansion)");
  if (layout.width == 0 || layout.height == 0) throw std::runtime_error(name + ": empty PNG");

  std::vector<unsigned char> pixels(layout.row_bytes * layout.height);
  std::vector<png_bytep> rows(layout.height);
  for (png_uint_32 y = 0; y < layout.height; ++y) rows[y] = pixels.data() + y * layout.row_bytes;
  png_bytepp row_pointers = rows.data();
  if (!guarded(png, [png, info, row_pointers] {
        png_read_image(png, row_pointers);
        png_read_end(png, info);
      }))
    throw std::runtime_error(name + ": " + source.message);

  BlendMap map;
  map.width = static_cast<int>(layout.width);
  map.height = static_cast<int>(layout.height);
  map.channels = layout.channels;
  map.bit_depth = layout.bit_depth;
  const std::size_t per_row = static_cast<std::size_t>(layout.width) * layout.channels;
  map.values.resize(per_row * layout.height);
  const float scale = layout.bit_depth == 16 ? 1.0f / 65535.0f : 1.0f / 255.0f;
  for (png_uint_32 y = 0; y < layout.height; ++y) {
    const unsigned char* row = rows[y];
    float* target = map.values.data() + y * per_row;
    for (std::size_t k = 0; k < per_row; ++k) {
      unsigned value = row[k];
      if (layout.bit_depth == 16) {
        std::uint16_t word = 0;
        std::memcpy(&word, row + 2 * k, 2);
        value = word;
      }
      target[k] = static_cast<float>(value) * scale;
    }
  }
  return map;
}

std::vector<std::uint16_t> encode_map_16(std::span<const float> values, double gamma) {
  if (!(gamma > 0.0 && gamma <= 10.0))
    throw std::invalid_argument("encode_map_16: gamma " + std::to_string(gamma) + ": must be in (0, 10]");
  std::vector<std::uint16_t> stored(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double value = std::isnan(values[k]) ? 0.0 : std::clamp(static_cast<double>(values[k]), 0.0, 1.0);
    const double encoded = gamma == 1.0 ? value : std::pow(value, 1.0 / gamma);
    stored[k] = static_cast<std::uint16_t>(std::lround(encoded * 65535.0));
  }
  return stored;
}

}  // namespace zenith::warp
