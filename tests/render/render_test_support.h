#pragma once
// Helpers of the renderer tests (renderer_test.cpp, blend_reconstruction_test.cpp):
// the headless GL context they render on and a camera orientation from a view
// direction.
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "render/gl/egl_context.h"

namespace zenith::render::testing {

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

}  // namespace zenith::render::testing
