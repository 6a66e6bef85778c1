#include "validate/stress_geometry.h"

#include <algorithm>
#include <cmath>

namespace zenith::validate {

double horizon_nadir_angle_rad(double r_m, double ground_radius_m) {
  // √((r − R)(r + R)): the distance to the horizon, free of the cancellation of r² − R².
  const double horizon_distance_m = std::sqrt(std::max(0.0, (r_m - ground_radius_m) * (r_m + ground_radius_m)));
  return std::atan2(ground_radius_m, horizon_distance_m);
}

Vec3 direction_at_nadir_angle(const Vec3& up, const Vec3& tangent, double nadir_angle_rad) {
  return -std::cos(nadir_angle_rad) * up + std::sin(nadir_angle_rad) * tangent;
}

Vec3 horizon_direction(const Vec3& camera_m, const Vec3& tangent, double ground_radius_m, double offset_rad) {
  const double r = atmosphere::length(camera_m);
  return direction_at_nadir_angle(camera_m / r, tangent, horizon_nadir_angle_rad(r, ground_radius_m) + offset_rad);
}

double offset_from_horizon_rad(const Vec3& camera_m, const Vec3& view, double ground_radius_m) {
  const double r = atmosphere::length(camera_m);
  const Vec3 up = camera_m / r;
  // atan2 of sine and cosine: accurate for nadir angles near 0 (40 au) and near π/2 (1 m).
  const double nadir_angle = std::atan2(atmosphere::length(atmosphere::cross(up, view)), -atmosphere::dot(up, view));
  return nadir_angle - horizon_nadir_angle_rad(r, ground_radius_m);
}

Vec3 tangent_at_azimuth(const Vec3& up, double azimuth_rad) {
  // Gram–Schmidt from the axis least aligned with `up`.
  const Vec3 axis = std::abs(up.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  const Vec3 e1 = atmosphere::normalize(axis - atmosphere::dot(axis, up) * up);
  const Vec3 e2 = atmosphere::cross(up, e1);
  return std::cos(azimuth_rad) * e1 + std::sin(azimuth_rad) * e2;
}

std::string_view region_name(Region region) {
  switch (region) {
    case Region::space: return "space";
    case Region::night: return "night";
    case Region::twilight: return "twilight";
    case Region::horizon: return "horizon";
    case Region::ground: return "ground";
    case Region::sky: return "sky";
  }
  return "?";
}

Region classify(const Configuration& c, double ground_radius_m, double top_radius_m) {
  const double r = atmosphere::length(c.camera_m);
  if (r > top_radius_m) return Region::space;
  const double cos_sun_zenith = atmosphere::dot(c.camera_m, c.sun) / r;
  if (cos_sun_zenith < std::cos(kTwilightEndZenith_rad)) return Region::night;
  if (cos_sun_zenith < 0.0) return Region::twilight;
  const double offset = offset_from_horizon_rad(c.camera_m, c.view, ground_radius_m);
  if (std::abs(offset) < kHorizonBandHalfWidth_rad) return Region::horizon;
  return offset < 0.0 ? Region::ground : Region::sky;
}

}  // namespace zenith::validate
