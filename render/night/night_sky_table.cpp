#include "render/night/night_sky_table.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::render {

NightSkyTable night_sky_table(const StarAtmosphere& atmosphere, const glm::dvec3& camera_m,
                              const astro::NightSkyFloor* floor, const astro::LightPollution* glow,
                              const std::vector<std::array<double, 3>>& rgb_weights, double exposure, int entries) {
  NightSkyTable table;
  const glm::dvec3 p = camera_m - atmosphere.centre_m;
  const double r = glm::length(p);
  table.up = p / r;
  const double ratio = std::min(1.0, atmosphere.ground_radius_m / r);
  table.horizon_mu = -std::sqrt(std::max(0.0, 1.0 - ratio * ratio));
  // Any direction perpendicular to up: the table has no azimuth.
  const glm::dvec3 side = glm::normalize(std::abs(table.up.x) < 0.9 ? glm::cross(table.up, glm::dvec3(1, 0, 0))
                                                                    : glm::cross(table.up, glm::dvec3(0, 1, 0)));
  const std::size_t n = rgb_weights.size();
  std::vector<double> transmittance(n, 1.0);
  table.rgb.resize(static_cast<std::size_t>(entries));
  for (int j = 0; j < entries; ++j) {
    const double t = static_cast<double>(j) / (entries - 1);
    const double mu = std::clamp(table.horizon_mu + (1.0 - table.horizon_mu) * t * t, -1.0, 1.0);
    // Just above the horizon: a ray that grazes the ground still sees the sky.
    const double mu_ray = j == 0 ? table.horizon_mu + 1e-6 : mu;
    const glm::dvec3 d = glm::normalize(table.up * mu_ray + side * std::sqrt(std::max(0.0, 1.0 - mu_ray * mu_ray)));
    const double zenith_angle = std::acos(std::clamp(mu_ray, -1.0, 1.0));
    std::vector<double> radiance(n, 0.0);
    if (floor) {
      star_transmittance(atmosphere, camera_m, d, transmittance.data());
      radiance = floor->observed_radiance(std::min(zenith_angle, 0.5 * core::kPi), transmittance);
    }
    if (glow && glow->zenith_mcd_m2() > 0.0) {
      const std::vector<double> g = glow->radiance(zenith_angle);
      for (std::size_t k = 0; k < n; ++k) radiance[k] += g[k];
    }
    std::array<float, 4>& out = table.rgb[static_cast<std::size_t>(j)];
    out = {0, 0, 0, 0};
    for (std::size_t c = 0; c < 3; ++c) {
      double v = 0.0;
      for (std::size_t k = 0; k < n; ++k) v += rgb_weights[k][c] * radiance[k];
      out[c] = static_cast<float>(v * exposure);
      table.largest[c] = std::max(table.largest[c], std::abs(v * exposure));
    }
  }
  return table;
}

}  // namespace zenith::render
