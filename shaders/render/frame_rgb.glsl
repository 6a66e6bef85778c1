// The band's output: linear sRGB × exposure per pixel, x fastest, rows of
// band_size.x pixels, one vec4 (rgb, 0) per pixel. Passes write it in place
// and the renderer maps it and packs the rows for its RowSink (3 floats per
// pixel). One 16-byte store per pixel: Mesa's llvmpipe turns each storage
// buffer store into a loop over the SIMD lanes, so three float stores per
// pixel cost three times one vec4 store (measured: docs/rendering-performance.md).
//
// Out-of-gamut colours (the CIE mapping's negative lobes) are clipped to 0 as
// the last write of a pixel does; a NaN stays visible (a comparison with NaN
// is false), so the stress tests still see it.
layout(std430, binding = FRAME_RGB_BINDING) buffer FrameRgb { vec4 frame_rgb[]; };

uint frame_rgb_index(ivec2 p) { return uint(p.y) * uint(band_size.x) + uint(p.x); }

vec3 load_frame_rgb(ivec2 p) { return frame_rgb[frame_rgb_index(p)].rgb; }

void store_frame_rgb(ivec2 p, vec3 rgb) { frame_rgb[frame_rgb_index(p)] = vec4(rgb, 0.0); }

/// Negative components to 0, NaN kept.
vec3 clip_negative(vec3 rgb) { return mix(rgb, vec3(0.0), lessThan(rgb, vec3(0.0))); }
