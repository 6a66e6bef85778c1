#pragma once
// `--moving` of the frame benchmarks (render_bench, render_bench --present):
// frames of a camera that moves, as in a show, instead of a still scene.
#include <glm/gtc/quaternion.hpp>

#include "scene/scene.h"

namespace zenith::bench {

/// Sets `s`'s camera to `still` turned about its up axis by +1 µrad on odd
/// frames and −1 µrad on even ones: consecutive frames never share their
/// inputs, so nothing the renderer keeps from a frame of a still scene (the
/// tile classification, render/frame/frame_tiles.h) is reused, while the
/// pixels move by a thousandth of a pixel at 8K.
inline void turn_camera(scene::Scene& s, const glm::dquat& still, int frame) {
  s.camera.orientation = glm::normalize(still * glm::angleAxis(frame % 2 != 0 ? 1e-6 : -1e-6, glm::dvec3(0, 1, 0)));
}

}  // namespace zenith::bench
