#include "render/window/window_context.h"

// No X11 types from <EGL/eglplatform.h>: EGL is only asked about the current context.
#ifndef EGL_NO_X11
#define EGL_NO_X11
#endif
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "render/gl/debug_output.h"
#include "render/gl/software_rasterizer.h"
#include "render/window/glfw_library.h"

namespace zenith::render::window {
namespace {

// Key values are GLFW's tokens: a KeyEvent carries any key by a plain cast.
static_assert(static_cast<int>(Key::unknown) == GLFW_KEY_UNKNOWN);
static_assert(static_cast<int>(Key::space) == GLFW_KEY_SPACE);
static_assert(static_cast<int>(Key::comma) == GLFW_KEY_COMMA);
static_assert(static_cast<int>(Key::minus) == GLFW_KEY_MINUS);
static_assert(static_cast<int>(Key::period) == GLFW_KEY_PERIOD);
static_assert(static_cast<int>(Key::digit_0) == GLFW_KEY_0);
static_assert(static_cast<int>(Key::digit_9) == GLFW_KEY_9);
static_assert(static_cast<int>(Key::equal) == GLFW_KEY_EQUAL);
static_assert(static_cast<int>(Key::a) == GLFW_KEY_A);
static_assert(static_cast<int>(Key::p) == GLFW_KEY_P);
static_assert(static_cast<int>(Key::z) == GLFW_KEY_Z);
static_assert(static_cast<int>(Key::left_bracket) == GLFW_KEY_LEFT_BRACKET);
static_assert(static_cast<int>(Key::right_bracket) == GLFW_KEY_RIGHT_BRACKET);
static_assert(static_cast<int>(Key::escape) == GLFW_KEY_ESCAPE);
static_assert(static_cast<int>(Key::enter) == GLFW_KEY_ENTER);
static_assert(static_cast<int>(Key::tab) == GLFW_KEY_TAB);
static_assert(static_cast<int>(Key::backspace) == GLFW_KEY_BACKSPACE);
static_assert(static_cast<int>(Key::right) == GLFW_KEY_RIGHT);
static_assert(static_cast<int>(Key::left) == GLFW_KEY_LEFT);
static_assert(static_cast<int>(Key::down) == GLFW_KEY_DOWN);
static_assert(static_cast<int>(Key::up) == GLFW_KEY_UP);
static_assert(static_cast<int>(Key::page_up) == GLFW_KEY_PAGE_UP);
static_assert(static_cast<int>(Key::page_down) == GLFW_KEY_PAGE_DOWN);
static_assert(static_cast<int>(Key::home) == GLFW_KEY_HOME);
static_assert(static_cast<int>(Key::end) == GLFW_KEY_END);
static_assert(static_cast<int>(Key::f1) == GLFW_KEY_F1);
static_assert(static_cast<int>(Key::f12) == GLFW_KEY_F12);

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s != nullptr ? std::string(s) : std::string();
}

/// Detaches an EGL context (a gl::HeadlessContext's) from the calling thread.
/// With libglvnd a thread has at most one current context across GLX and EGL:
/// glXMakeCurrent while an EGL context is current fails with an X BadAccess
/// error, which Xlib's default handler turns into exit(1). Within one API,
/// making a context current replaces the previous one; this extends that to
/// the pair. (zenith_render links libEGL: the query always finds it.)
void release_current_egl_context() {
  if (!epoxy_has_egl() || eglGetCurrentContext() == EGL_NO_CONTEXT) return;
  eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

KeyAction key_action(int action) {
  switch (action) {
    case GLFW_RELEASE: return KeyAction::release;
    case GLFW_REPEAT: return KeyAction::repeat;
    default: return KeyAction::press;
  }
}

}  // namespace

struct WindowContext::State {
  std::shared_ptr<GlfwLibrary> library;  // declared first: released after the window
  GLFWwindow* window = nullptr;
  GLFWmonitor* monitor = nullptr;  // fullscreen on this one
  std::string renderer, vendor, version, glsl_version;
  int gl_major = 0, gl_minor = 0;
  bool debug = false, software = false;
  std::vector<KeyEvent> keys;
  bool redraw = true;  // the first frame is always drawn

  State() = default;
  State(const State&) = delete;
  State& operator=(const State&) = delete;
  // GLFW detaches the context first if it is current on this thread.
  ~State() {
    if (window != nullptr) glfwDestroyWindow(window);
  }

  static State& of(GLFWwindow* w) { return *static_cast<State*>(glfwGetWindowUserPointer(w)); }

