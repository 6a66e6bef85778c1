#include "render/gl/debug_output.h"

#include <epoxy/gl.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <string_view>

namespace zenith::render::gl {
namespace {

const char* source_name(GLenum source) {
  switch (source) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
  }
}

const char* type_name(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated behavior";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behavior";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    case GL_DEBUG_TYPE_MARKER: return "marker";
    case GL_DEBUG_TYPE_PUSH_GROUP: return "push group";
    case GL_DEBUG_TYPE_POP_GROUP: return "pop group";
    default: return "other";
  }
}

spdlog::level::level_enum level_of(GLenum severity) {
  switch (severity) {
    case GL_DEBUG_SEVERITY_HIGH: return spdlog::level::err;
    case GL_DEBUG_SEVERITY_MEDIUM: return spdlog::level::warn;
    case GL_DEBUG_SEVERITY_LOW: return spdlog::level::info;
    default: return spdlog::level::debug;  // GL_DEBUG_SEVERITY_NOTIFICATION
  }
}

void GLAPIENTRY on_debug_message(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                 const GLchar* message, const void* /*user*/) {
  std::string_view text =
      length >= 0 ? std::string_view(message, static_cast<std::size_t>(length)) : std::string_view(message);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
  spdlog::log(level_of(severity), "GL {} [{} #{}]: {}", type_name(type), source_name(source), id, text);
}

}  // namespace

void enable_debug_output(bool synchronous) {
  glEnable(GL_DEBUG_OUTPUT);
  if (synchronous)
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  else
    glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

bool debug_output_requested() {
  const char* value = std::getenv("ZENITH_GL_DEBUG");
  return value != nullptr && *value != '\0' && std::string_view(value) != "0";
}

}  // namespace zenith::render::gl
