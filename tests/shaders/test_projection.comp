#version 450 core
// Test of projection.glsl (tests/render/projection_gpu_test.cpp): writes the ray
// of every pixel centre into an RGBA32F 2D image, rgb = the camera-frame
// direction, a = 1 where the pixel has a ray and 0 where it has none.
layout(local_size_x = 8, local_size_y = 8) in;

#include "projection.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image2D ray_image;

void main() {
  ivec2 size = imageSize(ray_image);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec3 direction;
  bool valid = projection_ray(vec2(p) + 0.5, direction);
  imageStore(ray_image, p, vec4(direction, valid ? 1.0 : 0.0));
}
