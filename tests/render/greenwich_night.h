#pragma once
// The night-sky tests' scene and renderer (night_sky_test.cpp,
// moonlight_test.cpp): the Earth with the shared small tables, the sky clock
// at Greenwich, the camera 2 m up, and a renderer that reads those tables.
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "../atmosphere/lut_fixture.h"
#include "astro/sky_positions.h"
#include "atmosphere/model_hash.h"
#include "core/units.h"
#include "render/renderer.h"
#include "scene/local_horizon.h"
#include "tests/render/render_test_support.h"

namespace zenith::render::testing {

inline constexpr double kGreenwichLatitudeDeg = 51.4769, kGreenwichLongitudeDeg = -0.0005;

/// The Earth at the origin (with the preset's atmosphere, or none), the sky
/// clock at Greenwich on `time`, the camera 2 m up looking along `look_enu` (a
/// direction in the site's east-north-up frame), the sun below the ground.
inline scene::Scene greenwich(const std::string& preset, const glm::dvec3& look_enu, double exposure,
                              const astro::UtcTime& time) {
  scene::Scene s = one_planet_scene("night sky test", "Earth", "earth-advanced", preset);
  s.camera.position_m = scene::direction_from_latitude_longitude(kGreenwichLatitudeDeg * core::kDeg,
                                                                 kGreenwichLongitudeDeg * core::kDeg) *
                        (s.bodies[0].radius_m + 2.0);
  const scene::LocalHorizon h = scene::local_horizon_at(s.camera.position_m, s.bodies[0]);
  const glm::dvec3 forward = glm::normalize(look_enu.x * h.east + look_enu.y * h.north + look_enu.z * h.up);
  s.camera.orientation = look_rotation(forward, std::abs(look_enu.z) > 0.99 ? h.north : h.up);
  s.camera.exposure = exposure;
  s.sun.direction = -h.up;  // midnight
  s.sky_clock = scene::SkyClock{time, astro::Site{kGreenwichLatitudeDeg, kGreenwichLongitudeDeg, 46.0}, 0};
  return s;
}

/// A renderer reading the shared small tables of earth-advanced and Mars.
struct TestRenderer {
  Renderer renderer;
  explicit TestRenderer(const RenderOptions& o)
      : renderer((context(), o), [](const atmosphere::AtmosphereModel& model) {
          for (const char* preset : {"earth-advanced", "mars"}) {
            const atmosphere::lut::SmallTables& t = atmosphere::lut::SmallTables::get(preset);
            if (atmosphere::lookup_table_hash(t.model) == atmosphere::lookup_table_hash(model)) return t.tables;
          }
          throw std::runtime_error("no test tables for " + model.name);
        }) {}
};

}  // namespace zenith::render::testing
