#pragma once
// render_to_texture()'s band output: a fragment pass
// (shaders/render/band_to_texture.frag, compiled on first use) that draws a
// band's pixels from the output buffer (render/band/gpu_band.h) into rows
// first_row… of the frame's texture, black tiles as 0. A draw, not a dispatch:
// it leaves the default draw framebuffer bound.

#include "render/band/gpu_band.h"
#include "render/frame/pass_timer.h"
#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/gl/texture_rows_draw.h"

namespace zenith::render {

class BandToTexture {
 public:
  /// Draws `band` (its output buffer and black-tile flags bound) into `target`
  /// (a 2D rgba32f or rgba16f texture of the frame's size); "copy to texture" in `timer`.
  void copy(const GpuBand& band, gl::Texture& target, PassTimer& timer);
  /// Queues the program's first draw into a `target`-format texture on
  /// `warmup`'s thread (render/gl/first_dispatch_warmup.h); builds it now.
  void warm(gl::FirstDispatchWarmup& warmup, gl::TextureFormat target);

 private:
  gl::ShaderProgram& program();

  gl::ShaderProgram program_;
  gl::TextureRowsDraw rows_;  // the target's rows as the framebuffer
};

}  // namespace zenith::render
