#version 450
// Body pass: for every pixel of the band, the nearest analytic sphere along the
// pixel's ray, written into the G-buffer:
//   gbuffer_hit:    x = distance from the camera [m] (−1: no body), y = body index,
//                   z = 1 where the projection has a ray, 0 outside it
//   gbuffer_albedo: rgb = linear sRGB albedo at the hit (from the body's map)
// The later passes rebuild the hit point and normal from (ray, distance, body).
#include "frame.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = 0, rgba32f) uniform writeonly image2D gbuffer_hit;
layout(binding = 1, rgba16f) uniform writeonly image2D gbuffer_albedo;

/// Every body's albedo map as one layer of an array texture (all resampled to
/// one size), so the map is picked by a coordinate, not by branching over samplers.
layout(binding = 8) uniform sampler2DArray albedo_maps;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, band_size))) return;
  vec3 ray;
  if (!pixel_ray(p, ray)) {
    imageStore(gbuffer_hit, p, vec4(-1.0, -1.0, 0.0, 0.0));
    imageStore(gbuffer_albedo, p, vec4(0.0));
    return;
  }
  float nearest = 3.4e38;
  int hit_body = -1;
  for (int b = 0; b < body_count; ++b) {
    const float t = intersect_body(b, ray);
    if (t >= 0.0 && t < nearest) {
      nearest = t;
      hit_body = b;
    }
  }
  if (hit_body < 0) {
    imageStore(gbuffer_hit, p, vec4(-1.0, -1.0, 1.0, 0.0));
    imageStore(gbuffer_albedo, p, vec4(0.0));
    return;
  }
  // Equirectangular map in the body frame: u from longitude −180°, v from the north pole.
  const vec3 n = body_normal(hit_body, ray, nearest);
  const vec3 nb = to_body_frame(hit_body, n);
  const float PI_F = 3.14159265;
  const vec2 uv = vec2(atan(nb.y, nb.x) / (2.0 * PI_F) + 0.5, acos(clamp(nb.z, -1.0, 1.0)) / PI_F);
  // Level of detail: the pixel's footprint on the surface (stretched by the
  // incidence angle) in texels of the map's level 0 (2π R per map width).
  const float layer = bodies[hit_body].shape.w;
  const float cos_incidence = max(abs(dot(n, ray)), 0.05);
  const float footprint_m = pixel_angle * nearest / cos_incidence;
  const float texel_m = 2.0 * PI_F * bodies[hit_body].shape.x / max(bodies[hit_body].albedo_map.x, 1.0);
  const float lod = max(0.0, log2(max(footprint_m / texel_m, 1e-6)));
  imageStore(gbuffer_hit, p, vec4(nearest, float(hit_body), 1.0, 0.0));
  imageStore(gbuffer_albedo, p, vec4(textureLod(albedo_maps, vec3(uv, layer), lod).rgb, 0.0));
}
