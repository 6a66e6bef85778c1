#pragma once
// A set of programs by key, each built once: started ahead where the caller
// knows it will need them (all at the beginning of a precompute), finished
// where first used (render/gl/shader_build.h). With the driver's parallel
// compile (GL_KHR_parallel_shader_compile) the started builds run on its
// threads at once; in `serial` mode, or without the extension, one at a time.
//
// It counts what the builds cost the calling thread, for the debug log: how
// many programs, the time in the start calls (handing the texts to the driver;
// a driver without parallel compile compiles there) and in finish() (waiting
// for the driver's threads, checking, storing binaries), and how many builds
// were in flight at once. (llvmpipe generates a program's machine code at its
// first dispatch, which neither counts.)
//
// Where the driver compiles in the calling thread (Mesa 22.3's llvmpipe, whose
// GLSL front end and link run in glCompileShader and glLinkProgram despite
// the parallel-compile extension), build_on() moves the started builds to a
// thread with a context of its own: the caller goes on with other work (the
// renderer uploads its tables) while they compile. CompileMode::contexts
// builds each program on a thread and context of its own, all at once, for a
// driver whose compiler threads overlap little (NVIDIA's: docs/gpu-precompute.md).
#include <functional>
#include <future>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/shader_build.h"
#include "render/gl/shader_program.h"

namespace zenith::render::gl {

class ProgramBinaryCache;  // render/gl/program_binary_cache.h
struct DispatchShapes;

/// Which frame waits for a build: the one being drawn (its programs), or a
/// later one (a variant the renderer will switch to once it is built:
/// ProgramBuilds::finish_ahead).
enum class BuildFor { this_frame, a_later_frame };

class ProgramBuilds {
 public:
  /// Starts a program's build. With build_on, it runs on that thread, after
  /// start() has returned: it must own (capture by value) what it reads.
  using Starter = std::function<ShaderBuild()>;

  /// Sets the current context's compiler threads (kAllCompilerThreads in
  /// parallel mode, 0 in serial mode) where the driver has the extension;
  /// the destructor puts back what they were.
  explicit ProgramBuilds(CompileMode mode);
  ~ProgramBuilds();
  ProgramBuilds(const ProgramBuilds&) = delete;
  ProgramBuilds& operator=(const ProgramBuilds&) = delete;

  CompileMode mode() const { return mode_; }
  /// Where the programs' linked binaries are kept between runs (null: none,
  /// every program compiled); the caller's starters pass it to
  /// ShaderBuild::compute. The cache must outlive these builds.
  void set_binary_cache(ProgramBinaryCache* binaries) { binaries_ = binaries; }
  ProgramBinaryCache* binary_cache() const { return binaries_; }
  /// Builds started from now on are built on `thread` (its context shares
  /// this one's objects), started and finished there, and get() waits for
  /// them; null: in the calling thread. Serial mode builds where first used
  /// whatever this says. `thread` must outlive the builds started on it or
  /// be unset first.
  void build_on(FirstDispatchWarmup* thread) {
    build_on(thread ? std::vector{thread} : std::vector<FirstDispatchWarmup*>{});
  }
  /// The same on several threads, each build on the next in turn (with as
  /// many threads as builds, each its own: CompileMode::contexts).
  void build_on(std::vector<FirstDispatchWarmup*> threads) {
    threads_ = std::move(threads);
    next_thread_ = 0;
  }
  /// Starts building `key`'s program with `starter` unless it is already
  /// started or built; in serial mode does nothing (get builds it). Built for
  /// a later frame, warm_started leaves it to finish_ahead.
  void start(const std::string& key, const Starter& starter, BuildFor build_for = BuildFor::this_frame);
  /// `key`'s program: its started build finished now, or built now (started
  /// with `starter` and finished). Throws what ShaderBuild::finish throws; a
  /// program that failed is not kept, so asking again builds it again.
  const ShaderProgram& get(const std::string& key, const Starter& starter);
  /// Queues every program started since the last call (its build finished
  /// now where it was not) for a first dispatch on `warmup`'s thread with
  /// stand-ins shaped as `shapes`, but those already dispatched. `order`
  /// gives where each comes in the caller's dispatches (negative: not
  /// dispatched, not queued; equal: in the order started); the warm-up takes
  /// the last first, so that the caller's thread and its own work from
  /// opposite ends and rarely wait for each other.
  void warm_started(FirstDispatchWarmup& warmup, const DispatchShapes& shapes,
                    const std::function<int(const ShaderProgram&)>& order);
  /// Whether `key`'s program is built (get() returns it at once).
  bool built(const std::string& key) const { return programs_.contains(key); }
  /// Finishes every build started for a later frame whose program is ready,
  /// never waiting for one, and queues its first dispatch on `warmup` (where
  /// given) with stand-ins shaped as `shapes`. True once none is left.
  bool finish_ahead(FirstDispatchWarmup* warmup, const DispatchShapes& shapes);
  /// Queues the first dispatch of each of `programs` (built here) that was
  /// never dispatched on `warmup`, with stand-ins shaped as `shapes`.
  void warm(FirstDispatchWarmup& warmup, const DispatchShapes& shapes,
            const std::vector<const ShaderProgram*>& programs);
  /// Whether any program was started since the last warm_started.
  bool started_since_warm() const { return !started_.empty(); }

