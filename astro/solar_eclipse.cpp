#include "astro/solar_eclipse.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>

#include "atmosphere/lut/gauss_legendre.h"
#include "core/strings.h"
#include "core/units.h"

namespace zenith::astro {

using core::kPi;

const char* to_string(EclipseKind kind) {
  constexpr const char* kNames[] = {"none", "partial", "annular", "total"};  // in the enum's order
  return kNames[static_cast<int>(kind)];
}

double disc_obscuration(double d, double r_s, double r_m) {
  if (!(d >= 0.0 && std::isfinite(d) && r_s > 0.0 && std::isfinite(r_s) && r_m >= 0.0 && std::isfinite(r_m)))
    throw std::invalid_argument(core::cat("disc_obscuration: separation ", d, ", radii ", r_s, " and ", r_m,
                                          " must be finite, >= 0 (the sun's > 0)"));
  if (d >= r_s + r_m) return 0.0;
  if (d <= std::abs(r_s - r_m)) return std::min(1.0, (r_m * r_m) / (r_s * r_s));
  // The lens: each circle's segment beyond the chord through the two intersection points,
  // a segment of angle 2φ in a circle of radius r having area r² (φ − sin φ cos φ).
  const double phi_s = std::acos(std::clamp((d * d + r_s * r_s - r_m * r_m) / (2.0 * d * r_s), -1.0, 1.0));
  const double phi_m = std::acos(std::clamp((d * d + r_m * r_m - r_s * r_s) / (2.0 * d * r_m), -1.0, 1.0));
  const double lens =
      r_s * r_s * (phi_s - std::sin(phi_s) * std::cos(phi_s)) + r_m * r_m * (phi_m - std::sin(phi_m) * std::cos(phi_m));
  return std::clamp(lens / (kPi * r_s * r_s), 0.0, 1.0);
}

namespace {

/// The angle of the circle of radius ρ about the disc's centre that lies inside the occulter
/// (radius r_m, centre d away): 0, 2π, or twice the half-angle from the law of cosines.
double covered_angle(double rho, double d, double r_m) {
  if (rho + d <= r_m) return 2.0 * kPi;  // the whole ring inside
  if (rho >= d + r_m || rho <= d - r_m || rho == 0.0) return 0.0;
  return 2.0 * std::acos(std::clamp((rho * rho + d * d - r_m * r_m) / (2.0 * rho * d), -1.0, 1.0));
}

}  // namespace

double limb_darkened_obscuration(double d, double r_s, double r_m, const atmosphere::LimbDarkening& limb) {
  const double uniform = disc_obscuration(d, r_s, r_m);  // checks the geometry
  atmosphere::check_limb_darkening(limb, "limb_darkened_obscuration");
  if (uniform == 0.0 || uniform == 1.0 || limb == atmosphere::LimbDarkening{}) return uniform;  // none, total, uniform
  // In μ = sqrt(1 − ρ²/r_s²): ρ dρ = −r_s² μ dμ, so the covered share of the light is
  //   1/(π m) ∫_0^1 I(μ)/I(1) μ c(ρ(μ)) dμ,
  // integrated piecewise between the rings where c(ρ) starts or stops changing.
  static const atmosphere::lut::GaussLegendre rule(64);
  std::vector<double> breaks = {0.0, 1.0};
  for (double rho : {std::abs(d - r_m), d + r_m})
    if (rho > 0.0 && rho < r_s) breaks.push_back(std::sqrt(1.0 - (rho * rho) / (r_s * r_s)));
  std::sort(breaks.begin(), breaks.end());
  double covered = 0.0;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double lo = breaks[k], hi = breaks[k + 1], half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
      const double mu = mid + half * rule.nodes[i];
      const double rho = r_s * std::sqrt(std::max(0.0, 1.0 - mu * mu));
      covered += half * rule.weights[i] * limb.intensity(mu) * mu * covered_angle(rho, d, r_m);
    }
  }
  return std::clamp(covered / (kPi * limb.mean_over_centre()), 0.0, 1.0);
}

SunAndMoon sun_and_moon(const SkyPositions& sky, double observer_radius_m) {
  const SunPlace sun = sky.sun();
  const MoonPlace moon = sky.moon();
  const auto north_east_up = [](const glm::dvec3& enu) { return glm::dvec3{enu.y, enu.x, enu.z}; };
  SunAndMoon s;
  s.sun_zenith_deg = 90.0 - sun.horizontal.altitude_rad / core::kDeg;
  s.sun_azimuth_deg = sun.horizontal.azimuth_rad / core::kDeg;
  s.sun_angular_radius_rad = sun.angular_radius_rad;
  s.moon_centre_m =
      glm::dvec3{0.0, 0.0, observer_radius_m} + moon.distance_km * 1e3 * north_east_up(moon.horizontal.east_north_up());
  s.moon_radius_m = kMoonRadius_km * 1e3;
  return s;
}

SolarEclipseView solar_eclipse_view(const SkyPositions& sky) {
  const SunPlace sun = sky.sun();
  const MoonPlace moon = sky.moon();
  SolarEclipseView v;
  // atan2(|a × b|, a · b): accurate for the small angles that matter here.
  const glm::dvec3 a = sun.horizontal.east_north_up(), b = moon.horizontal.east_north_up();
  v.separation_rad = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
  v.sun_radius_rad = sun.angular_radius_rad;
  v.moon_radius_rad = moon.angular_radius_rad;
  const double d = v.separation_rad, r_s = v.sun_radius_rad, r_m = v.moon_radius_rad;
  v.obscuration = disc_obscuration(d, r_s, r_m);
  if (d >= r_s + r_m)
    v.kind = EclipseKind::none;
  else if (d <= r_m - r_s)
    v.kind = EclipseKind::total;
  else if (d <= r_s - r_m)
    v.kind = EclipseKind::annular;
  else
    v.kind = EclipseKind::partial;
  const bool central = v.kind == EclipseKind::total || v.kind == EclipseKind::annular;
  v.magnitude = central ? r_m / r_s : (r_s + r_m - d) / (2.0 * r_s);
  return v;
}

}  // namespace zenith::astro
