#version 450 core
// Every field of render/body.glsl's Body, read from a Bodies buffer that the
// C++ side filled through render/frame/gpu_body.h's GpuBody, written out in
// declaration order (tests/render/shader_interface_test.cpp): field k of body b
// at fields[b · 6 + k].
layout(local_size_x = 1) in;

#include "render/body.glsl"

layout(std430, binding = BODIES_BINDING) readonly buffer Bodies { Body bodies[]; };
/// The test's output (FIELDS_BINDING, defined by the test).
layout(std430, binding = FIELDS_BINDING) writeonly buffer Fields { vec4 fields[]; };
uniform int body_count;

void main() {
  for (int b = 0; b < body_count; ++b) {
    fields[b * 6 + 0] = bodies[b].centre;
    fields[b * 6 + 1] = bodies[b].shape;
    fields[b * 6 + 2] = bodies[b].albedo_map;
    fields[b * 6 + 3] = bodies[b].world_to_body0;
    fields[b * 6 + 4] = bodies[b].world_to_body1;
    fields[b * 6 + 5] = bodies[b].world_to_body2;
  }
}
