#pragma once
// An upper bound of what an atmosphere's passes can draw per unit of a
// source's irradiance (docs/night-sky.md, "Moonlight"), for a source whose
// cosine to the local zenith is at most μs_max wherever the pixels' lookups
// read the tables: what the moonlight passes' test (render/night/moon_light.h)
// needs to know, before any GPU work, whether the Moon could change a display
// value. No GL.
//
// Each term of a pixel's radiance is bounded by the largest texel it can read,
// since every read interpolates between texels with weights in [0, 1] —
// bilinear in (μ, r), linear in ν, and in μs geometric a^(1−t) b^t or linear,
// both ≤ max(a, b) — over the μs columns up to the one above μs_max:
//   S ≤ max R · max P_R + max (M · P_M,max(λ, texel)) + max multiple   (4D tables)
//   L_ground ≤ ρ/π (max(μs_max, 0) + max E_sky),  ρ ≤ 1        (ground)
// and the aerial perspective's S(x0) − T S(y) ≤ S(x0), T ≤ 1 through the rest.
// P_M,max(λ, texel) is the largest Mie phase a lookup weighing that texel can
// apply (the view–source angle is bounded below by the texel's neighbourhood
// in μ, μs and ν): the forward peak counts only where the source can be near
// the view. The texels' maxima per μs column are taken once per table set.
#include <cstddef>
#include <optional>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"

namespace zenith::atmosphere::lut {

class SkyRadianceBound {
 public:
  SkyRadianceBound() = default;
  /// The tables' maxima per μs column and wavelength (one pass over the 4D tables).
  SkyRadianceBound(const AtmosphereModel& model, const LookupTables& tables);

  /// Per wavelength [sr⁻¹], the largest radiance per unit source irradiance any
  /// pixel of sky or ground can have when the source's cosine at every point read
  /// is at most `mu_s_max` (the source's disc and the surfaces of other bodies
  /// excluded) and, given `radius_m`, the 4D tables are read only at that radius
  /// (a camera inside the shell with no other body in it: every sky ray from the
  /// camera, the ground's light at RB) — else at every radius.
  std::vector<double> radiance_per_irradiance(double mu_s_max, std::optional<double> radius_m = std::nullopt) const;

 private:
  ShellGeometry geometry_{};
  TableSizes sizes_{};
  std::size_t channels_ = 0;
  // Per radius row z, μs column c and wavelength i, at [(z * columns + c) *
  // channels + i]: the largest single Rayleigh (times the largest P_R), single
  // Mie (times the largest P_M a lookup of it applies) and multiple-scattering
  // texel; per column and wavelength the largest sky irradiance at the ground.
  std::vector<double> single_, mie_, multiple_, irradiance_;
};

/// The cosine bound μs_max for a source at cosine `mu_s_camera` to the zenith
/// of a camera `camera_radius_m` from the centre of an atmosphere with these
/// radii: inside the shell the sky is read at the camera, the ground it sees
/// lies within an arc γ = acos(RB/r) of the camera's zenith, and a body inside
/// the shell (`bodies_inside`) within γ + acos(RB/RT), so the source stands at
/// most γ higher there; from outside, 1.
double source_cosine_bound(double mu_s_camera, double camera_radius_m, double ground_radius_m, double top_radius_m,
                           bool bodies_inside);

}  // namespace zenith::atmosphere::lut
