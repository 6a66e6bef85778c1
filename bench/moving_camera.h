#pragma once
// `--moving` of the frame benchmarks (render_bench, render_bench --present):
// frames of a camera and a sun that move, as in a show, instead of a still scene.
#include <glm/gtc/quaternion.hpp>

#include "scene/scene.h"

namespace zenith::bench {

/// Sets `s`'s camera to `still`'s turned about its up axis, and its sun to
/// `still`'s turned about the camera's right axis, by +1 µrad on odd frames
/// and −1 µrad on even ones: consecutive frames never share their inputs, so
/// nothing the renderer keeps from a frame of a still scene (the tile
/// classification, render/frame/frame_tiles.h; the sky-view tables,
/// render/frame/sky_view_table.h) is reused, as in a show whose camera and
/// clock run, while the pixels move by a thousandth of a pixel at 8K.
inline void move_camera_and_sun(scene::Scene& s, const scene::Scene& still, int frame) {
  const double angle_rad = frame % 2 != 0 ? 1e-6 : -1e-6;
  s.camera.orientation = glm::normalize(still.camera.orientation * glm::angleAxis(angle_rad, glm::dvec3(0, 1, 0)));
  const glm::dvec3 right = still.camera.orientation * glm::dvec3(1, 0, 0);
  s.sun.direction = glm::normalize(glm::angleAxis(angle_rad, right) * still.sun.direction);
}

}  // namespace zenith::bench
