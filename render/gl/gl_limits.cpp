#include "render/gl/gl_limits.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

namespace zenith::render::gl {
namespace {

int get_int(GLenum name) {
  GLint v = 0;
  glGetIntegerv(name, &v);
  return v;
}

int get_int(GLenum name, GLuint index) {
  GLint v = 0;
  glGetIntegeri_v(name, index, &v);
  return v;
}

}  // namespace

GlLimits query_gl_limits() {
  GlLimits l;
  l.max_texture_size = get_int(GL_MAX_TEXTURE_SIZE);
  l.max_3d_texture_size = get_int(GL_MAX_3D_TEXTURE_SIZE);
  l.max_texture_image_units = get_int(GL_MAX_TEXTURE_IMAGE_UNITS);
  l.max_image_units = get_int(GL_MAX_IMAGE_UNITS);
  l.max_compute_work_group_invocations = get_int(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
  for (GLuint i = 0; i < 3; ++i) {
    l.max_compute_work_group_size[i] = get_int(GL_MAX_COMPUTE_WORK_GROUP_SIZE, i);
    l.max_compute_work_group_count[i] = get_int(GL_MAX_COMPUTE_WORK_GROUP_COUNT, i);
  }
  l.max_compute_shared_memory_size = get_int(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
  GLint64 ssbo = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssbo);
  l.max_shader_storage_block_size = ssbo;
  l.max_uniform_block_size = get_int(GL_MAX_UNIFORM_BLOCK_SIZE);
  return l;
}

std::string to_string(const GlLimits& l) {
  std::string s;
  auto line = [&](const char* name, auto value) { s += fmt::format("{} = {}\n", name, value); };
  auto line3 = [&](const char* name, const std::array<int, 3>& v) {
    s += fmt::format("{} = {} {} {}\n", name, v[0], v[1], v[2]);
  };
  line("GL_MAX_TEXTURE_SIZE", l.max_texture_size);
  line("GL_MAX_3D_TEXTURE_SIZE", l.max_3d_texture_size);
  line("GL_MAX_TEXTURE_IMAGE_UNITS", l.max_texture_image_units);
  line("GL_MAX_IMAGE_UNITS", l.max_image_units);
  line("GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", l.max_compute_work_group_invocations);
  line3("GL_MAX_COMPUTE_WORK_GROUP_SIZE", l.max_compute_work_group_size);
  line3("GL_MAX_COMPUTE_WORK_GROUP_COUNT", l.max_compute_work_group_count);
  line("GL_MAX_COMPUTE_SHARED_MEMORY_SIZE", l.max_compute_shared_memory_size);
  line("GL_MAX_SHADER_STORAGE_BLOCK_SIZE", l.max_shader_storage_block_size);
  line("GL_MAX_UNIFORM_BLOCK_SIZE", l.max_uniform_block_size);
  return s;
}

}  // namespace zenith::render::gl
