#include "render/gl/egl_context.h"

// No X11 types from <EGL/eglplatform.h>: this context never touches a window system.
#ifndef EGL_NO_X11
#define EGL_NO_X11
#endif
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "render/gl/debug_output.h"
#include "render/gl/software_rasterizer.h"

// EGL_EXT_device_query_name (newer than epoxy's registry copy).
#ifndef EGL_RENDERER_EXT
#define EGL_RENDERER_EXT 0x335F
#endif

namespace zenith::render::gl {

const char* to_string(DevicePreference preference) {
  switch (preference) {
    case DevicePreference::automatic: return "auto";
    case DevicePreference::software: return "software";
    case DevicePreference::hardware: return "hardware";
  }
  return "?";
}

DevicePreference parse_device_preference(std::string_view text) {
  if (text == "auto") return DevicePreference::automatic;
  if (text == "software") return DevicePreference::software;
  if (text == "hardware") return DevicePreference::hardware;
  throw std::invalid_argument(
      fmt::format("unknown GL device preference '{}': expected auto, software or hardware", text));
}

namespace {

const char* egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "unknown EGL error";
  }
}

/// "eglCreateContext failed: EGL_BAD_MATCH (0x3009)".
std::string egl_failure(const char* call) {
  const EGLint e = eglGetError();
  return fmt::format("{} failed: {} (0x{:04X})", call, egl_error_name(e), e);
}

/// Whether a space-separated extension string names `name` exactly.
bool has_extension(const char* extensions, std::string_view name) {
  if (extensions == nullptr) return false;
  std::string_view rest(extensions);
  while (!rest.empty()) {
    const std::size_t space = rest.find(' ');
    if (rest.substr(0, space) == name) return true;
    if (space == std::string_view::npos) break;
    rest.remove_prefix(space + 1);
  }
  return false;
}

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s != nullptr ? std::string(s) : std::string();
}

enum class DeviceKind { nvidia, other_gpu, software, unknown };

/// One way to obtain an EGLDisplay.
struct Candidate {
  std::string source;    // for messages and HeadlessContext::source()
  EGLenum platform = 0;  // 0: eglGetDisplay(EGL_DEFAULT_DISPLAY)
  void* native = nullptr;
  DeviceKind kind = DeviceKind::unknown;
};

/// What the client-side EGL library offers (EGL_NO_DISPLAY queries).
struct ClientEgl {
  bool platform_base = false, platform_device = false, device_enumeration = false, surfaceless = false,
       display_reference = false;
};

ClientEgl query_client() {
  ClientEgl c;
  const char* ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);  // needs EGL_EXT_client_extensions
  if (ext == nullptr) {
    eglGetError();  // EGL_BAD_DISPLAY without client extensions: not an error for us
    return c;
  }
  c.platform_base = has_extension(ext, "EGL_EXT_platform_base");
  c.platform_device = c.platform_base && has_extension(ext, "EGL_EXT_platform_device");
  c.device_enumeration = has_extension(ext, "EGL_EXT_device_enumeration") || has_extension(ext, "EGL_EXT_device_base");
  c.surfaceless = c.platform_base && has_extension(ext, "EGL_MESA_platform_surfaceless");
  c.display_reference = c.platform_base && has_extension(ext, "EGL_KHR_display_reference");
  return c;
}

