#pragma once
// A band of a frame kept on the GPU, as Renderer::render_on_gpu hands it to
// its sink and render_to_texture copies it (render/band/band_to_texture.h):
// the band's pixels are in the output buffer bound at FRAME_RGB_BINDING
// (render/shader_bindings.h: one vec4 (rgb, 0) per pixel, rows of `width`
// pixels from row `first_row` of the frame), the band's black-tile flags at
// BLACK_TILES_BINDING (one uint per 16 × 16 tile, row by row, `tile_columns` a
// row; 1 where nothing was drawn: those pixels hold stale values and read as
// 0). shaders/render/band_output.glsl reads them.

namespace zenith::render {

namespace gl {
class ShaderProgram;  // render/gl/shader_program.h
}  // namespace gl

struct GpuBand {
  int first_row = 0, rows = 0, width = 0, tile_columns = 0;
};

/// band_output.glsl's uniforms of `band` (band_origin, band_size, tile_columns) on `program`.
void set_band_uniforms(const gl::ShaderProgram& program, const GpuBand& band);

}  // namespace zenith::render