  static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods) {
    KeyEvent e;
    e.key = static_cast<Key>(key);
    e.scancode = scancode;
    e.action = key_action(action);
    e.shift = (mods & GLFW_MOD_SHIFT) != 0;
    e.control = (mods & GLFW_MOD_CONTROL) != 0;
    e.alt = (mods & GLFW_MOD_ALT) != 0;
    e.super = (mods & GLFW_MOD_SUPER) != 0;
    of(w).keys.push_back(e);
  }
  static void on_refresh(GLFWwindow* w) { of(w).redraw = true; }
  static void on_framebuffer_size(GLFWwindow* w, int, int) { of(w).redraw = true; }
};

WindowContext::WindowContext(const WindowOptions& window, const gl::ContextOptions& context,
                             const WindowContext* share) {
  if (context.gl_major < 3 || (context.gl_major == 3 && context.gl_minor < 2) || context.gl_minor < 0)
    throw std::invalid_argument(fmt::format("WindowContext: GL {}.{} requested: a core profile needs GL 3.2 or later",
                                            context.gl_major, context.gl_minor));
  if (window.width < 1 || window.height < 1)
    throw std::invalid_argument(
        fmt::format("WindowContext: window size {}x{}: width and height must be ≥ 1", window.width, window.height));

  auto state = std::make_unique<State>();
  state->library = acquire_glfw();

  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, context.gl_major);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, context.gl_minor);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, context.debug ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, window.resizable ? GLFW_TRUE : GLFW_FALSE);
  // A window to be placed is shown once it is where it belongs.
  glfwWindowHint(GLFW_VISIBLE, window.visible && !window.position ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_DECORATED, window.decorated && !window.fullscreen ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
  glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
  glfwWindowHint(GLFW_RED_BITS, 8);
  glfwWindowHint(GLFW_GREEN_BITS, 8);
  glfwWindowHint(GLFW_BLUE_BITS, 8);
  glfwWindowHint(GLFW_ALPHA_BITS, 8);
  glfwWindowHint(GLFW_DEPTH_BITS, 0);
  glfwWindowHint(GLFW_STENCIL_BITS, 0);

  // glfwCreateWindow makes the new context current for a moment (to read its
  // attributes): no EGL context may be current then.
  release_current_egl_context();
  GLFWmonitor* monitor = nullptr;
  int width = window.width, height = window.height;
  if (window.fullscreen) {
    int count = 0;
    GLFWmonitor** monitors = glfwGetMonitors(&count);
    if (window.monitor < 0 || window.monitor >= count)
      throw std::invalid_argument(
          fmt::format("WindowContext: fullscreen on monitor {}: the window system has {} monitor{}", window.monitor,
                      count, count == 1 ? "" : "s"));
    monitor = monitors[window.monitor];
    // The monitor's current mode: no mode switch (a projector keeps its timing).
    if (const GLFWvidmode* mode = glfwGetVideoMode(monitor)) {
      width = mode->width;
      height = mode->height;
      glfwWindowHint(GLFW_REFRESH_RATE, mode->refreshRate);
    }
    glfwWindowHint(GLFW_AUTO_ICONIFY, GLFW_FALSE);  // stays up when another window takes the focus
  }
  GLFWwindow* shared = share != nullptr && share->state_ ? share->state_->window : nullptr;
  state->window = glfwCreateWindow(width, height, window.title.c_str(), monitor, shared);
  if (state->window == nullptr)
    throw std::runtime_error(fmt::format("WindowContext: no {}x{} window with a GL {}.{} core context{}: {}",
                                         window.width, window.height, context.gl_major, context.gl_minor,
                                         context.debug ? " (debug)" : "", glfw_error()));
  glfwSetWindowUserPointer(state->window, state.get());
  glfwSetKeyCallback(state->window, &State::on_key);
  glfwSetWindowRefreshCallback(state->window, &State::on_refresh);
  glfwSetFramebufferSizeCallback(state->window, &State::on_framebuffer_size);

  if (!window.fullscreen && window.position) {
    glfwSetWindowPos(state->window, (*window.position)[0], (*window.position)[1]);
    if (window.visible) glfwShowWindow(state->window);
  }
  if (window.hide_cursor) glfwSetInputMode(state->window, GLFW_CURSOR, GLFW_CURSOR_HIDDEN);
  state->monitor = monitor;

  glfwMakeContextCurrent(state->window);
  glfwSwapInterval(window.swap_interval);

  GLint major = 0, minor = 0, profile = 0, flags = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  state->renderer = gl_string(GL_RENDERER);
  state->vendor = gl_string(GL_VENDOR);
  state->version = gl_string(GL_VERSION);
  state->glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
  if (major < context.gl_major || (major == context.gl_major && minor < context.gl_minor))
    throw std::runtime_error(fmt::format("WindowContext: got GL {}.{} from '{}', {}.{} was requested", major, minor,
                                         state->renderer, context.gl_major, context.gl_minor));
  if ((profile & GL_CONTEXT_CORE_PROFILE_BIT) == 0)
    throw std::runtime_error(fmt::format("WindowContext: '{}' gave no core profile context", state->renderer));
  state->gl_major = major;
  state->gl_minor = minor;
  state->debug = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
  state->software = gl::renderer_is_software(state->renderer);
  if (context.debug) gl::enable_debug_output();
  state_ = std::move(state);
}

