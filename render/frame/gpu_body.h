#pragma once
// The frame's bodies as the render passes read them: shaders/render/body.glsl's
// Body, one element of frame.glsl's Bodies buffer (std430, BODIES_BINDING).
// tests/render/shader_interface_test.cpp writes a distinct value into every
// float of a GpuBody, reads each Body field back on the GPU and checks that it
// lands on this struct's field of the same name: a reordering fails naming it.
#include <array>

namespace zenith::render {

/// render/body.glsl's Body, std430 layout (six vec4, no padding).
struct GpuBody {
  using Vec4 = std::array<float, 4>;
  Vec4 centre;            ///< direction camera → centre, distance [m]
  Vec4 shape;             ///< R [m], |c|² − R² [m²], atmosphere slot, albedo layer
  Vec4 albedo_map;        ///< width of the albedo maps' level 0 [texels], unused ×3
  Vec4 world_to_body[3];  ///< rows of the rotation world → body frame (world_to_body0..2)
};
static_assert(sizeof(GpuBody) == 6 * 16);

}  // namespace zenith::render
