#include "render/band/band_to_texture.h"

#include "render/shader_programs.h"

namespace zenith::render {

gl::ShaderProgram& BandToTexture::program() {
  if (program_.id() == 0) program_ = load_graphics_program("render/present.vert", "render/band_to_texture.frag");
  return program_;
}

void BandToTexture::warm(gl::FirstDispatchWarmup& warmup, gl::TextureFormat target) {
  warmup.warm_draw(program(), {}, target);  // it reads the band's buffers only: no textures to shape
}

void BandToTexture::copy(const GpuBand& band, gl::Texture& target, PassTimer& timer) {
  set_band_uniforms(program(), band);
  // The band's rows of the frame's texture as the viewport: row r of the band is texel row first_row + r.
  rows_.bind(target, band.first_row, band.rows);
  timer.gpu("copy to texture", [&] { rows_.draw(program_); });
  rows_.unbind();
}

}  // namespace zenith::render