/// The EGL devices, ranked NVIDIA, other GPUs, software, and filtered by `prefer`.
std::vector<Candidate> device_candidates(DevicePreference prefer, std::vector<std::string>& failures) {
  std::vector<Candidate> out;
  EGLint count = 0;
  if (eglQueryDevicesEXT(0, nullptr, &count) != EGL_TRUE) {
    failures.push_back("EGL_EXT_platform_device: " + egl_failure("eglQueryDevicesEXT"));
    return out;
  }
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(std::max(count, 0)));
  if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count) != EGL_TRUE) {
    failures.push_back("EGL_EXT_platform_device: " + egl_failure("eglQueryDevicesEXT"));
    return out;
  }
  devices.resize(static_cast<std::size_t>(std::max(count, 0)));
  if (devices.empty()) failures.push_back("EGL_EXT_platform_device: eglQueryDevicesEXT found no device");
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const char* ext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
    if (ext == nullptr) eglGetError();
    Candidate c;
    c.platform = EGL_PLATFORM_DEVICE_EXT;
    c.native = devices[i];
    std::string vendor, file;
    if (has_extension(ext, "EGL_EXT_device_query_name")) {
      if (const char* v = eglQueryDeviceStringEXT(devices[i], EGL_VENDOR)) vendor = v;
      if (const char* r = eglQueryDeviceStringEXT(devices[i], EGL_RENDERER_EXT); r != nullptr && *r != '\0')
        vendor += vendor.empty() ? std::string(r) : ", " + std::string(r);
    }
    if (has_extension(ext, "EGL_EXT_device_drm")) {
      if (const char* f = eglQueryDeviceStringEXT(devices[i], EGL_DRM_DEVICE_FILE_EXT)) file = f;
    }
    eglGetError();  // a string a device does not have is not a failure
    if (has_extension(ext, "EGL_MESA_device_software")) {
      c.kind = DeviceKind::software;
      if (vendor.empty()) vendor = "Mesa software";
    } else if (has_extension(ext, "EGL_NV_device_cuda") || vendor.find("NVIDIA") != std::string::npos) {
      c.kind = DeviceKind::nvidia;
      if (vendor.empty()) vendor = "NVIDIA";
    } else if (!file.empty() || has_extension(ext, "EGL_EXT_device_drm_render_node")) {
      c.kind = DeviceKind::other_gpu;
    }
    c.source = fmt::format("EGL device {} of {} ({}{}{})", i, devices.size(),
                           vendor.empty() ? "unknown vendor" : vendor, file.empty() ? "" : ", ", file);
    if ((prefer == DevicePreference::software && c.kind != DeviceKind::software) ||
        (prefer == DevicePreference::hardware && c.kind == DeviceKind::software)) {
      failures.push_back(fmt::format("{}: skipped, prefer={}", c.source, to_string(prefer)));
      continue;
    }
    out.push_back(std::move(c));
  }
  auto rank = [](DeviceKind k) {
    switch (k) {
      case DeviceKind::nvidia: return 0;
      case DeviceKind::other_gpu: return 1;
      case DeviceKind::unknown: return 2;
      case DeviceKind::software: return 3;
    }
    return 4;
  };
  std::stable_sort(out.begin(), out.end(),
                   [&](const Candidate& a, const Candidate& b) { return rank(a.kind) < rank(b.kind); });
  return out;
}

/// Everything one attempt created; released by `release` on failure.
struct Attempt {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
  bool terminate = false;
  bool current = false;

  void release() noexcept {
    if (display == EGL_NO_DISPLAY) return;
    if (current) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    // Without EGL_KHR_display_reference an EGLDisplay is shared by everything in the
    // process that opened the same device, so terminating it could destroy another
    // HeadlessContext's context: leave it initialized (EGL releases it at exit).
    if (terminate) eglTerminate(display);
    *this = Attempt{};
  }
};

