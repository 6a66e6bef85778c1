#version 450
// Body pass over the tiles some atmosphere touches (the renderer's list): the
// nearest analytic sphere along the pixel's ray, written into the G-buffer,
//   gbuffer_hit:    x = distance from the camera [m] (−1: no body), y = body index,
//                   z = 1 where the projection has a ray, 0 outside it
//   gbuffer_albedo: rgb = linear sRGB albedo at the hit (from the body's map)
// and the running radiance and transmittance of the atmosphere passes set to
// 0 and 1 (no image clears). The later passes rebuild the hit point and
// normal from (ray, distance, body). Tiles no atmosphere touches never need a
// G-buffer: direct_light.comp draws them in one pass.
#include "frame.glsl"
#include "surface_albedo.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

layout(binding = GBUFFER_HIT_IMAGE, rgba32f) uniform writeonly image2D gbuffer_hit;
layout(binding = GBUFFER_ALBEDO_IMAGE, rgba16f) uniform writeonly image2D gbuffer_albedo;
layout(binding = RADIANCE_SUM_IMAGE, rgba32f) uniform writeonly image2D radiance_sum;
layout(binding = TRANSMITTANCE_PRODUCT_IMAGE, rgba32f) uniform writeonly image2D transmittance_product;

void main() {
  ivec2 p;
  if (!tile_pixel(p)) return;
  imageStore(radiance_sum, p, vec4(0.0));
  imageStore(transmittance_product, p, vec4(1.0));
  vec3 ray;
  if (!pixel_ray(p, ray)) {
    imageStore(gbuffer_hit, p, vec4(-1.0, -1.0, 0.0, 0.0));
    imageStore(gbuffer_albedo, p, vec4(0.0));
    return;
  }
  float nearest;
  const int hit_body = nearest_body(ray, nearest);
  if (hit_body < 0) {
    imageStore(gbuffer_hit, p, vec4(-1.0, -1.0, 1.0, 0.0));
    imageStore(gbuffer_albedo, p, vec4(0.0));
    return;
  }
  const vec3 n = body_normal(hit_body, ray, nearest);
  imageStore(gbuffer_hit, p, vec4(nearest, float(hit_body), 1.0, 0.0));
  imageStore(gbuffer_albedo, p, vec4(surface_albedo(hit_body, ray, nearest, n), 0.0));
}
