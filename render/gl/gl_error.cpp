#include "render/gl/gl_error.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace zenith::render::gl {

const char* gl_error_name(unsigned error) {
  switch (error) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: return "unknown GL error";
  }
}

void check_gl_error(std::string_view what) {
  std::string errors;
  // Bounded: a lost context may report GL_CONTEXT_LOST forever.
  for (int i = 0; i < 16; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    if (!errors.empty()) errors += ", ";
    errors += fmt::format("{} (0x{:04X})", gl_error_name(e), e);
  }
  if (!errors.empty()) throw std::runtime_error(fmt::format("{}: {}", what, errors));
}

}  // namespace zenith::render::gl
