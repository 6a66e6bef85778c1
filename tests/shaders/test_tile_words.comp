#version 450 core
// render/frame.glsl's tile_pixel() on tile words the C++ side packed
// (render/frame/tile_culling.h's pack_tile; tests/render/shader_interface_test.cpp):
// one work group per listed tile, as in the render passes; each invocation
// writes its band pixel and whether tile_pixel() found it inside the band,
// at pixels[tile · TILE_SIZE² + local index].
layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

#include "render/frame.glsl"

/// The test's output (PIXELS_BINDING, defined by the test).
layout(std430, binding = PIXELS_BINDING) writeonly buffer Pixels { ivec4 pixels[]; };

void main() {
  ivec2 p;
  const bool inside = tile_pixel(p);
  const uint tile = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  pixels[tile * uint(TILE_SIZE * TILE_SIZE) + gl_LocalInvocationIndex] = ivec4(p, inside ? 1 : 0, 0);
}
