#version 450
// The display pass of a live frame (render/display/display_encoder.h): the
// frame's exposed radiance (Renderer::render_to_texture) → tone mapping, fade,
// blend mask and black level, display encoding (display_transform.glsl) →
// an RGBA8 or RGBA16 texture that a window draws, or that is read back for a
// file; with an MPCDI colour profile, its decode, correct and encode around
// the output stage. Drawn as one triangle over a framebuffer holding the display texture
// (present.vert): fragment (x, y) is texel (x, y) of the frame, row 0 at the
// top as rendered. A fragment pass rather than a compute pass: a CPU
// rasterizer (llvmpipe) shades fragments in 4 × 4 stamps on every core and
// stores them through its JIT-compiled colour path, several times faster there
// than image stores from a compute shader; on a GPU the two cost the same.
// Codes are rounded here, round(code_max · V) / code_max, so the texture holds
// the code the CPU path computes (image::display_code) whatever rounding the
// conversion to unorm uses.
//
// FROM_BAND 1: the radiance comes straight from a band of the renderer's
// output buffer (band_output.glsl, Renderer::render_on_gpu), drawn over the
// band's rows: a live frame that needs no radiance texture skips writing and
// reading one.

#include "display_transform.glsl"

#if FROM_BAND
#include "band_output.glsl"
#else
layout(binding = DISPLAY_RADIANCE_UNIT) uniform sampler2D radiance;
#endif
uniform float code_max;  // 255 (rgba8) or 65535 (rgba16)

layout(location = 0) out vec4 display;

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
#if FROM_BAND
  const vec3 e = display_signal(p, band_rgb(p));
#else
  const vec3 e = display_signal(p, texelFetch(radiance, p, 0).rgb);
#endif
  display = vec4(floor(e * code_max + 0.5) / code_max, 1.0);
}
