#include "render/band/band_to_texture.h"

#include <epoxy/gl.h>

#include "render/shader_programs.h"

namespace zenith::render {

void BandToTexture::copy(const GpuBand& band, gl::Texture& target, PassTimer& timer) {
  if (program_.id() == 0) program_ = load_graphics_program("render/present.vert", "render/band_to_texture.frag");
  set_band_uniforms(program_, band);
  // The band's rows of the frame's texture as the viewport: row r of the band is texel row first_row + r.
  rows_.bind(target, band.first_row, band.rows);
  timer.gpu("copy to texture", [&] { rows_.draw(program_); });
  rows_.unbind();
  // The next band's passes write the output buffer this pass reads.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace zenith::render