/// Tries to create and make current a context on one candidate display; returns
/// the failure ("eglChooseConfig failed: ...") or nothing on success.
std::optional<std::string> try_candidate(const Candidate& candidate, const ClientEgl& client,
                                         const ContextOptions& options, Attempt& a) {
  if (candidate.platform == 0) {
    a.display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (a.display == EGL_NO_DISPLAY) return egl_failure("eglGetDisplay(EGL_DEFAULT_DISPLAY)");
  } else {
    std::vector<EGLint> attribs;
    if (client.display_reference) {
      attribs = {EGL_TRACK_REFERENCES_KHR, EGL_TRUE};
      a.terminate = true;
    }
    attribs.push_back(EGL_NONE);
    a.display = eglGetPlatformDisplayEXT(candidate.platform, candidate.native, attribs.data());
    if (a.display == EGL_NO_DISPLAY) {
      a.terminate = false;
      return egl_failure("eglGetPlatformDisplayEXT");
    }
  }
  EGLint major = 0, minor = 0;
  if (eglInitialize(a.display, &major, &minor) != EGL_TRUE) {
    const std::string failure = egl_failure("eglInitialize");
    a.terminate = false;
    a.display = EGL_NO_DISPLAY;
    return failure;
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) return egl_failure("eglBindAPI(EGL_OPENGL_API)");

  const char* ext = eglQueryString(a.display, EGL_EXTENSIONS);
  const bool egl15 = major > 1 || (major == 1 && minor >= 5);
  const bool create_context = egl15 || has_extension(ext, "EGL_KHR_create_context");
  if (!create_context)
    return fmt::format("EGL {}.{} without EGL_KHR_create_context cannot create a GL {}.{} core context", major, minor,
                       options.gl_major, options.gl_minor);
  const bool surfaceless = has_extension(ext, "EGL_KHR_surfaceless_context");
  const bool no_config =
      has_extension(ext, "EGL_KHR_no_config_context") || has_extension(ext, "EGL_MESA_configless_context");

  // Rendering goes to framebuffer objects: the config needs GL, and a pbuffer
  // only where the context cannot be surfaceless.
  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                   surfaceless ? 0 : EGL_PBUFFER_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (eglChooseConfig(a.display, config_attribs, &config, 1, &configs) != EGL_TRUE)
    return egl_failure("eglChooseConfig");
  if (configs == 0) {
    if (!(surfaceless && no_config))
      return std::string("eglChooseConfig: no config with EGL_OPENGL_BIT") +
             (surfaceless ? "" : " and EGL_PBUFFER_BIT");
    config = EGL_NO_CONFIG_KHR;
  }

  std::vector<EGLint> context_attribs = {EGL_CONTEXT_MAJOR_VERSION_KHR,       options.gl_major,
                                         EGL_CONTEXT_MINOR_VERSION_KHR,       options.gl_minor,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR};
  if (options.debug) {
    if (egl15)
      context_attribs.insert(context_attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
    else
      context_attribs.insert(context_attribs.end(), {EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR});
  }
  context_attribs.push_back(EGL_NONE);
  a.context = eglCreateContext(a.display, config, EGL_NO_CONTEXT, context_attribs.data());
  if (a.context == EGL_NO_CONTEXT)
    return egl_failure(fmt::format("eglCreateContext(GL {}.{} core{})", options.gl_major, options.gl_minor,
                                   options.debug ? ", debug" : "")
                           .c_str());

  if (!surfaceless) {
    const EGLint pbuffer_attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    a.surface = eglCreatePbufferSurface(a.display, config, pbuffer_attribs);
    if (a.surface == EGL_NO_SURFACE) return egl_failure("eglCreatePbufferSurface(1x1)");
  }
  if (eglMakeCurrent(a.display, a.surface, a.surface, a.context) != EGL_TRUE) return egl_failure("eglMakeCurrent");
  a.current = true;
  return std::nullopt;
}

}  // namespace

HeadlessContext::HeadlessContext(const ContextOptions& requested) {
  // ZENITH_GL_DEBUG: a debug context for a support log, its messages
  // asynchronous so that the frames keep their timing.
  const bool debug_from_environment = !requested.debug && debug_output_requested();
  ContextOptions options = requested;
  options.debug = requested.debug || debug_from_environment;
  default_software_rasterizer_threads();  // before any display exists: Mesa reads it then
  if (options.gl_major < 3 || (options.gl_major == 3 && options.gl_minor < 2) || options.gl_minor < 0)
    throw std::invalid_argument(fmt::format("HeadlessContext: GL {}.{} requested: a core profile needs GL 3.2 or later",
                                            options.gl_major, options.gl_minor));

  std::vector<std::string> failures;
  std::vector<Candidate> candidates;
  const ClientEgl client = query_client();
  if (client.platform_device && client.device_enumeration)
    candidates = device_candidates(options.prefer, failures);
  else
    failures.push_back("EGL_EXT_platform_device: not offered by the EGL client library");
  if (client.surfaceless)
    candidates.push_back(
        {"EGL_MESA_platform_surfaceless", EGL_PLATFORM_SURFACELESS_MESA, nullptr, DeviceKind::unknown});
  else
    failures.push_back("EGL_MESA_platform_surfaceless: not offered by the EGL client library");
  candidates.push_back({"default display", 0, nullptr, DeviceKind::unknown});

  for (const Candidate& candidate : candidates) {
    Attempt a;
    if (auto failure = try_candidate(candidate, client, options, a)) {
      failures.push_back(candidate.source + ": " + *failure);
      a.release();
      continue;
    }
    // Current: check what we got.
    GLint major = 0, minor = 0, profile = 0, flags = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    const std::string renderer = gl_string(GL_RENDERER);
    const bool software = candidate.kind == DeviceKind::software || renderer_is_software(renderer);
    std::string mismatch;
    if (major < options.gl_major || (major == options.gl_major && minor < options.gl_minor))
      mismatch = fmt::format("got GL {}.{} from '{}', {}.{} was requested", major, minor, renderer, options.gl_major,
                             options.gl_minor);
    else if ((profile & GL_CONTEXT_CORE_PROFILE_BIT) == 0)
      mismatch = fmt::format("'{}' gave no core profile context", renderer);
    else if (options.prefer == DevicePreference::hardware && software)
      mismatch = fmt::format("'{}' is a software rasterizer and prefer=hardware", renderer);
    else if (options.prefer == DevicePreference::software && !software)
      mismatch = fmt::format("'{}' is not a software rasterizer and prefer=software", renderer);
    if (!mismatch.empty()) {
      failures.push_back(candidate.source + ": " + mismatch);
      a.release();
      continue;
    }

    display_ = a.display;
    context_ = a.context;
    surface_ = a.surface == EGL_NO_SURFACE ? nullptr : a.surface;
    terminate_display_ = a.terminate;
    renderer_ = renderer;
    vendor_ = gl_string(GL_VENDOR);
    version_ = gl_string(GL_VERSION);
    glsl_version_ = gl_string(GL_SHADING_LANGUAGE_VERSION);
    source_ = candidate.source;
    if (const char* v = eglQueryString(a.display, EGL_VENDOR)) egl_vendor_ = v;
    if (const char* v = eglQueryString(a.display, EGL_VERSION)) egl_version_ = v;
    gl_major_ = major;
    gl_minor_ = minor;
    core_profile_ = true;
    debug_ = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
    software_ = software;
    if (options.debug) enable_debug_output(/*synchronous=*/!debug_from_environment);
    return;
  }

  std::string message =
      fmt::format("HeadlessContext: no EGL display gave a GL {}.{} core context (prefer={}):", options.gl_major,
                  options.gl_minor, to_string(options.prefer));
  for (const std::string& f : failures) message += "\n  " + f;
  throw std::runtime_error(message);
}

