#pragma once
// Pickering's air mass and how it enters the optical depth (paper section 4.4).
#include <vector>

#include "atmosphere/density_profile.h"

namespace zenith::atmosphere {

/// Pickering's (2002) relative air mass, paper eq. (21), for an observer at sea
/// level and an apparent altitude h [degrees above the horizon]:
///   X(h) = 1 / sin(h + 244 / (165 + 47 h^1.1))   (angles in degrees).
/// X(90°) = 1, X(30°) = 1.9932, X(10°) = 5.5807, X(0°) = 38.749. Defined for h ∈ [0°, 90°].
double pickering_air_mass(double apparent_altitude_deg);

/// How Pickering's air mass enters the model.
///
/// The paper stretches the path length of Earth rays so that the optical depth
/// follows Pickering's air mass, which includes refraction, instead of the
/// straight-line (geometric) air mass of a spherical shell. We implement that as
/// a multiplicative *stretch* s of the optical depth of every straight ray:
///
///   τ_corrected = s · τ_geometric,   s = X_Pickering(h_g) / X_geometric(h_g),
///
/// where h_g is the elevation angle the ray has where it crosses the ground
/// sphere and X_geometric is the straight-ray air mass of the model's own
/// molecular profile, integrated once at construction. Because h_g depends only
/// on the ray's impact parameter p = r·sinθ, which is constant along a straight
/// line, s is constant along a ray: T(x, y) = T(x, x₀)/T(y, x₀) stays exact and
/// the lookup tables need no new dimension. Consequences:
///  * an observer on the ground sees exactly Pickering's relative air mass;
///  * s → 1 toward the zenith and reaches ≈ 1.09 at Earth's horizon;
///  * for rays that pass above the ground (p > R_ground) the bending fades with
///    the density at the ray's lowest point: s = 1 + (s_h − 1)·ρ_R(p − R_ground);
///  * s is continuous in direction and altitude;
///  * s ≥ 1: where Pickering's fit dips a hair below the straight-ray air mass
///    (well above the horizon, by < 1e-3) refraction cannot shorten a path, so
///    the ratio is clamped to 1.
/// It is switchable (`air_mass: "geometric"` gives s ≡ 1) and meant for Earth,
/// the planet for which Pickering fitted it.
class AirMassStretch {
 public:
  /// Identity (geometric air mass, s ≡ 1).
  AirMassStretch() = default;
  /// Pickering stretch for a planet of radius `ground_radius_m` whose molecular
  /// density follows `molecular_profile` up to `top_radius_m`.
  static AirMassStretch pickering(double ground_radius_m, double top_radius_m, const DensityProfile& molecular_profile);

  bool enabled() const { return !stretch_.empty(); }
  /// Smallest and largest stretch over all ground elevations (1 when disabled).
  /// Pickering fitted Earth's refraction; for a planet of very different
  /// geometry the ratio leaves [1, 1.5] and the option is refused by the loader.
  double min_stretch() const;
  double max_stretch() const;
  /// Optical-depth stretch for a ray through radius r [m] with cosine μ of its zenith angle.
  double operator()(double r_m, double mu) const;
  /// Straight-ray relative air mass of the molecular profile from the ground at
  /// elevation h [deg] (the denominator of s); exposed for tests and reports.
  double geometric_air_mass(double elevation_deg) const;

  // The table behind operator() and its fade, for implementations that evaluate
  // the stretch elsewhere (the GPU precompute, render/lut/gpu_precompute.cpp).
  double ground_radius_m() const { return ground_radius_m_; }
  const DensityProfile& molecular_profile() const { return molecular_profile_; }
  const std::vector<double>& cos_zenith_table() const { return cos_zenith_; }  ///< abscissae μ_i = t_i², t uniform
  const std::vector<double>& stretch_table() const { return stretch_; }        ///< s at each abscissa

 private:
  /// Linear interpolation of a per-abscissa table at cos(zenith) at the ground.
  double interpolate(const std::vector<double>& values, double cos_zenith) const;
  double ground_radius_m_ = 0.0;
  DensityProfile molecular_profile_;
  std::vector<double> cos_zenith_;  // table abscissae in [0, 1]
  std::vector<double> stretch_;     // s at each abscissa
  std::vector<double> geometric_;   // X_geometric at each abscissa
};

}  // namespace zenith::atmosphere