WindowContext::~WindowContext() = default;
WindowContext::WindowContext(WindowContext&& other) noexcept = default;
WindowContext& WindowContext::operator=(WindowContext&& other) noexcept = default;

namespace {
[[noreturn]] void moved_from(const char* what) {
  throw std::logic_error(fmt::format("WindowContext::{} on a moved-from window", what));
}
}  // namespace

void WindowContext::make_current() const {
  if (!state_) moved_from("make_current");
  glfwGetError(nullptr);
  release_current_egl_context();
  glfwMakeContextCurrent(state_->window);
  if (glfwGetCurrentContext() != state_->window)
    throw std::runtime_error("WindowContext: glfwMakeContextCurrent failed: " + glfw_error());
}

void WindowContext::release_current() const {
  if (is_current()) glfwMakeContextCurrent(nullptr);
}

bool WindowContext::is_current() const { return state_ && glfwGetCurrentContext() == state_->window; }

const std::string& WindowContext::renderer() const {
  if (!state_) moved_from("renderer");
  return state_->renderer;
}
const std::string& WindowContext::vendor() const {
  if (!state_) moved_from("vendor");
  return state_->vendor;
}
const std::string& WindowContext::version() const {
  if (!state_) moved_from("version");
  return state_->version;
}
const std::string& WindowContext::glsl_version() const {
  if (!state_) moved_from("glsl_version");
  return state_->glsl_version;
}
int WindowContext::gl_major() const { return state_ ? state_->gl_major : 0; }
int WindowContext::gl_minor() const { return state_ ? state_->gl_minor : 0; }
bool WindowContext::debug() const { return state_ && state_->debug; }
bool WindowContext::is_software() const { return state_ && state_->software; }

FramebufferSize WindowContext::framebuffer_size() const {
  if (!state_) moved_from("framebuffer_size");
  FramebufferSize size;
  glfwGetFramebufferSize(state_->window, &size.width, &size.height);
  return size;
}

int WindowContext::refresh_hz() const {
  if (!state_) moved_from("refresh_hz");
  GLFWmonitor* monitor = state_->monitor != nullptr ? state_->monitor : glfwGetPrimaryMonitor();
  const GLFWvidmode* mode = monitor != nullptr ? glfwGetVideoMode(monitor) : nullptr;
  return mode != nullptr ? mode->refreshRate : 0;
}

bool WindowContext::should_close() const { return !state_ || glfwWindowShouldClose(state_->window) == GLFW_TRUE; }

void WindowContext::request_close() {
  if (state_) glfwSetWindowShouldClose(state_->window, GLFW_TRUE);
}

void WindowContext::set_title(const std::string& title) {
  if (!state_) moved_from("set_title");
  glfwSetWindowTitle(state_->window, title.c_str());
}

void WindowContext::poll_events() {
  if (!state_) moved_from("poll_events");
  glfwPollEvents();
}

void WindowContext::wait_events(double timeout_s) {
  if (!state_) moved_from("wait_events");
  if (timeout_s > 0.0)
    glfwWaitEventsTimeout(timeout_s);
  else
    glfwPollEvents();
}

GLFWwindow* WindowContext::glfw_window() const {
  if (!state_) moved_from("glfw_window");
  return state_->window;
}

void WindowContext::swap_buffers() {
  if (!state_) moved_from("swap_buffers");
  glfwSwapBuffers(state_->window);
}

std::vector<KeyEvent> WindowContext::take_key_events() {
  if (!state_) return {};
  return std::exchange(state_->keys, {});
}

bool WindowContext::take_redraw_request() { return state_ && std::exchange(state_->redraw, false); }

}  // namespace zenith::render::window
