#version 450
// Last pass of a wavelength group over the tiles of the G-buffer path: what
// lies behind every atmosphere — an airless body's sunlit surface or the sun's
// disc — seen through the running transmittance T, added to the in-scattered
// radiance L of the atmosphere passes, and the group's colour added to the
// band's output (group_light.glsl). Unless it is the last group, it resets L
// and T to 0 and 1 for the next one.
//
// Defines: SUN_DISC (0: no disc), LIMB_DARKENING (0: a uniform disc), ECLIPSES.
#include "frame.glsl"
#include "group_light.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

layout(binding = GBUFFER_HIT_IMAGE, rgba32f) uniform readonly image2D gbuffer_hit;
layout(binding = GBUFFER_ALBEDO_IMAGE, rgba16f) uniform readonly image2D gbuffer_albedo;
layout(binding = RADIANCE_SUM_IMAGE, rgba32f) uniform image2D radiance_sum;
layout(binding = TRANSMITTANCE_PRODUCT_IMAGE, rgba32f) uniform image2D transmittance_product;

void main() {
  ivec2 p;
  if (!tile_pixel(p)) return;
  const vec4 hit = imageLoad(gbuffer_hit, p);
  vec4 L = vec4(0.0);
  vec3 ray;
  if (hit.z != 0.0 && pixel_ray(p, ray)) {
    L = imageLoad(radiance_sum, p);
    const vec4 T = imageLoad(transmittance_product, p);
    if (any(greaterThan(T, vec4(0.0)))) {
      if (hit.x >= 0.0) L += T * airless_surface(int(hit.y), ray, hit.x, imageLoad(gbuffer_albedo, p).rgb);
      else L += T * sun_disc(ray);
    }
  }
  add_group_rgb(p, L);
  if (!last_group) {
    imageStore(radiance_sum, p, vec4(0.0));
    imageStore(transmittance_product, p, vec4(1.0));
  }
}
