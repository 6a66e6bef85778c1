#pragma once
// Real spherical harmonics of degree 3 and 4, orthonormal over the unit
// sphere (∫ Y_lm Y_l'm' dω = δ), in Cartesian form for a unit vector
// (x, y, z), m = −l … l (Sloan, "Stupid Spherical Harmonics (SH) Tricks",
// GDC 2008, appendix). Their use is the addition theorem
//   Σ_m Y_lm(u) Y_lm(v) = (2l + 1)/(4π) P_l(u·v),
// so for light L over the sphere with c_lm = ∫ L Y_lm dω,
//   ∫ P_l(ω·v) L(ω) dω = 4π/(2l + 1) Σ_m Y_lm(v) c_lm:
// a phase function's Legendre term l of the light from its 2l + 1
// coefficients (astro/moon_shadow.h). shaders/render/moon_shadow.glsl
// writes the same polynomials.
#include <array>

namespace zenith::core {

/// Y_3,−3 … Y_3,3 then Y_4,−4 … Y_4,4 of the unit vector (x, y, z).
inline std::array<double, 16> spherical_harmonics_3_4(double x, double y, double z) {
  const double x2 = x * x, y2 = y * y, z2 = z * z;
  return {
      0.5900435899266435 * y * (3.0 * x2 - y2),      2.890611442640554 * x * y * z,
      0.4570457994644658 * y * (5.0 * z2 - 1.0),     0.3731763325901154 * z * (5.0 * z2 - 3.0),
      0.4570457994644658 * x * (5.0 * z2 - 1.0),     1.445305721320277 * z * (x2 - y2),
      0.5900435899266435 * x * (x2 - 3.0 * y2),      2.503342941796705 * x * y * (x2 - y2),
      1.770130769779931 * y * z * (3.0 * x2 - y2),   0.9461746957575601 * x * y * (7.0 * z2 - 1.0),
      0.6690465435572892 * y * z * (7.0 * z2 - 3.0), 0.1057855469152043 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0),
      0.6690465435572892 * x * z * (7.0 * z2 - 3.0), 0.4730873478787800 * (x2 - y2) * (7.0 * z2 - 1.0),
      1.770130769779931 * x * z * (x2 - 3.0 * y2),   0.6258357354491761 * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2)),
  };
}

}  // namespace zenith::core
