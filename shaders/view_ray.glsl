// The view rays of the scattering table, sampled once per ray (cpu_precompute.cpp:
// view_ray_samples). A ray of the table, x = (r, μ), depends only on the texel's
// r and μ indices (z, y), not on μs or ν, so what depends only on the ray at its
// SCATTERING_SAMPLES + 1 samples y_i = x + t_i v (t_i from ray_sample_distance,
// crowded toward the ray's lowest point) is computed once per ray and per wavelength group (view_transmittance.comp) and
// read by every texel of the row (single_scattering.comp, multiple_scattering.comp):
//  * T(x, y_i), 4 wavelengths;
//  * the r and μ texture coordinates of y_i in the 4D table (u_r, u_μ of
//    scattering_uvwz, with the μ mapping of the stage), which cost two acos each.
// Needs atmosphere_common.glsl.

layout(std430, binding = VIEW_TRANSMITTANCE_BINDING) buffer ViewTransmittance { real4 view_transmittance[]; };
layout(std430, binding = VIEW_RAY_COORDINATES_BINDING) buffer ViewRayCoordinates { real2 view_ray_uv[]; };

int view_ray_sample_index(int z, int y, int i) { return (z * SCATTERING_MU + y) * (SCATTERING_SAMPLES + 1) + i; }
