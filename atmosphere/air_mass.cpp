#include "atmosphere/air_mass.h"

#include <algorithm>
#include <cmath>

#include "atmosphere/constants.h"

namespace zenith::atmosphere {

double pickering_air_mass(double apparent_altitude_deg) {
  const double h = std::clamp(apparent_altitude_deg, 0.0, 90.0);
  const double arg_deg = h + 244.0 / (165.0 + 47.0 * std::pow(h, 1.1));
  return 1.0 / std::sin(arg_deg * kPi / 180.0);
}

namespace {

/// Straight-ray column ∫ρ ds from radius R (the ground) with cosine μ of the
/// zenith angle up to radius `top`, by Gauss–Legendre quadrature on the
/// substitution s = L u², which concentrates nodes near the ground where the
/// density is largest. Returns the column in metres of reference-density gas.
double slant_column(double R, double top, double mu, const DensityProfile& profile) {
  // Distance to the top sphere along the ray.
  const double L = -R * mu + std::sqrt(std::max(0.0, top * top - R * R * (1.0 - mu * mu)));
  static constexpr int kPanels = 64;
  static constexpr double kNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                       0.8611363115940526};
  static constexpr double kWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                         0.3478548451374538};
  double sum = 0.0;
  for (int p = 0; p < kPanels; ++p) {
    const double u0 = double(p) / kPanels, u1 = double(p + 1) / kPanels;
    for (int k = 0; k < 4; ++k) {
      const double u = 0.5 * (u0 + u1) + 0.5 * (u1 - u0) * kNodes[k];
      const double s = L * u * u;
      const double r = std::sqrt(R * R + s * s + 2.0 * R * s * mu);
      sum += kWeights[k] * 0.5 * (u1 - u0) * profile(r - R) * 2.0 * L * u;
    }
  }
  return sum;
}

}  // namespace

AirMassStretch AirMassStretch::pickering(double ground_radius_m, double top_radius_m,
                                         const DensityProfile& molecular_profile) {
  AirMassStretch a;
  a.ground_radius_m_ = ground_radius_m;
  a.molecular_profile_ = molecular_profile;
  const double vertical = molecular_profile.column_m(0.0, top_radius_m - ground_radius_m);
  // Abscissae in cos(zenith) = sin(elevation), quadratically spaced: the air mass
  // changes fastest near the horizon.
  static constexpr int kSamples = 257;
  for (int i = 0; i < kSamples; ++i) {
    const double t = double(i) / (kSamples - 1);
    const double mu = t * t;
    const double elevation_deg = std::asin(mu) * 180.0 / kPi;
    const double geometric = slant_column(ground_radius_m, top_radius_m, mu, molecular_profile) / vertical;
    a.cos_zenith_.push_back(mu);
    a.geometric_.push_back(geometric);
    a.stretch_.push_back(std::max(1.0, pickering_air_mass(elevation_deg) / geometric));
  }
  return a;
}

double AirMassStretch::interpolate(const std::vector<double>& values, double cos_zenith) const {
  const double mu = std::clamp(cos_zenith, 0.0, 1.0);
  // Table abscissae are μ_i = t_i², so t = √μ indexes it uniformly.
  const double x = std::sqrt(mu) * double(cos_zenith_.size() - 1);
  const std::size_t i = std::min(std::size_t(x), cos_zenith_.size() - 2);
  const double f = (mu - cos_zenith_[i]) / (cos_zenith_[i + 1] - cos_zenith_[i]);
  return values[i] + f * (values[i + 1] - values[i]);
}

double AirMassStretch::operator()(double r_m, double mu) const {
  if (!enabled()) return 1.0;
  const double R = ground_radius_m_;
  const double p = r_m * std::sqrt(std::max(0.0, 1.0 - mu * mu));  // impact parameter, constant along the ray
  if (p < R) return interpolate(stretch_, std::sqrt(1.0 - (p / R) * (p / R)));
  return 1.0 + (stretch_.front() - 1.0) * molecular_profile_(p - R);
}

double AirMassStretch::min_stretch() const {
  return enabled() ? *std::min_element(stretch_.begin(), stretch_.end()) : 1.0;
}

double AirMassStretch::max_stretch() const {
  return enabled() ? *std::max_element(stretch_.begin(), stretch_.end()) : 1.0;
}

double AirMassStretch::geometric_air_mass(double elevation_deg) const {
  return interpolate(geometric_, std::sin(std::clamp(elevation_deg, 0.0, 90.0) * kPi / 180.0));
}

}  // namespace zenith::atmosphere
