#version 450
// The display pass of a live frame (render/display/display_encoder.h): the
// frame's exposed radiance (Renderer::render_to_texture) → tone mapping, fade,
// blend mask and black level, display encoding (display_transform.glsl) →
// an RGBA8 or RGBA16 texture (TARGET_FORMAT rgba8 or rgba16) that a window
// draws, or that is read back for a file. Codes are rounded here,
// round(code_max · V) / code_max, so the texture holds the code the CPU path
// computes (image::display_code) whatever rounding the conversion to unorm uses.
layout(local_size_x = 16, local_size_y = 16) in;

#include "display_transform.glsl"

layout(binding = DISPLAY_RADIANCE_UNIT) uniform sampler2D radiance;
layout(binding = OUTPUT_IMAGE, TARGET_FORMAT) uniform writeonly image2D display;
uniform float code_max;  // 255 (rgba8) or 65535 (rgba16)

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(display)))) return;
  const vec3 v = display_linear(p, texelFetch(radiance, p, 0).rgb);
  const vec3 e = vec3(display_encode(v.r), display_encode(v.g), display_encode(v.b));
  imageStore(display, p, vec4(floor(e * code_max + 0.5) / code_max, 1.0));
}
