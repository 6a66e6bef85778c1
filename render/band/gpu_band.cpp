#include "render/band/gpu_band.h"

#include <array>

#include "render/gl/shader_program.h"

namespace zenith::render {

void set_band_uniforms(const gl::ShaderProgram& program, const GpuBand& band) {
  program.set_uniform("band_origin", std::array<int, 2>{0, band.first_row});
  program.set_uniform("band_size", std::array<int, 2>{band.width, band.rows});
  program.set_uniform("tile_columns", band.tile_columns);
}

}  // namespace zenith::render
