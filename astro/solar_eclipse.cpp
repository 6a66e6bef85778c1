#include "astro/solar_eclipse.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/strings.h"
#include "core/units.h"

namespace zenith::astro {

using core::kPi;

const char* to_string(EclipseKind kind) {
  switch (kind) {
    case EclipseKind::none: return "none";
    case EclipseKind::partial: return "partial";
    case EclipseKind::annular: return "annular";
    case EclipseKind::total: return "total";
  }
  return "none";
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
