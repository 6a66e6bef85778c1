#pragma once
// glGetError as exceptions, for the few places where a failure must not pass
// silently (storage allocation, readback). Needs a current context.
#include <string_view>

namespace zenith::render::gl {

/// "GL_INVALID_VALUE", "GL_OUT_OF_MEMORY", ...; "unknown GL error" otherwise.
const char* gl_error_name(unsigned error);

/// Drains glGetError; if any error was pending, throws std::runtime_error
/// "<what>: GL_INVALID_VALUE (0x0501)" naming every pending error.
void check_gl_error(std::string_view what);

}  // namespace zenith::render::gl
