#pragma once
// Private to zenith_window: the process-wide GLFW library, initialised by the
// first holder (a WindowContext, a monitor query) and terminated with the last
// (see window_context.h, "Process-wide state").
#include <memory>
#include <string>

namespace zenith::render::window {

/// The initialised GLFW library; glfwTerminate when the last holder lets go.
class GlfwLibrary {
 public:
  /// Throws std::runtime_error "no display: …" (with GLFW's reason) when no window system can be reached.
  GlfwLibrary();
  ~GlfwLibrary();
  GlfwLibrary(const GlfwLibrary&) = delete;
  GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

/// The shared handle to GLFW: a live one if anyone holds it, else a freshly
/// initialised one. Main thread only (GLFW's rule).
std::shared_ptr<GlfwLibrary> acquire_glfw();

/// GLFW's description of the most recent error (clearing it), or a placeholder.
std::string glfw_error();

}  // namespace zenith::render::window
