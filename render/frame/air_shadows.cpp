#include "render/frame/air_shadows.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>

#include "atmosphere/model_hash.h"
#include "atmosphere/solar_limb_darkening.h"
#include "render/frame/frame_in_progress.h"

namespace zenith::render {

void AirShadows::update(const scene::Scene& scene) {
  shadows_.clear();
  std::vector<Built> kept;
  const glm::dvec3 axis = -glm::normalize(scene.sun.direction);  // away from the Sun
  const double sun_radius = scene.sun.angular_radius_rad;
  for (std::size_t o = 0; o < scene.bodies.size(); ++o) {
    const scene::Body& occluder = scene.bodies[o];
    if (!occluder.atmosphere || occluder.atmosphere->loaded.model.wavelengths_nm != scene.wavelengths_nm) continue;
    const atmosphere::LoadedAtmosphere& air = occluder.atmosphere->loaded;
    for (std::size_t r = 0; r < scene.bodies.size(); ++r) {
      if (r == o) continue;
      const scene::Body& receiver = scene.bodies[r];
      const glm::dvec3 from_occluder = receiver.position_m - occluder.position_m;
      const double along = glm::dot(from_occluder, axis);
      if (!(along >= 10.0 * air.model.top_radius_m)) continue;  // EarthShadow's range; nearer, the solid shadow
      const double across = glm::length(from_occluder - along * axis);
      const double reach = air.model.top_radius_m + along * std::tan(sun_radius);
      if (across - receiver.radius_m >= reach) continue;
      if (shadows_.size() == kMaxAirShadows) {
        if (!warned_)
          spdlog::warn("more than {} shadows through the air: {}'s on {} is drawn as the solid body's", kMaxAirShadows,
                       occluder.name, receiver.name);
        warned_ = true;
        continue;
      }

      const std::string key = atmosphere::lookup_table_hash(air.model);
      Built built;
      for (Built& b : built_)
        if (b.occluder == o && b.receiver == r && b.atmosphere == key && b.shadow &&
            std::abs(along / b.distance_m - 1.0) <= 1e-3 && std::abs(sun_radius / b.sun_radius_rad - 1.0) <= 1e-3)
          built = std::move(b);
      if (!built.shadow) {
        const auto start = std::chrono::steady_clock::now();
        built.occluder = o;
        built.receiver = r;
        built.atmosphere = key;
        built.distance_m = along;
        built.sun_radius_rad = sun_radius;
        built.shadow = std::make_unique<astro::EarthShadow>(air, along, sun_radius,
                                                            atmosphere::solar_limb_darkening(scene.wavelengths_nm));
        spdlog::info("the shadow of {}'s air on {} built in {:.2f} s", occluder.name, receiver.name,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
      AirShadow shadow;
      shadow.occluder = o;
      shadow.receiver = r;
      shadow.reach_m = air.model.top_radius_m + built.distance_m * std::tan(built.sun_radius_rad);  // the table's
      shadow.light_left.resize(kAirShadowEntries);
      for (std::size_t k = 0; k < kAirShadowEntries; ++k) {
        const double y = shadow.reach_m * static_cast<double>(k) / static_cast<double>(kAirShadowEntries - 1);
        for (std::size_t i = 0; i < scene.wavelengths_nm.size(); ++i)
          shadow.light_left[k].push_back(built.shadow->illumination(y, i));
      }
      shadows_.push_back(std::move(shadow));
      kept.push_back(std::move(built));
    }
  }
  built_ = std::move(kept);
}

std::size_t air_shadow_values_per_entry(const FrameConstants& frame) { return 3 + frame.groups; }

std::vector<std::array<float, 4>> air_shadow_buffer(const std::vector<AirShadow>& shadows, const FrameConstants& frame,
                                                    const scene::Scene& scene) {
  if (shadows.empty()) return {{0.0f, 0.0f, 0.0f, 0.0f}};
  std::vector<std::array<float, 4>> out;
  out.reserve(shadows.size() * kAirShadowEntries * air_shadow_values_per_entry(frame));
  for (const AirShadow& shadow : shadows)
    for (const std::vector<double>& left : shadow.light_left) {
      const std::array<float, 9> m = direct_light_colour_matrix(frame, scene, left);
      for (std::size_t column = 0; column < 3; ++column)
        out.push_back({m[column * 3], m[column * 3 + 1], m[column * 3 + 2], 0.0f});
      for (std::size_t g = 0; g < frame.groups; ++g) out.push_back(group_lanes(left, g));
    }
  return out;
}

}  // namespace zenith::render
