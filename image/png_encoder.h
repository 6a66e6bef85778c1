#pragma once
// PNG in memory: 8-bit sRGB pixels, already encoded, to the bytes of a PNG
// file (the operator console serves its dome preview this way). Files are
// written by image_writer.h.
#include <cstdint>
#include <span>
#include <vector>

namespace zenith::image {

/// The PNG file of a `width` × `height` image of 8-bit sRGB `rgb` (rows top
/// to bottom, RGB interleaved; width · height · 3 bytes), with an sRGB chunk
/// and no text chunks. Throws std::invalid_argument for a size below 1 or
/// above 32768 or a byte count other than width · height · 3, and
/// std::runtime_error when libpng fails.
std::vector<std::uint8_t> encode_png_rgb8(int width, int height, std::span<const std::uint8_t> rgb);

}  // namespace zenith::image
