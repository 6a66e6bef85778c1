#version 450 core
// Per-row sums of in-scattered radiance of each of one group's wavelengths,
// for the share of each scattering order (PrecomputeReport::order_fraction),
// the tolerance stop and the series tail's caps (series_tail.h): one
// invocation per (μ, r) row of the scattering tables.
//   SINGLE 1: single scattering with its phase functions (total_radiance_sum);
//   SINGLE 0: the radiance of the last order (delta_radiance_texture).
// row_sums[(wavelength_group · rows + row) · 4 + lane]; `lanes`: wavelengths in
// this group (the others' sums are 0).
layout(local_size_x = 64) in;

#include "atmosphere_common.glsl"

layout(std430, binding = ROW_SUMS_BINDING) writeonly buffer RowSums { real row_sums[]; };
uniform int lanes;
#if SINGLE
layout(binding = SINGLE_RAYLEIGH_UNIT) uniform sampler3D single_rayleigh_texture;
#if HAS_MIE
layout(binding = SINGLE_MIE_UNIT) uniform sampler3D single_mie_texture;
#endif
#else
layout(binding = DELTA_RADIANCE_UNIT) uniform sampler3D delta_radiance_texture;
#endif

void main() {
  const int rows = SCATTERING_R * SCATTERING_MU;
  const int row = int(gl_GlobalInvocationID.x);
  if (row >= rows) return;
  const int z = row / SCATTERING_MU, y = row % SCATTERING_MU;
  // The lanes beyond `lanes` hold no wavelength: they are left out by selection, a whole-vector
  // operation (NVIDIA refuses a double vector written at a non-constant index, C9999).
  const bvec4 used_lane = lessThan(ivec4(0, 1, 2, 3), ivec4(lanes));
  real4 sum = real4(0);
  for (int x = 0; x < SCATTERING_NU * SCATTERING_MU_S; ++x) {
    const ivec3 p = ivec3(x, y, z);
#if SINGLE
    const ScatteringCoordinates c = scattering_texel_coordinates(x, y, z, ANGLE_MAPPING_DISTANCE);
    real4 v = real4(texelFetch(single_rayleigh_texture, p, 0)) * rayleigh_phase(c.nu);
#if HAS_MIE
    v = v + real4(texelFetch(single_mie_texture, p, 0)) * model_mie_phase(c.nu);
#endif
#else
    const real4 v = real4(texelFetch(delta_radiance_texture, p, 0));
#endif
    sum += mix(real4(0), v, used_lane);
  }
  for (int k = 0; k < 4; ++k) row_sums[(wavelength_group * rows + row) * 4 + k] = sum[k];
}
