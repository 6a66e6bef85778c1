#pragma once
// Portable float maps (PFM): the raster format of warp maps (MPCDI geometry
// warps, plain PFM warp files). docs/warp-meshes.md describes what is accepted.
//
// Layout of a file:
//
//   "PF" (3 channels) or "Pf" (1 channel), whitespace,
//   width, whitespace, height, whitespace,          decimal integers in [1, 16384]
//   scale, one whitespace character ("\r\n" also accepted),
//   width · height · channels IEEE 754 binary32 samples, x fastest, channels interleaved.
//
// The sign of the scale gives the byte order of the samples (negative: little
// endian, positive: big endian); its magnitude is not used. The classic format
// stores the bottom row first; MPCDI's geometry warps store the top row first
// ("samples start top-left"), so the reader takes the stored row order as a
// parameter. NaN (and any non-finite value) is kept as it is: warp maps use it
// for "no data".
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace zenith::warp {

/// The order in which a PFM stores its rows.
enum class PfmRowOrder {
  bottom_to_top,  ///< classic PFM: the first stored row is the bottom of the image
  top_to_bottom,  ///< MPCDI geometry warps: the first stored row is the top
};

/// A decoded PFM, whatever its stored row order: row 0 is the top of the image,
/// x fastest, channels interleaved.
struct PfmImage {
  int width = 0, height = 0;
  int channels = 0;            ///< 1 ("Pf") or 3 ("PF")
  std::vector<float> samples;  ///< width · height · channels

  /// Sample c of the pixel in column x, row y (row 0 at the top).
  float at(int x, int y, int c) const { return samples[(static_cast<std::size_t>(y) * width + x) * channels + c]; }
};

/// Largest accepted width and height (a 16K projector is 15360 px wide).
inline constexpr int kMaxPfmSizePx = 16384;

/// Decodes a PFM held in memory. `name` (a file name, or "archive.mpcdi:warp.pfm")
/// starts every error message. Throws std::runtime_error "<name>: PFM: <what is
/// wrong>" for a bad magic or header field, a size outside [1, 16384], a zero or
/// non-finite scale, fewer sample bytes than the header promises ("truncated")
/// and bytes after the samples.
PfmImage parse_pfm(std::string_view bytes, const std::string& name, PfmRowOrder stored_rows);

/// Reads and decodes a PFM file; also throws std::runtime_error "<path>: cannot
/// open" when the file cannot be read.
PfmImage read_pfm(const std::filesystem::path& path, PfmRowOrder stored_rows = PfmRowOrder::bottom_to_top);

/// The bytes of a PFM holding `image` (row 0 = its top), its rows stored in
/// `stored_rows` order, samples little endian (scale −1), NaN kept: what
/// parse_pfm(bytes, name, stored_rows) reads back bit for bit. Throws
/// std::invalid_argument for a channel count other than 1 or 3, a size outside
/// [1, 16384] or a sample count that does not match.
std::string encode_pfm(const PfmImage& image, PfmRowOrder stored_rows);

}  // namespace zenith::warp