HeadlessContext::~HeadlessContext() { destroy(); }

HeadlessContext::HeadlessContext(HeadlessContext&& other) noexcept { *this = std::move(other); }

HeadlessContext& HeadlessContext::operator=(HeadlessContext&& other) noexcept {
  if (this == &other) return *this;
  destroy();
  display_ = std::exchange(other.display_, nullptr);
  context_ = std::exchange(other.context_, nullptr);
  surface_ = std::exchange(other.surface_, nullptr);
  terminate_display_ = std::exchange(other.terminate_display_, false);
  renderer_ = std::move(other.renderer_);
  vendor_ = std::move(other.vendor_);
  version_ = std::move(other.version_);
  glsl_version_ = std::move(other.glsl_version_);
  source_ = std::move(other.source_);
  egl_vendor_ = std::move(other.egl_vendor_);
  egl_version_ = std::move(other.egl_version_);
  gl_major_ = std::exchange(other.gl_major_, 0);
  gl_minor_ = std::exchange(other.gl_minor_, 0);
  core_profile_ = std::exchange(other.core_profile_, false);
  debug_ = std::exchange(other.debug_, false);
  software_ = std::exchange(other.software_, false);
  return *this;
}

void HeadlessContext::make_current() const {
  if (context_ == nullptr) throw std::logic_error("HeadlessContext::make_current on a moved-from context");
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) throw std::runtime_error(egl_failure("eglBindAPI(EGL_OPENGL_API)"));
  if (eglMakeCurrent(display_, surface_ != nullptr ? surface_ : EGL_NO_SURFACE,
                     surface_ != nullptr ? surface_ : EGL_NO_SURFACE, context_) != EGL_TRUE)
    throw std::runtime_error("HeadlessContext: " + egl_failure("eglMakeCurrent"));
}

bool HeadlessContext::is_current() const { return context_ != nullptr && eglGetCurrentContext() == context_; }

void HeadlessContext::destroy() noexcept {
  if (context_ == nullptr) return;
  Attempt a;
  a.display = display_;
  a.context = context_;
  a.surface = surface_ != nullptr ? surface_ : EGL_NO_SURFACE;
  a.terminate = terminate_display_;
  // Only release the calling thread's binding if it is this context; another
  // context current here stays current.
  a.current = eglGetCurrentContext() == context_;
  a.release();
  display_ = context_ = surface_ = nullptr;
  terminate_display_ = false;
}

}  // namespace zenith::render::gl
