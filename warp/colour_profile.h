#pragma once
// An MPCDI region's colour profile (VESA MPCDI v2.0 §2.5, the <color> element
// with the fileset's <decodeLUT>, <correctLUT> and <encodeLUT>): the three
// stages a media player applies to the signal it sends a projector,
//
//   1 decode   (§2.5.1.1)    L = (E / Scale)^γ_d, or the decode 1D LUT
//   2 correct  (§2.5.1.2)    1D LUT then the 3×3 primaries matrix, or the 3D LUT;
//                            then the blend: L' = α · L · (1 − β) + β  (processPixel, §2.5.2)
//   3 encode   (§2.5.1.3)    E' = Scale · L'^(1/γ_e), or the encode 1D or 3D LUT; none: E' = L'
//
// Values here are normalized signals (E / Scale in [0, 1]); the caller scales
// to codes. docs/warp-meshes.md, "Colour profile", places it in zenith's
// output stage. Pure arithmetic: the GPU twin is shaders/render/display_transform.glsl.
#include <array>
#include <optional>
#include <string>

#include "warp/cube_lut.h"

namespace zenith::warp {

/// Exponents a <decode> or <encode> gamma may take (§2.5.1.2.4 names none; a
/// display's is about 1.8 to 2.6, the interval is generous).
inline constexpr double kMinColourGamma = 0.1;
inline constexpr double kMaxColourGamma = 10.0;

struct MpcdiColourProfile {
  struct Decode {
    enum class Type { gamma, lut1d };
    Type type = Type::gamma;
    double gamma = 1.0;          ///< gamma: L = E^gamma ("none" reads as gamma 1)
    std::optional<CubeLut> lut;  ///< lut1d: the fileset's <decodeLUT> (1D)
  };
  struct Correct {
    enum class Type { none, lut1d_primary, lut3d };
    Type type = Type::none;
    /// lut1d_primary: the fileset's <correctLUT> (1D; absent: identity);
    /// lut3d: the <correctLUT> (3D), which replaces the 1D LUT and primaries (§2.5.1.2.3).
    std::optional<CubeLut> lut;
    /// lut1d_primary: <primaries>, row i the output channel i's weights of
    /// (R, G, B): Rout = R·red.red + G·red.green + B·red.blue (§2.5.2,
    /// correctColor1D). Identity when absent.
    std::array<std::array<double, 3>, 3> primaries{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  };
  struct Encode {
    enum class Type { none, gamma, lut1d, lut3d };
    Type type = Type::none;
    double gamma = 1.0;          ///< gamma: E = L^(1/gamma)
    std::optional<CubeLut> lut;  ///< lut1d, lut3d: the fileset's <encodeLUT>
  };
  Decode decode;
  Correct correct;
  Encode encode;
  int line = 0;  ///< of <color> in the descriptor (messages)

  /// Stage 1 of a normalized signal (each channel clamped to [0, 1]).
  std::array<double, 3> decoded(const std::array<double, 3>& signal) const;
  /// Stage 2's global part, clamped to [0, 1] (a projector emits between its
  /// black and its white; the encode's power of a negative would be undefined).
  std::array<double, 3> corrected(const std::array<double, 3>& linear) const;
  /// Stage 3 of a linear value in [0, 1], clamped to [0, 1].
  std::array<double, 3> encoded(const std::array<double, 3>& linear) const;
  /// processPixel (§2.5.2) upstream of the projector: decode, correct, the
  /// blend L' = α · L · (1 − β) + β, encode. `signal` normalized.
  std::array<double, 3> process(const std::array<double, 3>& signal, double alpha, double black_level) const;
};

/// "gamma 2.2", "lut1d (17 entries)", "lut1d-primary", "lut3d (17³)", ...: for logs and image attributes.
std::string describe(const MpcdiColourProfile& profile);

}  // namespace zenith::warp
