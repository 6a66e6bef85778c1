#pragma once
// A lower bound of the sky radiance the atmosphere passes draw per unit of the
// sun's irradiance on any ray that leaves the atmosphere, for a camera inside
// it (docs/night-sky.md, "Rendering the night sky"): what the star pass's test
// (render/frame/star_visibility.h) needs to know, before any GPU work, that
// the sky behind every star in view is at least this bright. No GL. The
// counterpart of SkyRadianceBound (render/frame/sky_radiance_bound.h), which
// bounds the same reads from above.
//
// A pixel whose ray from a camera at radius r leaves the shell without meeting
// the ground reads S = R · P_R(ν) + M · P_M(ν) + multiple at (r, μ, μs, ν),
// μs the sun's cosine at the camera, from the 4D tables' sky half (texels
// y ≥ n_μ/2: the ground half is a separate layer no sky read weighs), or the
// sky-view table's sky half, whose texels are those same reads at the camera.
// Every read interpolates with weights in [0, 1] — bilinear in (μ, r), linear
// in ν, in μs geometric a^(1−t) b^t, linear or in between (all ≥ the
// geometric one, which grows with a and b) — and every pixel's read has the
// same r and μs, so the same row weights (1 − t_r, t_r) and μs weight t_s:
//   column c:  A_c ≥ (1 − t_r) m(r₀, c) + t_r m(r₁, c),  m the least texel
//              over every μ of the sky half and every ν slice;
//   S ≥ A_c₀^(1−t_s) A_c₁^t_s for R, M and multiple (each with its own μs
//       mapping), R and M times their smallest phases.
// A table's texel below 0 (the multiple table's tail of orders) makes that
// term's bound the smaller of its columns. Bodies in front of the sky, the
// Moon's light, the night floor and other atmospheres only add.
#include <cstddef>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"

namespace zenith::render {

class SkyRadianceFloor {
 public:
  SkyRadianceFloor() = default;
  /// The tables' sky-half minima per radius row, μs column and wavelength (one
  /// pass over the 4D tables); `multiple_scattering`: whether the passes read
  /// the multiple-scattering table (AtmospherePassFeatures::multiple_scattering
  /// and a table of order ≥ 2).
  SkyRadianceFloor(const atmosphere::AtmosphereModel& model, const atmosphere::lut::LookupTables& tables,
                   bool multiple_scattering);

  /// Per wavelength [sr⁻¹], a lower bound of the sky radiance per unit sun
  /// irradiance on every ray from a camera at `radius_m` (in the shell) that
  /// meets no ground, the sun's cosine at the camera `mu_s`. Zeros for an
  /// empty floor (default-constructed).
  std::vector<double> radiance_per_irradiance(double mu_s, double radius_m) const;

 private:
  atmosphere::lut::ShellGeometry geometry_{};
  atmosphere::lut::TableSizes sizes_{};
  std::size_t channels_ = 0;
  // Per radius row z, μs column c and wavelength i, at [(z * columns + c) *
  // channels + i]: the smallest sky-half texel of single Rayleigh times the
  // smallest P_R, of single Mie times the smallest P_M, of multiple scattering.
  std::vector<double> rayleigh_, mie_, multiple_;
};

}  // namespace zenith::render
