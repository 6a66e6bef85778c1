#pragma once
// Reading images (albedo maps) — the writers for rendered frames are in image_writer.h.
#include <filesystem>
#include <vector>

namespace zenith::image {

/// A float RGB image in linear light, row 0 at the top, x fastest.
struct LinearImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< width · height · 3
};

/// Reads a PNG (1–16 bit, grey/grey+alpha/RGB/RGBA/palette, interlaced or not; sRGB
/// decoded to linear with the exact IEC 61966-2-1 curve, alpha dropped) or an
/// OpenEXR (R, G, B or else Y channels, half/float/uint; linear as stored), told
/// apart by their magic bytes. Throws std::runtime_error starting "<path>: " and
/// saying what is wrong (missing, not an image, truncated, corrupt, a missing
/// channel, unsupported layout, larger than 32768 px per side, empty).
LinearImage read_image(const std::filesystem::path& path);

}  // namespace zenith::image
