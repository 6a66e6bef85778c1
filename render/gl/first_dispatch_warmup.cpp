#include "render/gl/first_dispatch_warmup.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/texture_rows_draw.h"

namespace zenith::render::gl {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Mesa's reading of a boolean variable (util/u_debug.c env_var_as_boolean):
/// "1", "true", "y", "yes" turn it on, whatever the case.
bool environment_says_yes(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr) return false;
  std::string v(value);
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return v == "1" || v == "true" || v == "y" || v == "yes";
}

GLenum target_of(TextureShape::Kind kind) {
  switch (kind) {
    case TextureShape::Kind::texture_2d: return GL_TEXTURE_2D;
    case TextureShape::Kind::texture_2d_array: return GL_TEXTURE_2D_ARRAY;
    case TextureShape::Kind::texture_3d: return GL_TEXTURE_3D;
  }
  return GL_TEXTURE_2D;
}

/// The kind a sampler or image uniform of GL type `type` binds; false for other uniforms.
bool kind_of_sampler(GLenum type, TextureShape::Kind& kind) {
  switch (type) {
    case GL_SAMPLER_2D: kind = TextureShape::Kind::texture_2d; return true;
    case GL_SAMPLER_2D_ARRAY: kind = TextureShape::Kind::texture_2d_array; return true;
    case GL_SAMPLER_3D: kind = TextureShape::Kind::texture_3d; return true;
    default: return false;
  }
}
bool kind_of_image(GLenum type, TextureShape::Kind& kind) {
  switch (type) {
    case GL_IMAGE_2D: kind = TextureShape::Kind::texture_2d; return true;
    case GL_IMAGE_2D_ARRAY: kind = TextureShape::Kind::texture_2d_array; return true;
    case GL_IMAGE_3D: kind = TextureShape::Kind::texture_3d; return true;
    default: return false;
  }
}

/// A stand-in size: 2 where the real one is a power of two, else 3 (what the
/// code depends on is only which it is).
int stand_in_size(int size) { return size > 0 && (size & (size - 1)) == 0 ? 2 : 3; }

struct Job {
  unsigned program = 0;
  std::string name;  // for the debug log
  DispatchShapes shapes;
  std::optional<TextureFormat> draw_target;  // a draw into a texture of this format; none: a dispatch
};

/// The stand-in textures and buffer of the thread's context, made on first need.
class StandIns {
 public:
  ~StandIns() {
    for (auto& [shape, id] : textures_) glDeleteTextures(1, &id);
    if (buffer_ != 0) glDeleteBuffers(1, &buffer_);
  }
  StandIns() = default;
  StandIns(const StandIns&) = delete;
  StandIns& operator=(const StandIns&) = delete;

  unsigned texture(const TextureShape& shape) {
    for (const auto& [s, id] : textures_)
      if (s == shape) return id;
    const int w = stand_in_size(shape.width), h = stand_in_size(shape.height), d = stand_in_size(shape.depth);
    const GLenum target = target_of(shape.kind);
    const int levels = shape.mipmapped ? 2 : 1;
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    if (shape.kind == TextureShape::Kind::texture_2d)
      glTextureStorage2D(id, levels, internal_format(shape.format), w, h);
    else
      glTextureStorage3D(id, levels, internal_format(shape.format), w, h, d);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, shape.mipmapped ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, shape.repeat_s ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    textures_.emplace_back(shape, id);
    return id;
  }

  /// A 2 × 2 texture of `format` to draw into, and the framebuffer and
  /// vertex array of this thread's context that draw it (TextureRowsDraw).
  struct DrawTarget {
    Texture texture;
    TextureRowsDraw draw;
  };
  DrawTarget& draw_target(TextureFormat format) {
    for (auto& [f, target] : draw_targets_)
      if (f == format) return target;
    return draw_targets_.emplace_back(format, DrawTarget{Texture::create_2d(format, 2, 2), {}}).second;
  }

