#include "render/night/moon_in_shadow.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>

#include "astro/sky_positions.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/solar_limb_darkening.h"
#include "scene/local_horizon.h"

namespace zenith::render {

double MoonInShadow::moon_radius_m() const { return astro::kMoonRadius_km * 1e3; }

void MoonInShadow::update(const scene::Scene& scene, const FrameSky& sky) {
  shadowed_ = false;
  face_.assign(scene.wavelengths_nm.size(), 1.0);
  if (!scene.sky_clock) return;
  const scene::SkyClock& clock = *scene.sky_clock;
  const scene::Body& planet = scene.bodies.at(clock.body);
  if (!planet.atmosphere) return;
  // The Moon's centre from the planet's centre: the camera's place plus the
  // topocentric, geometric Moon (ERFA), in the world frame; the axis away from the Sun.
  const astro::MoonPlace moon = sky.positions().moon();
  const scene::LocalHorizon horizon = scene::local_horizon_at(scene.camera.position_m, planet);
  const glm::dvec3 toward_moon =
      glm::normalize(horizon.direction(moon.horizontal.azimuth_rad, moon.horizontal.altitude_rad));
  moon_centre_m_ = scene.camera.position_m - planet.position_m + toward_moon * (moon.distance_km * 1e3);
  axis_ = -glm::normalize(scene.sun.direction);
  const double along = glm::dot(moon_centre_m_, axis_);
  const double across = glm::length(moon_centre_m_ - along * axis_);
  const atmosphere::LoadedAtmosphere& air = planet.atmosphere->loaded;
  reach_m_ = air.model.top_radius_m + along * std::tan(scene.sun.angular_radius_rad);
  if (!(along > 0.0) || across - moon_radius_m() >= reach_m_) return;
  if (air.model.wavelengths_nm != scene.wavelengths_nm) return;  // the renderer refuses such scenes anyway
  const std::string key = atmosphere::lookup_table_hash(air.model);
  if (!shadow_ || key != shadow_atmosphere_ || std::abs(along / shadow_distance_m_ - 1.0) > 1e-3 ||
      std::abs(scene.sun.angular_radius_rad / shadow_sun_radius_rad_ - 1.0) > 1e-3) {
    const auto start = std::chrono::steady_clock::now();
    shadow_ = std::make_unique<astro::EarthShadow>(air, along, scene.sun.angular_radius_rad,
                                                   atmosphere::solar_limb_darkening(scene.wavelengths_nm));
    shadow_atmosphere_ = key;
    shadow_distance_m_ = along;
    shadow_sun_radius_rad_ = scene.sun.angular_radius_rad;
    spdlog::info("the Earth's shadow on the Moon built in {:.2f} s",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  shadowed_ = true;
  for (std::size_t i = 0; i < face_.size(); ++i) face_[i] = shadow_->disc_illumination(across, moon_radius_m(), i);
}

double MoonInShadow::illumination(double axis_distance_m, std::size_t i) const {
  if (!shadowed_ || axis_distance_m >= reach_m_) return 1.0;
  return shadow_->illumination(axis_distance_m, i);
}

}  // namespace zenith::render
