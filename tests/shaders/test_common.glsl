// The analytic pattern of the GL smoke test (tests/render/gl_context_test.cpp
// computes the same values in C++). Included by test_pattern.comp.
//
// Variants (#define, injected after #version by ShaderProgram):
//   PATTERN_SCALE       factor on the normalized coordinates (default 1.0)
//   PATTERN_INDEX_TERM  0 drops the linear texel index from alpha (default 1)
#ifndef PATTERN_SCALE
#define PATTERN_SCALE 1.0
#endif
#ifndef PATTERN_INDEX_TERM
#define PATTERN_INDEX_TERM 1
#endif

// Texel p of a size.x × size.y × size.z grid: rgb = texel centre in [0, 1]^3
// times PATTERN_SCALE, a = linear index x + size.x·(y + size.y·z) (exact in float).
vec4 test_pattern(ivec3 p, ivec3 size) {
  vec3 uvw = (vec3(p) + 0.5) / vec3(size);
  float index = 0.0;
#if PATTERN_INDEX_TERM
  index = float(p.x + size.x * (p.y + size.y * p.z));
#endif
  return vec4(uvw * PATTERN_SCALE, index);
}