  /// A zero-filled buffer for every uniform and storage block: what the
  /// stand-in dispatch reads there is never used.
  unsigned buffer(GLint64 at_least_bytes) {
    const GLint64 bytes = std::max<GLint64>(at_least_bytes, 64 * 1024);
    if (buffer_ != 0 && buffer_bytes_ >= bytes) return buffer_;
    if (buffer_ != 0) glDeleteBuffers(1, &buffer_);
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    const float zero = 0.0f;
    glClearNamedBufferData(buffer_, GL_R32F, GL_RED, GL_FLOAT, &zero);
    buffer_bytes_ = bytes;
    return buffer_;
  }

 private:
  std::vector<std::pair<TextureShape, GLuint>> textures_;
  GLuint buffer_ = 0;
  GLint64 buffer_bytes_ = 0;
  std::vector<std::pair<TextureFormat, DrawTarget>> draw_targets_;
};

/// Binds stand-ins for every texture, image and block `program` uses, and
/// dispatches one work group or draws one triangle into a 2 × 2 target (the
/// machine code is generated there).
void run_with_stand_ins(const Job& job, StandIns& stand_ins) {
  const GLuint program = job.program;
  GLint uniforms = 0;
  glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &uniforms);
  for (GLint i = 0; i < uniforms; ++i) {
    const GLenum properties[] = {GL_TYPE, GL_LOCATION, GL_ARRAY_SIZE};
    GLint values[3] = {0, -1, 1};
    glGetProgramResourceiv(program, GL_UNIFORM, static_cast<GLuint>(i), 3, properties, 3, nullptr, values);
    TextureShape::Kind kind{};
    const bool sampler = kind_of_sampler(static_cast<GLenum>(values[0]), kind);
    const bool image = !sampler && kind_of_image(static_cast<GLenum>(values[0]), kind);
    if ((!sampler && !image) || values[1] < 0) continue;
    for (GLint element = 0; element < values[2]; ++element) {
      GLint unit = 0;
      glGetUniformiv(program, values[1] + element, &unit);
      const auto& shapes = sampler ? job.shapes.sampled : job.shapes.images;
      TextureShape shape;
      shape.kind = kind;
      if (auto it = shapes.find({unit, kind}); it != shapes.end()) shape = it->second;
      const GLuint texture = stand_ins.texture(shape);
      if (sampler)
        glBindTextureUnit(static_cast<GLuint>(unit), texture);
      else
        glBindImageTexture(static_cast<GLuint>(unit), texture, 0,
                           kind == TextureShape::Kind::texture_2d ? GL_FALSE : GL_TRUE, 0, GL_READ_WRITE,
                           internal_format(shape.format));
    }
  }
  for (const GLenum block : {GL_UNIFORM_BLOCK, GL_SHADER_STORAGE_BLOCK}) {
    GLint blocks = 0;
    glGetProgramInterfaceiv(program, block, GL_ACTIVE_RESOURCES, &blocks);
    for (GLint i = 0; i < blocks; ++i) {
      const GLenum properties[] = {GL_BUFFER_BINDING, GL_BUFFER_DATA_SIZE};
      GLint values[2] = {0, 0};
      glGetProgramResourceiv(program, block, static_cast<GLuint>(i), 2, properties, 2, nullptr, values);
      glBindBufferBase(block == GL_UNIFORM_BLOCK ? GL_UNIFORM_BUFFER : GL_SHADER_STORAGE_BUFFER,
                       static_cast<GLuint>(values[0]), stand_ins.buffer(values[1]));
    }
  }
  if (job.draw_target) {
    StandIns::DrawTarget& target = stand_ins.draw_target(*job.draw_target);
    target.draw.bind(target.texture, 0, 2);
    glUseProgram(program);
    target.draw.draw_with_program_in_use();
    glUseProgram(0);
    target.draw.unbind();
    glFinish();
    return;
  }
  glUseProgram(program);
  glDispatchCompute(1, 1, 1);
  glFinish();
  glUseProgram(0);
}

