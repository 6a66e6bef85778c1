#version 450
// The band's output zeroed on the listed tiles (render/renderer.cpp): the
// one-pass tiles the sun's pass leaves black when its light cannot move a
// display value (render/frame/sun_light.h), before the Moon's light, the
// night floor and the stars add to them. A GPU driver's buffer clear need
// not run as fast as a pass: NVIDIA's of a 2048² band took 2.9 ms on an H200
// where the pass storing every pixel of its sky took 0.1 ms, and four dome
// nodes sharing that GPU doubled their frame time from the frame the clear
// began (docs/gpu-precompute.md, "The second H200 session"). A CPU
// rasterizer (llvmpipe) keeps the buffer clear, a memset there, where this
// pass's stores run lane by lane (7.3 ms on a 1280x720 night frame).

#include "frame.glsl"
#include "frame_rgb.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

void main() {
  ivec2 p;
  if (tile_pixel(p)) store_frame_rgb(p, vec3(0.0));
}
