#pragma once
// A program's machine code generated on a second thread while the
// renderer's thread goes on.
//
// Mesa's llvmpipe generates a compute program's machine code at its first
// dispatch, on the dispatching thread, and keeps it in Mesa's shader cache
// keyed by the program and the shape of what is bound at that dispatch
// (each texture's and image's kind, format, filtering, wrap and
// power-of-two sizes). With that cache cold, a frame's first dispatches are
// mostly LLVM, one program after another on one core (docs/shows.md, "Where
// the start goes").
//
// FirstDispatchWarmup dispatches programs once each (or draws, for the
// display pass's fragment program) on a thread of its own,
// in a context that shares the renderer's objects, with stand-in textures,
// images and buffers shaped as the renderer will bind them
// (DispatchShapes): the code lands in Mesa's cache, and the renderer's own
// first dispatch of the program loads it from there. The renderer's thread
// meanwhile dispatches what it reaches first itself: a program's first
// dispatch there takes it off this queue, or waits while this thread is
// generating its code (ShaderProgram::set_before_first_dispatch), so no
// program is compiled twice and two cores compile at once.
//
// The same thread builds programs ahead of their first use (build()): Mesa
// 22.3 compiles and links GLSL in the calling thread whatever
// GL_KHR_parallel_shader_compile says, so a frame's programs built there
// leave the renderer's thread to its table uploads meanwhile
// (ProgramBuilds::build_on).
//
// Only where it helps (first_dispatch_warmup_worthwhile): llvmpipe with its
// shader cache on. A GPU driver compiles at link time (render/gl/program_builds.h).
#include <atomic>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <thread>
#include <utility>

#include "render/gl/shader_program.h"
#include "render/gl/texture.h"

namespace zenith::render::gl {

/// How the renderer's textures and images will be bound when it dispatches:
/// by unit and kind (a unit serves different kinds in different programs).
/// A unit a program uses that is not listed gets a single-level rgba32f
/// stand-in, linear and clamped, of power-of-two size.
struct DispatchShapes {
  using Slot = std::pair<int, TextureShape::Kind>;
  std::map<Slot, TextureShape> sampled;  ///< texture units (sampler2D, sampler2DArray, sampler3D)
  std::map<Slot, TextureShape> images;   ///< image units (image2D, image2DArray, image3D), format as declared
  bool operator==(const DispatchShapes&) const = default;
};

/// Whether first dispatches are worth warming on the current context's
/// driver: Mesa's llvmpipe with its shader cache on (MESA_SHADER_CACHE_DISABLE
/// unset or false).
bool first_dispatch_warmup_worthwhile();

class FirstDispatchWarmup {
 public:
  /// A warm-up where first_dispatch_warmup_worthwhile(), else null; also null,
  /// with one info line naming `who` and EGL's reason, where no shared
  /// context can be made (then every first dispatch compiles where it runs).
  static std::unique_ptr<FirstDispatchWarmup> if_worthwhile(const char* who);
  /// Needs a current EGL context (surfaceless), whose objects the thread's
  /// own context shares. Throws std::runtime_error where EGL gives none.
  FirstDispatchWarmup();
  /// Drops what is still queued and waits for the program in hand.
  ~FirstDispatchWarmup();
  FirstDispatchWarmup(const FirstDispatchWarmup&) = delete;
  FirstDispatchWarmup& operator=(const FirstDispatchWarmup&) = delete;

  /// Queues a dispatch of `program` (linked; it must outlive this object)
  /// with stand-ins shaped as `shapes`, and sets the program's
  /// before-first-dispatch hook. Programs are warmed in the order queued; the
  /// same program with the same shapes is queued once per warm-up.
  void warm(ShaderProgram& program, const DispatchShapes& shapes);
  /// The same for a graphics program drawn over a framebuffer of one
  /// `target`-format texture as TextureRowsDraw draws it (one triangle; no
  /// blending, depth, scissor or sRGB): the display pass's fragment code,
  /// which llvmpipe keys by the target's format as well.
  void warm_draw(ShaderProgram& program, const DispatchShapes& shapes, TextureFormat target);
  /// A build queued on the thread (build()).
  class QueuedBuild {
   public:
    /// The program, or what the build threw; std::future_error
    /// (broken_promise) where the build was dropped or taken back.
    std::future<ShaderProgram> program;
    /// Claims the build for the caller where the thread has not begun it:
    /// then it never will, and the caller, which would otherwise wait for
    /// it, builds the program itself. False: the thread has it.
    bool take_back() { return !begun_->exchange(true); }

   private:
    friend class FirstDispatchWarmup;
    std::shared_ptr<std::atomic<bool>> begun_ = std::make_shared<std::atomic<bool>>(false);
  };
  /// Runs `build` (a program's compile and link: ShaderBuild's start and
  /// finish) on the thread, before any first dispatch still queued; the
  /// program, or what `build` threw, comes back through the future, complete
  /// for every context (glFinish after the link). `build` must own what it
  /// reads. A build still queued when this object goes is dropped (the
  /// future then holds std::future_error, broken_promise).
  QueuedBuild build(std::function<ShaderProgram()> build);

  /// Whether the thread has nothing left to do: every program queued so far
  /// is warmed (or was taken back) and every build queued is done.
  bool idle() const;

  struct Statistics {
    int built = 0;         ///< programs built on the thread (build(); not those taken back)
    double build_s = 0.0;  ///< the thread, building
    int queued = 0;
    int warmed = 0;       ///< dispatched on the thread (their code in Mesa's cache)
    int taken_back = 0;   ///< dispatched by the renderer before the thread reached them
    int waited = 0;       ///< first dispatches that waited for the thread
    double wait_s = 0.0;  ///< the renderer's thread, waiting
    double warm_s = 0.0;  ///< the thread, dispatching
  };
  Statistics statistics() const;

 private:
  void queue(ShaderProgram& program, const DispatchShapes& shapes, std::optional<TextureFormat> draw_target);

  struct State;
  std::shared_ptr<State> state_;
  std::thread thread_;
};

}  // namespace zenith::render::gl
