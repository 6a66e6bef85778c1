#pragma once
// An on-screen OpenGL context: a GLFW window with a GL 4.5 core context, the
// windowed twin of gl::HeadlessContext. Everything that renders (the Renderer,
// shader programs, textures) runs unchanged on either; only presentation
// differs (render/window/frame_presenter.h draws a finished frame into the
// window).
//
// Threads: GLFW requires initialisation, window creation, event processing and
// destruction on the main thread. Construct, poll and destroy WindowContext
// there; make_current() may bind the GL context on another thread.
//
// Process-wide state: GLFW is a process-wide library (glfwInit/glfwTerminate).
// The first live WindowContext initialises it and the last one to be destroyed
// terminates it; the count is held by a shared handle to the library, found
// through one mutex-guarded weak reference in window_context.cpp. That weak
// reference mirrors GLFW's own global initialisation and is the only global
// state here: callbacks reach their window's state through
// glfwSetWindowUserPointer, and errors are read with glfwGetError (no global
// error callback is installed).
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/gl/egl_context.h"

struct GLFWwindow;

namespace zenith::render::window {

/// Keyboard keys. The values are GLFW's key tokens (checked in
/// window_context.cpp), so any key GLFW reports can be carried, named here or
/// not. Printable keys are named by their position on a US layout, as in GLFW.
enum class Key : int {
  unknown = -1,
  space = 32,
  comma = 44,   ///< ,
  minus = 45,   ///< -
  period = 46,  ///< .
  digit_0 = 48,
  digit_9 = 57,
  equal = 61,  ///< =
  a = 65,
  p = 80,
  z = 90,
  left_bracket = 91,   ///< [
  right_bracket = 93,  ///< ]
  escape = 256,
  enter = 257,
  tab = 258,
  backspace = 259,
  right = 262,
  left = 263,
  down = 264,
  up = 265,
  page_up = 266,
  page_down = 267,
  home = 268,
  end = 269,
  f1 = 290,
  f12 = 301,
};

enum class KeyAction { press, repeat, release };

/// One key transition, in the order the window system reported them.
struct KeyEvent {
  Key key = Key::unknown;
  int scancode = 0;  ///< platform-specific; identifies keys GLFW has no token for
  KeyAction action = KeyAction::press;
  bool shift = false, control = false, alt = false, super = false;
};

struct WindowOptions {
  std::string title = "zenith";
  int width = 1280;  ///< client area in screen coordinates, ≥ 1
  int height = 720;
  bool resizable = true;
  bool visible = true;
  /// Frames between buffer swaps (1: synchronised to the display's refresh,
  /// 0: as fast as possible). Window systems without vsync (Xvfb) ignore it.
  int swap_interval = 1;
  /// Fullscreen on monitor `monitor` (an index of list_monitors(),
  /// render/window/monitors.h) at its current video mode; width and height are
  /// then ignored.
  bool fullscreen = false;
  int monitor = 0;
  /// Title bar and borders (windowed only).
  bool decorated = true;
  /// Top-left corner of the window's client area in screen coordinates
  /// (windowed only); unset: where the window system puts it.
  std::optional<std::array<int, 2>> position;
  /// Hide the cursor over the window (a projector's picture).
  bool hide_cursor = false;
};

/// The framebuffer's size in pixels (may differ from the window's size in
/// screen coordinates on high-DPI displays).
struct FramebufferSize {
  int width = 0;
  int height = 0;
};

/// A GLFW window plus its core-profile GL context, current on the constructing
/// thread from construction until destruction (or until another context is made
/// current). ContextOptions::gl_major/gl_minor/debug apply as for
/// HeadlessContext; ContextOptions::prefer does not (the window system picks
/// the device). The default framebuffer is double-buffered RGBA8, not sRGB:
/// FramePresenter encodes sRGB itself.
class WindowContext {
 public:
  /// Throws std::runtime_error "no display: set DISPLAY or use the headless
  /// path (omit --window)" (with GLFW's reason) when no window system can be
  /// reached, and std::runtime_error naming GLFW's reason when the window or a
  /// GL context of the requested version cannot be created.
  /// With `share`, the new context shares that window's GL objects (textures,
  /// buffers, programs, sync objects; not framebuffers and vertex arrays):
  /// several windows of one node draw the textures one renderer made.
  explicit WindowContext(const WindowOptions& window = {}, const gl::ContextOptions& context = {},
                         const WindowContext* share = nullptr);
  ~WindowContext();
  WindowContext(WindowContext&& other) noexcept;
  WindowContext& operator=(WindowContext&& other) noexcept;
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;

  /// Makes the window's context current on the calling thread (e.g. after a
  /// headless context was used for a precompute), replacing whatever context
  /// is current there, an EGL one (gl::HeadlessContext) included: with
  /// libglvnd a thread holds one current context across GLX and EGL, and GLX
  /// refuses (fatally, through Xlib) while an EGL context is current. The
  /// constructor does the same.
  void make_current() const;
  /// Detaches this window's context from the calling thread if it is current
  /// there: needed before making a gl::HeadlessContext current on this thread
  /// (EGL refuses while a GLX context is current). make_current() re-attaches.
  void release_current() const;
  /// Whether this context is current on the calling thread.
  bool is_current() const;

  /// GL_RENDERER, GL_VENDOR, GL_VERSION, GL_SHADING_LANGUAGE_VERSION.
  const std::string& renderer() const;
  const std::string& vendor() const;
  const std::string& version() const;
  const std::string& glsl_version() const;
  /// The version the context actually has (GL_MAJOR_VERSION, GL_MINOR_VERSION).
  int gl_major() const;
  int gl_minor() const;
  bool debug() const;
  /// True for a CPU rasterizer (llvmpipe, softpipe, swrast).
  bool is_software() const;

  FramebufferSize framebuffer_size() const;
  /// The refresh rate of the monitor the window is fullscreen on, else of the
  /// primary monitor; 0 where the window system does not say.
  int refresh_hz() const;
  /// True once the user asked to close the window (its close button, or
  /// request_close()).
  bool should_close() const;
  void request_close();
  void set_title(const std::string& title);

  /// Processes pending window-system events without waiting (keys are queued).
  void poll_events();
  /// Waits up to `timeout_s` seconds for an event, then processes what arrived.
  void wait_events(double timeout_s);
  /// The GLFW window, for the platform's own calls (render/window/swap_sync.h).
  GLFWwindow* glfw_window() const;
  /// Shows the back buffer (the frame drawn since the last swap).
  void swap_buffers();

  /// The key events received since the last call, oldest first.
  std::vector<KeyEvent> take_key_events();
  /// True when the window system asked for a redraw (exposed, resized) since
  /// the last call: present the last frame again (no new render needed).
  bool take_redraw_request();

 private:
  struct State;
  std::unique_ptr<State> state_;  // stable address: the GLFW user pointer points here
};

}  // namespace zenith::render::window
