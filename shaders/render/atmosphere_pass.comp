#version 450
// One atmosphere's pass over the tiles of the G-buffer path (tiles two or
// more shells can touch; render/renderer.cpp), for one group of 4 wavelengths:
// paper section 5.2, Algorithm 1.
//
// Several atmospheres are composited front to back (render/renderer.cpp runs
// the passes in the order the camera meets the shells). Per pixel the passes
// keep a running radiance L and transmittance T (images radiance_sum and
// transmittance_product, set to 0 and 1 by gbuffer.comp); this pass adds T·S
// for the in-scattered radiance S of its segment of the ray and multiplies T
// by the segment's transmittance (atmosphere_segment.glsl). Where the ray ends
// on this planet's own ground it adds the ground's reflected light too and
// sets T to 0: nothing behind is seen. Tiles a single shell touches are drawn
// in one pass instead (atmosphere_tile.comp).
//
// Defines (render/frame/gpu_atmosphere.cpp): those of atmosphere_common.glsl,
// MULTIPLE_SCATTERING, ECLIPSES (atmosphere_segment.glsl).
#include "atmosphere_common.glsl"
#include "frame.glsl"
#include "atmosphere_segment.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

layout(binding = GBUFFER_HIT_IMAGE, rgba32f) uniform readonly image2D gbuffer_hit;
layout(binding = GBUFFER_ALBEDO_IMAGE, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(binding = RADIANCE_SUM_IMAGE, rgba32f) uniform image2D radiance_sum;
layout(binding = TRANSMITTANCE_PRODUCT_IMAGE, rgba32f) uniform image2D transmittance_product;

uniform vec4 sun_irradiance;  // E_sun per wavelength of the group [W m^-2 nm^-1]
uniform vec4 albedo_from_r;   // reflectance of each wavelength from linear sRGB albedo
uniform vec4 albedo_from_g;
uniform vec4 albedo_from_b;

void main() {
  ivec2 p;  // the tiles of the G-buffer path this shell can touch (frame.glsl)
  if (!tile_pixel(p)) return;
  const vec4 hit = imageLoad(gbuffer_hit, p);
  if (hit.z == 0.0) return;  // outside the projection's image
  vec4 T_so_far = imageLoad(transmittance_product, p);
  if (all(equal(T_so_far, vec4(0.0)))) return;  // an opaque surface in front
  vec3 ray;
  if (!pixel_ray(p, ray)) return;
  const int hit_body = hit.x >= 0.0 ? int(hit.y) : -1;
  real4 rho = real4(0);
  if (hit_body == planet) {
    const vec3 albedo = imageLoad(gbuffer_albedo, p).rgb;
    rho = real4(albedo_from_r * albedo.r + albedo_from_g * albedo.g + albedo_from_b * albedo.b);
  }
  real4 radiance, transmittance_segment;
  if (!atmosphere_segment(ray, hit.x, hit_body, rho, radiance, transmittance_segment)) return;
  const vec4 L = imageLoad(radiance_sum, p);
  imageStore(radiance_sum, p, L + T_so_far * vec4(radiance) * sun_irradiance);
  imageStore(transmittance_product, p, T_so_far * vec4(transmittance_segment));
}
