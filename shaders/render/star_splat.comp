#version 450
// Stars as point sources of flux (render/night/star_placement.h computes each
// star's pixel position and radiance on the CPU; docs/night-sky.md,
// "Rendering the night sky"): one invocation per star of the band spreads
// its radiance bilinearly over the 2 × 2 pixels around its position (weights
// summing to 1; pixel centres at i + 0.5), so a star moving across pixels
// keeps its energy and does not flicker. The weights go to the band's star
// accumulator (star_accumulator.glsl) in fixed point of a constant step, the
// same on every node; night_sky.comp adds them to the band's output.

layout(local_size_x = 64) in;

#include "star_accumulator.glsl"

/// Per star two vec4: (x_px, y_px, 0, 0) in the full image, (r, g, b, 0).
layout(std430, binding = STAR_SPLATS_BINDING) readonly buffer StarSplats { vec4 star_splats[]; };

uniform int star_count;
uniform ivec2 band_origin;
uniform ivec2 band_size;

void add_to_pixel(ivec2 image_pixel, vec3 rgb) {
  const ivec2 p = image_pixel - band_origin;
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, band_size))) return;
  const uint i = STAR_UINTS_PER_PIXEL * (uint(p.y) * uint(band_size.x) + uint(p.x));
  add_star_counts(i, rgb.r);
  add_star_counts(i + 2u, rgb.g);
  add_star_counts(i + 4u, rgb.b);
}

void main() {
  const uint star = gl_GlobalInvocationID.x;
  if (star >= uint(star_count)) return;
  const vec2 position = star_splats[2u * star].xy - vec2(0.5);
  const vec3 rgb = star_splats[2u * star + 1u].rgb;
  const vec2 corner = floor(position);
  const vec2 t = position - corner;
  const ivec2 c = ivec2(corner);
  add_to_pixel(c, rgb * ((1.0 - t.x) * (1.0 - t.y)));
  add_to_pixel(c + ivec2(1, 0), rgb * (t.x * (1.0 - t.y)));
  add_to_pixel(c + ivec2(0, 1), rgb * ((1.0 - t.x) * t.y));
  add_to_pixel(c + ivec2(1, 1), rgb * (t.x * t.y));
}
