// A body's albedo where a ray meets it: its equirectangular map (one layer of
// an array texture per body, all resampled to one size, so the map is picked
// by a coordinate, not by branching over samplers), at the mip level of the
// pixel's footprint. Shared by gbuffer.comp and direct_light.comp so that a
// surface looks the same whichever pass draws its tile.
// Include after frame.glsl.

layout(binding = ALBEDO_MAPS_UNIT) uniform sampler2DArray albedo_maps;

/// Linear sRGB albedo of a body at distance t along `ray`, n its outward normal there.
vec3 surface_albedo(Body body, vec3 ray, float t, vec3 n) {
  // Equirectangular map in the body frame: u from longitude −180°, v from the north pole.
  const vec3 nb = to_body_frame(body, n);
  const vec2 uv = vec2(atan(nb.y, nb.x) / (2.0 * PI_F) + 0.5, acos(clamp(nb.z, -1.0, 1.0)) / PI_F);
#if defined(ALBEDO_LOD0) && ALBEDO_LOD0
  // The renderer found every footprint of the frame under a texel (albedo_at_full_resolution).
  return textureLod(albedo_maps, vec3(uv, body.shape.w), 0.0).rgb;
#else
  // Level of detail: the pixel's footprint on the surface (stretched by the
  // incidence angle) in texels of the map's level 0 (2π R per map width).
  const float cos_incidence = max(abs(dot(n, ray)), 0.05);
  // pixel_footprint: this pixel's own (frame.glsl), not the image's bound.
  const float footprint_m = pixel_footprint * t / cos_incidence;
  const float texel_m = 2.0 * PI_F * body.shape.x / max(body.albedo_map.x, 1.0);
  const float lod = max(0.0, log2(max(footprint_m / texel_m, 1e-6)));
  return textureLod(albedo_maps, vec3(uv, body.shape.w), lod).rgb;
#endif
}
vec3 surface_albedo(int b, vec3 ray, float t, vec3 n) { return surface_albedo(bodies[b], ray, t, n); }
