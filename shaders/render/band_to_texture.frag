#version 450
// Renderer::render_to_texture's band output (render/renderer.h): the band's
// pixels (band_output.glsl; black tiles as 0) into their rows of the frame's
// texture, which stays on the GPU. Drawn as one triangle (present.vert) over
// the band's rows of a framebuffer holding the frame's texture (the
// viewport): fragment (x, y) is frame pixel (x, y), row 0 at the top as
// rendered. A fragment pass: a CPU rasterizer (llvmpipe) stores fragments
// through its JIT-compiled colour path on every core, much faster there than a
// compute shader's image stores; on a GPU the two cost the same.

#include "band_output.glsl"

layout(location = 0) out vec4 frame;

void main() { frame = vec4(band_rgb(ivec2(gl_FragCoord.xy)), 1.0); }
