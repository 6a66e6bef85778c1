#version 450
// A thumbnail of what a projector shows (render/display/display_encoder.h,
// cluster/node/thumbnail.h), reduced on the GPU so only its few pixels are read
// back: thumbnail pixel (x, y) is the mean of the display-linear values
// (display_transform.glsl, each clamped to [0, 1], NaN as 0) of the frame's
// columns [x·w/tw, (x+1)·w/tw) and rows likewise (integer division, at least
// one each), as cluster::make_thumbnail computes it on the CPU.
layout(local_size_x = 8, local_size_y = 8) in;

#include "display_transform.glsl"

layout(binding = DISPLAY_RADIANCE_UNIT) uniform sampler2D radiance;
layout(binding = OUTPUT_IMAGE, rgba32f) uniform writeonly image2D thumbnail;
uniform ivec2 frame_size;
uniform ivec2 thumbnail_size;

/// The frame's pixels [begin, end) that thumbnail pixel i of n covers along an axis of `total`.
ivec2 span_of(int i, int n, int total) {
  const int begin = i * total / n;
  return ivec2(begin, max(begin + 1, (i + 1) * total / n));
}

void main() {
  const ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(t, thumbnail_size))) return;
  const ivec2 xs = span_of(t.x, thumbnail_size.x, frame_size.x);
  const ivec2 ys = span_of(t.y, thumbnail_size.y, frame_size.y);
  vec3 sum = vec3(0.0);
  for (int y = ys.x; y < ys.y; ++y) {
    vec3 row = vec3(0.0);  // a row at a time: fewer terms per float sum
    for (int x = xs.x; x < xs.y; ++x) {
      const ivec2 p = ivec2(x, y);
      const vec3 v = display_linear(p, texelFetch(radiance, p, 0).rgb);
      row += mix(clamp(v, 0.0, 1.0), vec3(0.0), isnan(v));
    }
    sum += row;
  }
  imageStore(thumbnail, t, vec4(sum / float((xs.y - xs.x) * (ys.y - ys.x)), 1.0));
}