  struct Statistics {
    int built = 0;            ///< programs finished
    int built_on_thread = 0;  ///< of them, built on build_on's thread
    /// Of them, taken back from that thread before it began them and built
    /// here, where finishing would otherwise have waited.
    int built_while_waiting = 0;
    int built_ahead = 0;     ///< besides them, built for later frames (finish_ahead)
    int most_in_flight = 0;  ///< builds started and not yet finished, at most
    double start_s = 0.0;    ///< in the start calls (giving the texts to the driver)
    double wait_s = 0.0;     ///< in finish(): waiting for the driver, checking, storing binaries
    double seconds() const { return start_s + wait_s; }
  };
  const Statistics& statistics() const { return statistics_; }
  /// "11 programs, 2.310 s building them (0.120 s starting, 2.190 s waiting),
  /// at most 11 at once on the driver's compiler threads (parallel shader compile)"
  /// (or "…, 6 of them compiled on a second thread, one at a time, 3 here while waiting for it (…)"),
  /// and with a binary cache "; binaries: 11 of 11 loaded, 0 stored, 0 refused (DIR)".
  std::string summary() const;

 private:
  ShaderBuild timed_start(const Starter& starter);
  /// A build handed to build_on's thread, with its starter: built here
  /// instead where the thread dropped it (it went before reaching it, or its
  /// context could not be made current).
  struct OnThread {
    FirstDispatchWarmup::QueuedBuild queued;
    Starter starter;
  };
  using Pending = std::variant<ShaderBuild, OnThread>;
  /// The program of a started build: finished here, or waited for.
  ShaderProgram finish(Pending& build);
  /// Whether finishing `build` would not wait (its thread or the driver is done with it).
  static bool ready(const Pending& build);

  CompileMode mode_;
  bool driver_threads_ = false;  ///< the driver has the extension
  ProgramBinaryCache* binaries_ = nullptr;
  std::vector<FirstDispatchWarmup*> threads_;  // build_on
  std::size_t next_thread_ = 0;
  int previous_threads_ = 0;
  std::map<std::string, Pending, std::less<>> pending_;  // started, not yet finished
  std::vector<std::string> started_;                     // keys started since warm_started, in order
  std::vector<std::string> ahead_;                       // keys started for a later frame, not finished
  std::map<std::string, ShaderProgram, std::less<>> programs_;
  Statistics statistics_;
};

}  // namespace zenith::render::gl
