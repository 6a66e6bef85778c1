#include "scene/scene.h"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::scene {
namespace {

using core::kPi;
constexpr double kUnitTolerance = 1e-9;
constexpr double kMinCameraClearance_m = 0.1;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool unit(const glm::dquat& q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return std::isfinite(n) && std::abs(n - 1.0) <= kUnitTolerance;
}

[[noreturn]] void fail(std::ostream& message) {
  throw std::invalid_argument("scene: " + static_cast<std::ostringstream&>(message).str());
}

}  // namespace

const Body* Scene::find_body(const std::string& body_name) const {
  for (const Body& b : bodies)
    if (b.name == body_name) return &b;
  return nullptr;
}

glm::dvec3 direction_from_latitude_longitude(double latitude_rad, double longitude_rad) {
  const double c = std::cos(latitude_rad);
  return {c * std::cos(longitude_rad), c * std::sin(longitude_rad), std::sin(latitude_rad)};
}

void check_scene(const Scene& scene) {
  std::ostringstream s;
  if (scene.wavelengths_nm.empty()) fail(s << "no wavelengths");
  for (double wl : scene.wavelengths_nm)
    if (!(wl > 0.0 && std::isfinite(wl))) fail(s << "wavelength " << wl << " nm must be finite and > 0");

  std::set<std::string> names;
  int with_atmosphere = 0;
  for (const Body& b : scene.bodies) {
    if (b.name.empty()) fail(s << "a body has an empty name");
    if (!names.insert(b.name).second) fail(s << "two bodies are named \"" << b.name << "\"");
    if (!(b.radius_m > 0.0 && std::isfinite(b.radius_m)))
      fail(s << "body \"" << b.name << "\": radius " << b.radius_m << " m must be finite and > 0");
    if (!finite(b.position_m)) fail(s << "body \"" << b.name << "\": position is not finite");
    if (!unit(b.orientation)) fail(s << "body \"" << b.name << "\": orientation is not a unit quaternion");
    if (b.atmosphere) {
      ++with_atmosphere;
      const auto& m = b.atmosphere->loaded.model;
      if (std::abs(m.ground_radius_m - b.radius_m) > 1.0)
        fail(s << "body \"" << b.name << "\": radius " << b.radius_m
               << " m differs from its atmosphere's ground radius " << m.ground_radius_m << " m by more than 1 m");
      if (m.wavelengths_nm != scene.wavelengths_nm)
        fail(s << "body \"" << b.name << "\": its atmosphere is resolved at other wavelengths than the scene's");
    }
  }
  if (with_atmosphere > 8) fail(s << with_atmosphere << " bodies have an atmosphere; at most 8 may");
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    for (std::size_t j = i + 1; j < scene.bodies.size(); ++j) {
      const Body &a = scene.bodies[i], &b = scene.bodies[j];
      if (glm::length(a.position_m - b.position_m) <= a.radius_m + b.radius_m)
        fail(s << "bodies \"" << a.name << "\" and \"" << b.name << "\" intersect");
    }

  const Sun& sun = scene.sun;
  if (!finite(sun.direction) || std::abs(glm::length(sun.direction) - 1.0) > kUnitTolerance)
    fail(s << "the sun direction is not a unit vector");
  if (!(sun.angular_radius_rad > 0.0 && sun.angular_radius_rad <= 15.0 * kPi / 180.0))
    fail(s << "the sun's angular radius " << sun.angular_radius_rad << " rad must be in (0, 15 deg]");
  if (sun.irradiance_W_m2_nm.size() != scene.wavelengths_nm.size())
    fail(s << "the sun has " << sun.irradiance_W_m2_nm.size() << " irradiance values for "
           << scene.wavelengths_nm.size() << " wavelengths");
  for (double e : sun.irradiance_W_m2_nm)
    if (!(e >= 0.0 && std::isfinite(e))) fail(s << "the sun's irradiance " << e << " must be finite and >= 0");

  const Camera& camera = scene.camera;
  if (!finite(camera.position_m)) fail(s << "the camera position is not finite");
  if (!unit(camera.orientation)) fail(s << "the camera orientation is not a unit quaternion");
  if (!(camera.exposure > 0.0 && camera.exposure <= 1e6))
    fail(s << "exposure " << camera.exposure << " must be in (0, 1e6]");
  for (const Body& b : scene.bodies) {
    // Allow for rounding of positions far from the origin (1 ulp at 40 AU is ~1 mm).
    const double slack_m = 1e-6 + 1e-15 * (glm::length(camera.position_m) + glm::length(b.position_m) + b.radius_m);
    if (glm::length(camera.position_m - b.position_m) - b.radius_m < kMinCameraClearance_m - slack_m)
      fail(s << "the camera is less than " << kMinCameraClearance_m << " m above (or inside) body \"" << b.name
             << "\"");
  }
}

}  // namespace zenith::scene
