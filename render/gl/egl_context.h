#pragma once
// A headless OpenGL context through EGL: no window, no display server. Runs on
// Mesa llvmpipe (CPU) and on NVIDIA's EGL where a GPU exists.
#include <string>
#include <string_view>

namespace zenith::render::gl {

/// Which kind of GL implementation HeadlessContext may pick.
enum class DevicePreference {
  automatic,  ///< a GPU if one works (NVIDIA first), else the Mesa software rasterizer
  software,   ///< the Mesa software rasterizer only (llvmpipe), even where a GPU exists
  hardware,   ///< a GPU only; fails where there is none
};
/// "auto", "software", "hardware".
const char* to_string(DevicePreference preference);
/// Parses "auto", "software", "hardware"; throws std::invalid_argument otherwise.
DevicePreference parse_device_preference(std::string_view text);

struct ContextOptions {
  int gl_major = 4;  ///< requested core-profile version, at least 3.2
  int gl_minor = 5;
  bool debug = false;  ///< debug context, messages routed to spdlog (gl/debug_output.h)
  DevicePreference prefer = DevicePreference::automatic;
};

/// An EGL display plus a core-profile GL context, current on the constructing
/// thread from construction until destruction. It tries, in order:
///  1. EGL_EXT_platform_device: every EGL device, NVIDIA first, other GPUs next,
///     the Mesa software device last (filtered by `prefer`);
///  2. EGL_MESA_platform_surfaceless;
///  3. the default display.
/// The context is surfaceless (EGL_KHR_surfaceless_context) where the display
/// allows it, else bound to a 1×1 pbuffer; render into framebuffer objects.
/// Throws std::runtime_error listing every attempt (the EGL call and its error
/// code) when none gives a context. Holds no global state: several contexts may
/// coexist (one current per thread).
class HeadlessContext {
 public:
  explicit HeadlessContext(const ContextOptions& options = {});
  ~HeadlessContext();
  HeadlessContext(HeadlessContext&& other) noexcept;
  HeadlessContext& operator=(HeadlessContext&& other) noexcept;
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// Makes the context current on the calling thread (e.g. after moving it to
  /// another thread, or after another context was made current). Throws on failure.
  void make_current() const;
  /// Whether this context is current on the calling thread.
  bool is_current() const;

  /// GL_RENDERER, GL_VENDOR, GL_VERSION, GL_SHADING_LANGUAGE_VERSION.
  const std::string& renderer() const { return renderer_; }
  const std::string& vendor() const { return vendor_; }
  const std::string& version() const { return version_; }
  const std::string& glsl_version() const { return glsl_version_; }
  /// The version the context actually has (GL_MAJOR_VERSION, GL_MINOR_VERSION).
  int gl_major() const { return gl_major_; }
  int gl_minor() const { return gl_minor_; }
  bool core_profile() const { return core_profile_; }
  bool debug() const { return debug_; }
  /// True for a CPU rasterizer (llvmpipe, softpipe, swrast).
  bool is_software() const { return software_; }
  /// How the display was obtained, e.g. "EGL device 1 (NVIDIA, /dev/dri/card0)",
  /// "EGL_MESA_platform_surfaceless", "default display".
  const std::string& source() const { return source_; }
  /// EGL_VENDOR and EGL_VERSION of the display.
  const std::string& egl_vendor() const { return egl_vendor_; }
  const std::string& egl_version() const { return egl_version_; }
  /// True when bound to no surface (EGL_KHR_surfaceless_context), false with a 1×1 pbuffer.
  bool surfaceless() const { return surface_ == nullptr; }

 private:
  void destroy() noexcept;

  // EGLDisplay, EGLContext, EGLSurface (kept opaque so this header needs no EGL headers).
  void* display_ = nullptr;
  void* context_ = nullptr;
  void* surface_ = nullptr;
  bool terminate_display_ = false;  // the display was opened with EGL_KHR_display_reference
  std::string renderer_, vendor_, version_, glsl_version_, source_, egl_vendor_, egl_version_;
  int gl_major_ = 0, gl_minor_ = 0;
  bool core_profile_ = false, debug_ = false, software_ = false;
};

}  // namespace zenith::render::gl
