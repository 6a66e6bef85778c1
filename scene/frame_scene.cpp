#include "scene/frame_scene.h"

#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/strings.h"
#include "core/units.h"

namespace zenith::scene {
namespace {

/// The polar axis of the body nearest the camera, or world +z.
glm::dvec3 sun_axis(const Scene& scene) {
  const Body* nearest = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const Body& body : scene.bodies) {
    const double altitude = glm::length(scene.camera.position_m - body.position_m) - body.radius_m;
    if (altitude < best) {
      best = altitude;
      nearest = &body;
    }
  }
  return nearest != nullptr ? glm::normalize(nearest->orientation * glm::dvec3(0.0, 0.0, 1.0)) : glm::dvec3(0, 0, 1);
}

}  // namespace

FrameDescription default_show_frame(const Scene& scene, std::uint64_t frame, double sun_step_deg,
                                    const std::vector<AtmosphereTableRef>& atmospheres, std::uint32_t render_flags) {
  FrameDescription s;
  s.frame = frame;
  s.show_time_s = 0.0;
  s.camera_position_m = scene.camera.position_m;
  s.camera_orientation = scene.camera.orientation;
  s.exposure = scene.camera.exposure;
  // Negative: westward, as the day advances on a prograde-rotating body.
  const double angle_rad = -static_cast<double>(frame) * sun_step_deg * core::kPi / 180.0;
  // Frame 0 (and every frame of a still sun) is the scene exactly as configured.
  s.sun_direction = frame == 0 || sun_step_deg == 0.0
                        ? scene.sun.direction
                        : glm::normalize(glm::angleAxis(angle_rad, sun_axis(scene)) * scene.sun.direction);
  s.sun_angular_radius_rad = scene.sun.angular_radius_rad;
  s.sun_irradiance_W_m2_nm = scene.sun.irradiance_W_m2_nm;
  s.atmospheres = atmospheres;
  s.render_flags = render_flags;
  if (scene.sky_clock) s.sky = sky_frame(astro::AstroTime::from_utc(scene.sky_clock->time));
  return s;
}

SkyFrame sky_frame(const astro::AstroTime& time, const core::Sha256Digest& star_catalogue) {
  SkyFrame sky;
  sky.has_time = true;
  sky.utc_jd1 = time.utc().day1;
  sky.utc_jd2 = time.utc().day2;
  sky.star_catalogue = star_catalogue;
  return sky;
}

void check_frame(const FrameDescription& frame, const Scene& scene) {
  if (frame.sun_irradiance_W_m2_nm.size() != scene.wavelengths_nm.size())
    throw std::invalid_argument(core::cat("apply_state: ", frame.sun_irradiance_W_m2_nm.size(),
                                          " sun irradiance values for a scene of ", scene.wavelengths_nm.size(),
                                          " wavelengths (do master and node read the same scene?)"));
}

void apply_frame(const FrameDescription& frame, Scene& scene) {
  check_frame(frame, scene);
  scene.camera.position_m = frame.camera_position_m;
  scene.camera.orientation = frame.camera_orientation;
  scene.camera.exposure = frame.exposure;
  scene.sun.direction = frame.sun_direction;
  scene.sun.angular_radius_rad = frame.sun_angular_radius_rad;
  scene.sun.irradiance_W_m2_nm = frame.sun_irradiance_W_m2_nm;
  // The sky clock's instant (the stars, the Moon): the scene's own time otherwise.
  if (frame.sky.has_time && scene.sky_clock)
    scene.sky_clock->time =
        astro::AstroTime::from_utc_julian(astro::JulianDate{frame.sky.utc_jd1, frame.sky.utc_jd2}).calendar_utc();
}

}  // namespace zenith::scene
