#pragma once
// Implementation limits that size lookup tables and compute dispatches.
#include <array>
#include <cstdint>
#include <string>

namespace zenith::render::gl {

struct GlLimits {
  int max_texture_size = 0;     ///< GL_MAX_TEXTURE_SIZE (2D width/height)
  int max_3d_texture_size = 0;  ///< GL_MAX_3D_TEXTURE_SIZE (each 3D dimension)
  int max_texture_image_units = 0;
  int max_image_units = 0;
  int max_compute_work_group_invocations = 0;            ///< local_size_x·y·z at most
  std::array<int, 3> max_compute_work_group_size = {};   ///< per axis
  std::array<int, 3> max_compute_work_group_count = {};  ///< per axis, per dispatch
  int max_compute_shared_memory_size = 0;                ///< bytes
  std::int64_t max_shader_storage_block_size = 0;        ///< bytes
  int max_uniform_block_size = 0;                        ///< bytes
};

/// Queries the current context.
GlLimits query_gl_limits();
/// One line per limit, "GL_MAX_3D_TEXTURE_SIZE = 2048", for logs.
std::string to_string(const GlLimits& limits);

}  // namespace zenith::render::gl
