#include "cluster/frame_scene.h"

#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "show/show.h"
#include "core/units.h"

namespace zenith::cluster {
namespace {

/// The polar axis of the body nearest the camera, or world +z.
glm::dvec3 sun_axis(const scene::Scene& scene) {
  const scene::Body* nearest = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const scene::Body& body : scene.bodies) {
    const double altitude = glm::length(scene.camera.position_m - body.position_m) - body.radius_m;
    if (altitude < best) {
      best = altitude;
      nearest = &body;
    }
  }
  return nearest != nullptr ? glm::normalize(nearest->orientation * glm::dvec3(0.0, 0.0, 1.0)) : glm::dvec3(0, 0, 1);
}

}  // namespace

FrameState default_show_frame(const scene::Scene& scene, std::uint64_t frame, double sun_step_deg,
                              const std::vector<AtmosphereTableRef>& atmospheres, std::uint32_t render_flags) {
  FrameState s;
  s.frame = frame;
  s.show_time_s = 0.0;
  s.camera_position_m = scene.camera.position_m;
  s.camera_orientation = scene.camera.orientation;
  s.exposure = scene.camera.exposure;
  // Negative: westward, as the day advances on a prograde-rotating body.
  const double angle_rad = -static_cast<double>(frame) * sun_step_deg * core::kPi / 180.0;
  // Frame 0 (and every frame of a still sun) is the scene exactly as configured.
  s.sun_direction = frame == 0 || sun_step_deg == 0.0 ? scene.sun.direction
                               : glm::normalize(glm::angleAxis(angle_rad, sun_axis(scene)) * scene.sun.direction);
  s.sun_angular_radius_rad = scene.sun.angular_radius_rad;
  s.sun_irradiance_W_m2_nm = scene.sun.irradiance_W_m2_nm;
  s.atmospheres = atmospheres;
  s.render_flags = render_flags;
  return s;
}

void apply_frame_state(const FrameState& state, scene::Scene& scene) {
  // The per-frame parts are show::apply_state's without the atmospheres (those
  // the node replaces by table version itself).
  FrameState parts = state;
  parts.atmospheres.clear();
  show::apply_state(parts, {}, scene);
}

}  // namespace zenith::cluster