/// A context sharing the objects of the one current on the constructing
/// thread, on the same display, bound to no surface.
struct SharedContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  SharedContext() {
    display = eglGetCurrentDisplay();
    const EGLContext share = eglGetCurrentContext();
    if (display == EGL_NO_DISPLAY || share == EGL_NO_CONTEXT)
      throw std::runtime_error("FirstDispatchWarmup: no EGL context is current");
    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    if (extensions == nullptr || std::string_view(extensions).find("EGL_KHR_surfaceless_context") == std::string::npos)
      throw std::runtime_error("FirstDispatchWarmup: the display has no EGL_KHR_surfaceless_context");
    EGLint config_id = 0;
    eglQueryContext(display, share, EGL_CONFIG_ID, &config_id);
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (config_id != 0) {
      const EGLint attributes[] = {EGL_CONFIG_ID, config_id, EGL_NONE};
      EGLint count = 0;
      if (eglChooseConfig(display, attributes, &config, 1, &count) != EGL_TRUE || count != 1)
        config = EGL_NO_CONFIG_KHR;
    }
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION_KHR,
                                 major,
                                 EGL_CONTEXT_MINOR_VERSION_KHR,
                                 minor,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
                                 EGL_NONE};
    context = eglCreateContext(display, config, share, attributes);
    if (context == EGL_NO_CONTEXT)
      throw std::runtime_error(fmt::format("FirstDispatchWarmup: eglCreateContext (shared) failed: 0x{:x}",
                                           static_cast<unsigned>(eglGetError())));
  }
  ~SharedContext() {
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
  }
  SharedContext(const SharedContext&) = delete;
  SharedContext& operator=(const SharedContext&) = delete;
};

}  // namespace

bool first_dispatch_warmup_worthwhile() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer != nullptr && std::string_view(renderer).find("llvmpipe") != std::string_view::npos &&
         !environment_says_yes("MESA_SHADER_CACHE_DISABLE") && !environment_says_yes("MESA_GLSL_CACHE_DISABLE");
}

struct FirstDispatchWarmup::State {
  SharedContext context;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Job> queue;
  std::deque<std::function<bool()>> builds;  // build(): before the queue's dispatches; false: taken back
  std::vector<Job> ever_queued;              // what warm() was given, for its one-time rule
  unsigned in_hand = 0;                      // the program the thread is dispatching; 0: none
  bool building = false;                     // the thread is running a build()
  bool stop = false;
  Statistics statistics;

  /// The renderer's first dispatch of `program`: off the queue if still
  /// there, or wait while the thread has it in hand.
  void before_first_dispatch(unsigned program) {
    std::unique_lock lock(mutex);
    const auto queued = std::find_if(queue.begin(), queue.end(), [&](const Job& j) { return j.program == program; });
    if (queued != queue.end()) {
      spdlog::debug("first dispatch of {} here, before the warm-up thread reached it", queued->name);
      queue.erase(queued);
      ++statistics.taken_back;
      return;
    }
    if (in_hand != program) return;
    const auto start = std::chrono::steady_clock::now();
    changed.wait(lock, [&] { return in_hand != program; });
    ++statistics.waited;
    statistics.wait_s += seconds_since(start);
    spdlog::debug("first dispatch of program {} waited {:.3f} s for the warm-up thread", program, seconds_since(start));
  }

