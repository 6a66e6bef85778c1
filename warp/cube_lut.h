#pragma once
// Colour lookup tables in the IRIDAS/Adobe .cube format, as VESA MPCDI v2.0
// §3.8 stores its decode, correct and encode LUTs:
//
//   # a comment (a line whose first non-blank character is '#')
//   TITLE "projector 1"                 optional, once
//   LUT_1D_SIZE N                       N in [4, 65536] (MPCDI §3.8), or
//   LUT_3D_SIZE N                       N in [2, 256]
//   DOMAIN_MIN 0 0 0                    optional; must be 0 0 0
//   DOMAIN_MAX 1 1 1                    optional; must be 1 1 1 (> 1 is reserved for HDR, §3.8)
//   r g b                               N (1D) or N³ (3D) rows, red fastest in 3D
//
// Strict: every error is a std::runtime_error naming the source (the archive
// and member), the line and the field, e.g.
//   "show.mpcdi:decode.cube:3: LUT_1D_SIZE 2: must be in [4, 65536] (VESA MPCDI v2.0 §3.8)".
// Lenient only where real exports are known to differ from Adobe's text:
// CRLF line ends and blank lines (every writer on Windows), comments after the
// header and between rows (Resolve, OCIO's ociobakelut), keywords in any case,
// and Resolve's LUT_1D_INPUT_RANGE / LUT_3D_INPUT_RANGE lo hi read as
// DOMAIN_MIN lo lo lo / DOMAIN_MAX hi hi hi (so held to 0 and 1 alike).
// Output values are not limited to [0, 1] (a correction may overshoot; the
// output stage clamps where it encodes) but must be finite.
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace zenith::warp {

inline constexpr int kMinCube1dSize = 4;  ///< VESA MPCDI v2.0 §3.8
inline constexpr int kMaxCube1dSize = 65536;
inline constexpr int kMinCube3dSize = 2;
inline constexpr int kMaxCube3dSize = 256;

struct CubeLut {
  enum class Kind { lut_1d, lut_3d };
  Kind kind = Kind::lut_1d;
  std::string title;  ///< TITLE, "" when absent
  int size = 0;       ///< entries per channel (1D) or lattice points per axis (3D)
  /// RGB triples: 1D, entry i at 3i (input i / (size − 1)); 3D, lattice point
  /// (r, g, b) at 3 · (r + size · (g + size · b)) (red fastest, as .cube stores them).
  std::vector<float> rgb;

  bool is_3d() const { return kind == Kind::lut_3d; }
  /// 1D: each channel through its own column, linear interpolation between
  /// entries (input clamped to [0, 1], position x · (size − 1)). 3D: trilinear
  /// interpolation in the lattice of the clamped input. Computed in double.
  std::array<double, 3> apply(const std::array<double, 3>& input) const;
};

/// Parses the text of a .cube file; `source` names it in messages.
CubeLut parse_cube_lut(std::string_view text, const std::string& source);

/// A .cube file's text of `lut` (TITLE when set, the size, DOMAIN_MIN/MAX 0 and
/// 1, the rows with 9 significant digits): what parse_cube_lut reads back.
std::string format_cube_lut(const CubeLut& lut);

}  // namespace zenith::warp
