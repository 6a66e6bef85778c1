#pragma once
// A lower bound of the sky radiance the atmosphere passes draw per unit of the
// sun's irradiance on any ray that leaves the atmosphere, for a camera inside
// it (docs/night-sky.md, "Rendering the night sky"): what the star pass's test
// (render/night/star_visibility.h) needs to know, before any GPU work, that
// the sky behind every star in view is at least this bright. No GL. The
// counterpart of SkyRadianceBound (atmosphere/lut/sky_radiance_bound.h), which
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
#include <array>
#include <cstddef>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"

namespace zenith::atmosphere::lut {

/// A closed interval [lo, hi].
struct Interval {
  double lo = 0.0, hi = 0.0;
};

class SkyRadianceLowerBound;

/// The frame's part of the tables for bounds over parts of the sky
/// (SkyRadianceLowerBound::slice): every read of a frame from a camera inside the
/// shell has the camera's radius r and the sun's cosine μs there, so the same
/// two radius rows with the same weights and the same two μs columns with the
/// same blend; only μ and ν vary. Per table, per μs column, ν slice, sky-half
/// μ texel and wavelength: the least its two rows give for any row weight the
/// texture unit can use (t_r ± 1/256: the 8 bits of sub-texel weight of
/// NVIDIA's filtering). A read at (μ, φ) weighs the μ texels and ν slices
/// around it with weights in [0, 1] summing to 1, so it is at least their
/// least; the μs blend of two columns at least a and b is at least the
/// geometric a^(1−t) b^t (least_blend), t within 1e-3 of the frame's.
class SkyLowerBoundSlice {
 public:
  SkyLowerBoundSlice() = default;
  /// Per wavelength [sr⁻¹] into `out` (channels values): a lower bound of S per
  /// unit sun irradiance of every sky-half read whose view cosine μ lies in
  /// `mu` and whose azimuth from the sun's vertical φ (scattering_u_nu: u_ν =
  /// φ/π) lies in `phi_rad` ⊂ [0, π], Rayleigh's phase applied at a ν in
  /// `nu_rayleigh` and Mie's at a ν in `nu_mie`. Zeros for an empty slice.
  void radiance_per_irradiance(Interval mu, Interval phi_rad, Interval nu_rayleigh, Interval nu_mie, double* out) const;
  std::size_t channels() const { return channels_; }

 private:
  friend class SkyRadianceLowerBound;
  struct Term {
    std::size_t a = 0, b = 0;                // μs columns
    double t_lo = 0.0, t_hi = 0.0;           // the blend's weight of b, widened
    std::vector<double> column_a, column_b;  // [(k * half + y) * channels + i]
  };
  /// The least over μ texels [y0, y1] (of the sky half) and ν slices [k0, k1], blended in μs.
  double least(const Term& term, std::size_t y0, std::size_t y1, std::size_t k0, std::size_t k1, std::size_t i) const;
  /// The sky-half μ texel range and ν slice range a read in (mu, phi) weighs, per μ mapping.
  void texel_ranges(Interval mu, Interval phi_rad, bool blended, std::size_t& y0, std::size_t& y1, std::size_t& k0,
                    std::size_t& k1) const;
  const SkyRadianceLowerBound* floor_ = nullptr;
  double radius_m_ = 0.0, mu_s_ = 0.0;  // clamped to the tables' ranges
  std::size_t channels_ = 0, half_ = 0, nu_ = 0;
  Term rayleigh_, mie_, multiple_;
  bool multiple_on_ = false, mie_on_ = false;
};

class SkyRadianceLowerBound {
 public:
  SkyRadianceLowerBound() = default;
  /// The tables' sky-half minima per radius row, μs column and wavelength (one
  /// pass over the 4D tables); `multiple_scattering`: whether the passes read
  /// the multiple-scattering table (AtmospherePassFeatures::multiple_scattering
  /// and a table of order ≥ 2).
  SkyRadianceLowerBound(const AtmosphereModel& model, const LookupTables& tables, bool multiple_scattering);

  /// Per wavelength [sr⁻¹], a lower bound of the sky radiance per unit sun
  /// irradiance on every ray from a camera at `radius_m` (in the shell) that
  /// meets no ground, the sun's cosine at the camera `mu_s`. Zeros for an
  /// empty floor (default-constructed).
  std::vector<double> radiance_per_irradiance(double mu_s, double radius_m) const;

  /// The frame's slice of the tables' sky half for a camera at `radius_m`
  /// with the sun's cosine `mu_s` there: bounds over parts of the sky
  /// (SkyLowerBoundSlice). Empty for an empty floor.
  SkyLowerBoundSlice slice(double mu_s, double radius_m) const;

 private:
  friend class SkyLowerBoundSlice;
  ShellGeometry geometry_{};
  TableSizes sizes_{};
  std::size_t channels_ = 0;
  // Per radius row z, μs column c and wavelength i, at [(z * columns + c) *
  // channels + i]: the smallest sky-half texel of single Rayleigh times the
  // smallest P_R, of single Mie times the smallest P_M, of multiple scattering.
  std::vector<double> rayleigh_, mie_, multiple_;
  // The sky half of the three tables as the passes read them (per radius row
  // z, sky-half μ texel y, packed x = ν slice · μs columns + μs column and
  // wavelength, at [((z * half + y) * width + x) * channels + i]; 18 MiB for
  // the paper's sizes): the frame's slices. The multiple table's is empty
  // where the passes do not read it, the Mie table's without Mie.
  std::vector<float> sky_rayleigh_, sky_mie_, sky_multiple_;
  // The phases: Rayleigh's A + B ν² (P(0), P(1)); Mie's on a grid of 4097 cosines per wavelength.
  double rayleigh_at_0_ = 0.0, rayleigh_at_1_ = 0.0;
  std::vector<double> mie_phase_grid_;  // [k * channels + i]
};

}  // namespace zenith::atmosphere::lut
