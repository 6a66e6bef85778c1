#pragma once
// Helpers of the renderer tests (renderer_test.cpp, blend_reconstruction_test.cpp,
// night_sky_test.cpp): the headless GL context they render on, a camera
// orientation from a view direction, and the one-planet scene they start from.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "../atmosphere/lut_fixture.h"
#include "atmosphere/parameters.h"
#include "atmosphere/photometry.h"
#include "render/gl/egl_context.h"
#include "scene/scene.h"

namespace zenith::render::testing {

/// An RGBA frame of exposed radiance for the output-stage tests: along the
/// frame (row after row) each channel grows geometrically from `lowest` by a
/// factor `span`, the channels offset by 0.31 of the range; alpha 1.
inline std::vector<float> geometric_radiance(int width, int height, double lowest, double span) {
  std::vector<float> rgba(static_cast<std::size_t>(width) * height * 4, 1.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 4;
      const double t = (y * width + x) / double(width * height - 1);
      for (int c = 0; c < 3; ++c)
        rgba[i + c] = static_cast<float>(lowest * std::pow(span, std::fmod(t + 0.31 * c, 1.0)));
    }
  return rgba;
}

/// The headless EGL context of the test program (created on first use), made current.
inline gl::HeadlessContext& context() {
  static gl::HeadlessContext c;
  c.make_current();
  return c;
}

/// Camera frame (+x right, +y up, −z forward) → world, for a camera looking
/// along `forward` with `up` above.
inline glm::dquat look_rotation(const glm::dvec3& forward, const glm::dvec3& up) {
  const glm::dvec3 z = -glm::normalize(forward);
  const glm::dvec3 x = glm::normalize(glm::cross(up, z));
  const glm::dvec3 y = glm::cross(z, x);
  return glm::quat_cast(glm::dmat3(x, y, z));
}

/// A scene of one planet centred at the origin: `body_name`, of the ground
/// radius of `tables_preset`'s small tables (atmosphere::lut::SmallTables), at
/// their wavelengths, albedo 0.1 grey, with `preset`'s atmosphere ("" for
/// none); the sun's spectrum at those wavelengths (solar_irradiance_W_m2_nm),
/// its angular radius 4.65e-3 rad. The caller places the camera and the sun.
inline scene::Scene one_planet_scene(const std::string& scene_name, const std::string& body_name,
                                     const std::string& tables_preset, const std::string& preset) {
  const atmosphere::lut::SmallTables& t = atmosphere::lut::SmallTables::get(tables_preset);
  scene::Scene s;
  s.name = scene_name;
  s.wavelengths_nm = t.model.wavelengths_nm;
  scene::Body planet;
  planet.name = body_name;
  planet.radius_m = t.model.ground_radius_m;
  planet.albedo.colour_linear_rgb = {0.1, 0.1, 0.1};
  if (!preset.empty()) planet.atmosphere = scene::BodyAtmosphere{"preset:" + preset, atmosphere::load_preset(preset)};
  s.bodies.push_back(planet);
  s.sun.angular_radius_rad = 4.65e-3;
  for (double w : s.wavelengths_nm) s.sun.irradiance_W_m2_nm.push_back(atmosphere::solar_irradiance_W_m2_nm(w));
  return s;
}

}  // namespace zenith::render::testing