  void run() {
    eglBindAPI(EGL_OPENGL_API);
    if (eglMakeCurrent(context.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context.context) != EGL_TRUE) {
      spdlog::warn("first dispatches not warmed: eglMakeCurrent on the warm-up thread failed (0x{:x})",
                   static_cast<unsigned>(eglGetError()));
      std::lock_guard lock(mutex);
      queue.clear();
      builds.clear();
      stop = true;
      return;
    }
    {
      StandIns stand_ins;
      std::unique_lock lock(mutex);
      while (true) {
        changed.wait(lock, [&] { return stop || !queue.empty() || !builds.empty(); });
        if (stop) break;
        if (!builds.empty()) {
          const std::function<bool()> build = std::move(builds.front());
          builds.pop_front();
          building = true;
          lock.unlock();
          const auto start = std::chrono::steady_clock::now();
          const bool built = build();
          const double seconds = seconds_since(start);
          lock.lock();
          building = false;
          if (built) {
            ++statistics.built;
            statistics.build_s += seconds;
          }
          changed.notify_all();
          continue;
        }
        const Job job = std::move(queue.front());
        queue.pop_front();
        in_hand = job.program;
        lock.unlock();
        const auto start = std::chrono::steady_clock::now();
        run_with_stand_ins(job, stand_ins);
        const double seconds = seconds_since(start);
        spdlog::debug("first dispatch of {} warmed on the warm-up thread: {:.3f} s", job.name, seconds);
        lock.lock();
        in_hand = 0;
        ++statistics.warmed;
        statistics.warm_s += seconds;
        changed.notify_all();
      }
    }
    eglMakeCurrent(context.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
};

std::unique_ptr<FirstDispatchWarmup> FirstDispatchWarmup::if_worthwhile(const char* who) {
  if (!first_dispatch_warmup_worthwhile()) return nullptr;
  try {
    return std::make_unique<FirstDispatchWarmup>();
  } catch (const std::runtime_error& e) {
    spdlog::info("{}: first dispatches not warmed: {}", who, e.what());
    return nullptr;
  }
}

FirstDispatchWarmup::FirstDispatchWarmup() : state_(std::make_shared<State>()) {
  thread_ = std::thread([state = state_] { state->run(); });
}

FirstDispatchWarmup::~FirstDispatchWarmup() {
  {
    std::lock_guard lock(state_->mutex);
    state_->stop = true;
    state_->queue.clear();
    state_->builds.clear();
  }
  state_->changed.notify_all();
  thread_.join();
}

FirstDispatchWarmup::QueuedBuild FirstDispatchWarmup::build(std::function<ShaderProgram()> build) {
  auto program = std::make_shared<std::promise<ShaderProgram>>();  // dropped unset: broken_promise
  QueuedBuild result;
  result.program = program->get_future();
  std::function<bool()> task = [build = std::move(build), program, begun = result.begun_] {
    if (begun->exchange(true)) return false;  // taken back: the caller builds it
    try {
      ShaderProgram built = build();
      glFinish();  // the link complete before the renderer's context uses the program
      program->set_value(std::move(built));
    } catch (...) {
      program->set_exception(std::current_exception());
    }
    return true;
  };
  {
    std::lock_guard lock(state_->mutex);
    if (state_->stop) return result;  // the task dropped: broken_promise
    state_->builds.push_back(std::move(task));
  }
  state_->changed.notify_all();
  return result;
}

void FirstDispatchWarmup::warm(ShaderProgram& program, const DispatchShapes& shapes) {
  queue(program, shapes, std::nullopt);
}

void FirstDispatchWarmup::warm_draw(ShaderProgram& program, const DispatchShapes& shapes, TextureFormat target) {
  queue(program, shapes, target);
}

void FirstDispatchWarmup::queue(ShaderProgram& program, const DispatchShapes& shapes,
                                std::optional<TextureFormat> draw_target) {
  const unsigned id = program.id();
  {
    std::lock_guard lock(state_->mutex);
    if (state_->stop) return;
    const auto same = [&](const Job& j) {
      return j.program == id && j.shapes == shapes && j.draw_target == draw_target;
    };
    if (std::any_of(state_->ever_queued.begin(), state_->ever_queued.end(), same)) return;
    state_->queue.push_back({id, program.name(), shapes, draw_target});
    state_->ever_queued.push_back(state_->queue.back());
    ++state_->statistics.queued;
  }
  state_->changed.notify_all();
  // The hook holds the state, not this object: a program may outlive the warm-up.
  program.set_before_first_dispatch([state = std::weak_ptr<State>(state_), id] {
    if (const auto s = state.lock()) s->before_first_dispatch(id);
  });
}

bool FirstDispatchWarmup::idle() const {
  std::lock_guard lock(state_->mutex);
  return state_->queue.empty() && state_->builds.empty() && !state_->building && state_->in_hand == 0;
}

FirstDispatchWarmup::Statistics FirstDispatchWarmup::statistics() const {
  std::lock_guard lock(state_->mutex);
  return state_->statistics;
}

}  // namespace zenith::render::gl
