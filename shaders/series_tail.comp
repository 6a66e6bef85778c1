#version 450 core
// The series tail of the radiance (atmosphere/lut/series_tail.h): every order
// after the last one computed, L_N · k / (1 − k) with k = L_N / L_{N−1} per
// texel and wavelength, capped at that wavelength's ratio_cap
// (series_tail_ratio_cap, from the orders' sums over the table: computed on
// the CPU), 0 where either order is not positive; added to the
// multiple-scattering table and written over the last order's delta (for the
// tail's share, radiance_sum.comp). For one group of 4 wavelengths, one r
// layer per dispatch (z_offset). The irradiance's tail is computed on the CPU
// (gpu_precompute.cpp).
layout(local_size_x = 8, local_size_y = 8) in;

#include "atmosphere_common.glsl"

layout(binding = OUTPUT_IMAGE, rgba32f) uniform image3D last_order_image;
layout(binding = SECOND_OUTPUT_IMAGE, rgba32f) uniform image3D sum_image;
layout(binding = DELTA_RADIANCE_UNIT) uniform sampler3D order_before_texture;
uniform vec4 ratio_cap;  // per wavelength of the group: series_tail_ratio_cap (< 1)

/// series_tail_factor (series_tail.h), per lane: k/(1 − k) with k = min(last/before_last, cap),
/// and 0 where either order is not positive (no light, or NaN). Written on whole vectors: NVIDIA
/// refuses a double vector written at a non-constant index (C9999 __setVectorIndex).
real4 series_tail_factor(real4 last, real4 before_last, real4 cap) {
  const bvec4 lit = bvec4(uvec4(greaterThan(last, real4(0))) & uvec4(greaterThan(before_last, real4(0))));
  const real4 k = min(last / mix(real4(1), before_last, lit), cap);
  return mix(real4(0), k / (real4(1) - k), lit);
}

void main() {
  const ivec3 p = ivec3(gl_GlobalInvocationID.xy, z_offset + int(gl_GlobalInvocationID.z));
  if (p.x >= SCATTERING_NU * SCATTERING_MU_S || p.y >= SCATTERING_MU || p.z >= SCATTERING_R) return;
  const real4 last = real4(imageLoad(last_order_image, p));
  const real4 before = real4(texelFetch(order_before_texture, p, 0));
  const real4 tail = series_tail_factor(last, before, real4(ratio_cap)) * last;
  // Rounded to float first, as the CPU does (series_tail.cpp), before the sum.
  const vec4 tail_f = vec4(tail);
  imageStore(sum_image, p, imageLoad(sum_image, p) + tail_f);
  imageStore(last_order_image, p, tail_f);
}
