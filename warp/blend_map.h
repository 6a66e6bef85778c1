#pragma once
// Blend and black-level maps (MPCDI alpha and beta maps): PNG images whose
// stored values are used as they are, with no colour decoding. (image::read_image
// decodes sRGB to linear light: right for pictures, wrong for these maps, whose
// encoding is told by the file that references them, e.g. MPCDI's gammaEmbedded.)
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace zenith::warp {

/// A decoded map: row 0 at the top, x fastest, channels interleaved; each value
/// is the stored integer divided by 2^bit_depth − 1, so in [0, 1].
struct BlendMap {
  int width = 0, height = 0;
  int channels = 0;   ///< 1 (grey, grey + alpha) or 3 (RGB, RGBA, palette); alpha channels are dropped
  int bit_depth = 0;  ///< 8 or 16 after expansion (1, 2 and 4-bit greys and palettes read as 8)
  std::vector<float> values;

  float at(int x, int y, int c) const { return values[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
};

/// Decodes a PNG held in memory. Throws std::runtime_error "<name>: <what is
/// wrong>" for data that is not a PNG, truncated or corrupt data (libpng's
/// message), and images larger than 16384 px per side.
BlendMap decode_png_map(std::string_view bytes, const std::string& name);

/// The inverse for 16-bit maps: each value in [0, 1] (clamped; NaN → 0) encoded
/// as stored = round(value^(1 / gamma) · 65535), so that a reader recovers
/// value = (stored / 65535)^gamma (MPCDI's gammaEmbedded, a viewport blend
/// file's "gamma"). gamma 1: linear; 2.2: the display encoding of projector
/// blend maps. Throws std::invalid_argument for gamma outside (0, 10].
std::vector<std::uint16_t> encode_map_16(std::span<const float> values, double gamma);

}  // namespace zenith::warp
