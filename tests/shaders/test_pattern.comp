#version 450 core
// Smoke test of the compute path: writes test_pattern() (test_common.glsl) into
// every texel of an RGBA32F 3D image. Work groups of 4×4×2; invocations outside
// the image return.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 2) in;

#include "test_common.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image3D pattern_image;

void main() {
  ivec3 size = imageSize(pattern_image);
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(p, size))) return;
  imageStore(pattern_image, p, test_pattern(p, size));
}
