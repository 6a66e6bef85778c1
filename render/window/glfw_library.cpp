#include "render/window/glfw_library.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <mutex>
#include <stdexcept>

#include "render/gl/software_rasterizer.h"

namespace zenith::render::window {

std::string glfw_error() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  if (code == GLFW_NO_ERROR) return "no error reported by GLFW";
  return fmt::format("{} (0x{:05X})", description != nullptr ? description : "no description", code);
}

GlfwLibrary::GlfwLibrary() {
  glfwGetError(nullptr);                      // drop any error left from an earlier, failed use
  gl::default_software_rasterizer_threads();  // before GLFW opens the display: Mesa reads it then
  if (glfwInit() != GLFW_TRUE)
    throw std::runtime_error(
        fmt::format("no display: set DISPLAY or use the headless path (omit --window) (GLFW: {})", glfw_error()));
}

GlfwLibrary::~GlfwLibrary() { glfwTerminate(); }

// The weak reference mirrors GLFW's own process-wide initialisation (see
// window_context.h); GLFW is main-thread only, the mutex merely keeps the
// reference itself consistent.
std::shared_ptr<GlfwLibrary> acquire_glfw() {
  static std::mutex mutex;
  static std::weak_ptr<GlfwLibrary> live;
  const std::lock_guard lock(mutex);
  if (std::shared_ptr<GlfwLibrary> library = live.lock()) return library;
  auto library = std::make_shared<GlfwLibrary>();
  live = library;
  return library;
}

}  // namespace zenith::render::window
