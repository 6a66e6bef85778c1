#pragma once
// A program's build, started and finished apart, so that a caller who knows
// which programs it needs can hand them all to the driver at once and check
// each only where it is first used.
//
// With GL_KHR_parallel_shader_compile (or its ARB twin) and
// set_shader_compiler_threads(kAllCompilerThreads), glCompileShader and
// glLinkProgram return at once and the driver compiles on its own threads;
// asking for a status (GL_COMPILE_STATUS, GL_LINK_STATUS) waits for that
// build only. NVIDIA compiles a program when it is linked, 0.3–1.5 s each for
// the precompute's programs on an H100 (docs/gpu-precompute.md, "Program
// binary cache"), so a precompute that starts its 11 programs together waits
// for about the slowest instead of their sum. Without the extension the same
// calls run in order: glCompileShader compiles, and finish() only checks.
//
// finish() does what ShaderProgram::compute and ::graphics have always done:
// the driver's log annotated with the offending lines (file and line through
// ShaderCode::files), NVIDIA's C5025 retried with loop unrolling off
// (kNvidiaLoopUnrollOff; that retry builds at once, in the calling thread's
// turn), the program-binary cache read at start and written after a link.
#include <span>
#include <string>
#include <vector>

#include "render/gl/shader_program.h"

namespace zenith::render::gl {

class ProgramBinaryCache;

/// GL_MAX_SHADER_COMPILER_THREADS_KHR's "as many as the driver likes".
inline constexpr unsigned kAllCompilerThreads = 0xFFFFFFFFu;

/// Whether the current context offers GL_KHR_parallel_shader_compile or
/// GL_ARB_parallel_shader_compile.
bool has_parallel_shader_compile();
/// glMaxShaderCompilerThreadsKHR(threads) (or the ARB one): 0 compiles in the
/// calling thread, kAllCompilerThreads lets the driver choose. Returns false,
/// and does nothing, where neither extension is offered.
bool set_shader_compiler_threads(unsigned threads);

/// How a set of programs is built (render/gl/program_builds.h).
enum class CompileMode {
  parallel,  ///< builds started ahead, on the driver's compiler threads where it has them
  serial,    ///< each program built where first used, the driver told to compile in the calling thread
  contexts,  ///< builds started ahead, each on a thread with a context of its own (sharing the caller's
             ///< objects), all at once: for a driver whose own compiler threads overlap little
};
const char* to_string(CompileMode mode);

class ShaderBuild {
 public:
  /// Starts building a compute program: its text given to the driver,
  /// compiled and linked without asking for a status; with `binaries`, the
  /// program is given to glProgramBinary instead when the cache holds it.
  /// Throws only for a malformed define (std::invalid_argument) or a driver
  /// that cannot create a shader object; a compile or link error shows at finish().
  static ShaderBuild compute(const ShaderCode& code, std::span<const ShaderDefine> defines = {},
                             ProgramBinaryCache* binaries = nullptr);
  static ShaderBuild graphics(const ShaderCode& vertex, const ShaderCode& fragment,
                              std::span<const ShaderDefine> defines = {});

  ShaderBuild() = default;  ///< nothing started
  ~ShaderBuild();           ///< an unfinished build is abandoned (its GL objects deleted)
  ShaderBuild(ShaderBuild&& other) noexcept;
  ShaderBuild& operator=(ShaderBuild&& other) noexcept;
  ShaderBuild(const ShaderBuild&) = delete;
  ShaderBuild& operator=(const ShaderBuild&) = delete;

  /// Whether a build was started and not yet finished.
  bool started() const { return program_ != 0; }
  const std::string& name() const { return name_; }
  /// Whether finish() would return without waiting for the driver
  /// (GL_COMPLETION_STATUS_KHR; always true without the extension).
  bool ready() const;
  /// Waits for the build and returns the program, or throws ShaderBuildError
  /// with the message documented at ShaderProgram::compute. Once only.
  ShaderProgram finish();

 private:
  struct Stage {
    ShaderStage stage;
    std::string name;
    std::string text;  ///< as given to glShaderSource, for the annotated log
    std::vector<std::string> files;
    unsigned shader = 0;
  };
  static ShaderBuild start_compute(const ShaderCode& code, std::span<const ShaderDefine> defines, bool retrievable);
  void start_stage(ShaderStage stage, const ShaderCode& code);
  void start_link(bool retrievable);
  /// Throws ShaderBuildError for a stage that did not compile or a program
  /// that did not link; otherwise frees the stages.
  void check();
  ShaderProgram rebuild(const ShaderCode& code, bool rolled);
  void release() noexcept;

  std::string name_;
  bool compute_ = false;
  unsigned program_ = 0;
  std::vector<Stage> stages_;  ///< empty for a program given to glProgramBinary
  /// To compile again (the C5025 retry, a binary the driver refused).
  ShaderCode code_;
  std::vector<ShaderDefine> defines_;
  ProgramBinaryCache* binaries_ = nullptr;
  std::string key_;      ///< of the binary cache; empty without one
  bool rolled_ = false;  ///< already the C5025 retry (kNvidiaLoopUnrollOff)
};

}  // namespace zenith::render::gl
