#version 450
// The stars' light joins the band's output (render/night/star_pass.h;
// docs/night-sky.md, "Rendering the night sky"), pixel by pixel: one
// invocation per pixel a star's 2 × 2 splat reaches (star_splat.comp), listed
// once each on the CPU, after night_sky.comp has added the night floor and
// the Moon's disc to the tiles. Each reads its 64-bit fixed-point sums from
// the star accumulator (star_accumulator.glsl) and clears them, and adds them
// where the pixel shows the sky: not a fisheye's corners beyond its circle, a
// warp's pixels beyond its mesh, nor a pixel whose ray ends on the ground or
// another body next to a star at its limb (the pass's test,
// render/night/star_visibility.h, bounds the stars against the sky). The list
// holds each pixel once, so no two invocations touch the same pixel.
//
// Only those pixels read the accumulator: when every pixel of a tile a splat
// reached read it (two 16-byte loads, which llvmpipe runs lane by lane), that
// was most of the stars' cost on a night ground view, where splats reach
// about half the sky's tiles.

#include "frame.glsl"
#include "frame_rgb.glsl"
#define STAR_PIXELS
#include "star_accumulator.glsl"

layout(local_size_x = 64) in;

/// Band pixels as y · band_size.x + x.
layout(std430, binding = STAR_PIXEL_LIST_BINDING) readonly buffer StarPixelList { uint star_pixel_list[]; };
uniform int star_pixel_count;

void main() {
  const uint k = gl_GlobalInvocationID.x;
  if (k >= uint(star_pixel_count)) return;
  const uint i = star_pixel_list[k];
  const ivec2 p = ivec2(int(i % uint(band_size.x)), int(i / uint(band_size.x)));
  const uvec4 rg = star_pixels[2u * i], b = star_pixels[2u * i + 1u];
  star_pixels[2u * i] = uvec4(0u);
  star_pixels[2u * i + 1u] = uvec4(0u);
  vec3 ray;
  float distance_m;
  if (!pixel_ray(p, ray) || nearest_body(ray, distance_m) >= 0) return;
  const vec3 stars = vec3(star_value(rg.x, rg.y), star_value(rg.z, rg.w), star_value(b.x, b.y));
  store_frame_rgb(p, clip_negative(load_frame_rgb(p) + stars));
}
