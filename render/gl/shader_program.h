#pragma once
// A linked GLSL program: one compute shader, or a vertex + fragment pair.
// Variants are made by injecting `#define NAME VALUE` lines after the #version
// line, so a shader can drop the terms a variant disables at compile time.
// Needs a current GL 4.5 context.
#include <array>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace zenith::render::gl {

class ProgramBinaryCache;
class ShaderBuild;

enum class ShaderStage { vertex, fragment, compute };
const char* to_string(ShaderStage stage);

/// `#define name value`; an empty value defines the name to nothing.
struct ShaderDefine {
  std::string name;   ///< a GLSL identifier, not starting with "GL_" and without "__"
  std::string value;  ///< one line
};

/// One stage's GLSL text. `files` names the source-string numbers used by #line
/// directives (files[0] is the shader itself; see render/shader_source.h's
/// ExpandedShader); empty means {name}.
struct ShaderCode {
  std::string name;  ///< for messages: "test_pattern.comp"
  std::string text;  ///< starts with a #version line (comments and blank lines may precede it)
  std::vector<std::string> files;
};

/// `text` with one `#define` line per define inserted right after its #version
/// line, followed by `#line <n> 0` so that later lines keep their numbers.
/// Throws std::invalid_argument when there is no #version line or a define is
/// not a valid identifier / has a multi-line value.
std::string inject_defines(std::string_view name, std::string_view text, std::span<const ShaderDefine> defines);

/// `text` with `lines` inserted right after its #version line, followed by
/// `#line <n> 0` so that later lines keep their numbers (inject_defines
/// inserts its #define lines this way). Throws std::invalid_argument naming
/// the shader when there is no #version line.
std::string insert_after_version(std::string_view name, std::string_view text, std::span<const std::string> lines);

/// A shader stage that did not compile or a program that did not link: what
/// ShaderProgram throws then (the message as documented at ShaderProgram::compute).
/// `program()` names the shader ("harmonic_density.comp") or the pair
/// ("render/present.vert + render/present.frag"), so that a caller can fall back
/// and say which one a driver refused.
class ShaderBuildError : public std::runtime_error {
 public:
  ShaderBuildError(std::string program, const std::string& message)
      : std::runtime_error(message), program_(std::move(program)) {}
  const std::string& program() const { return program_; }

 private:
  std::string program_;
};

/// NVIDIA's pragma that turns its GLSL compiler's loop unrolling off. Driver
/// 580.159.04 (an H200, 2026-11-26) fails to link some programs whose loops
/// it unrolls — harmonic_density.comp with 64 wavelengths or the fp32 model,
/// transmittance.comp with absorbers, test_shader_model.comp — with "error
/// C5025: lvalue in array access too complex"; with this pragma every one of
/// them probed (9 of 9) linked. Other compilers ignore pragmas they do not
/// know (GLSL 4.50, section 3.3).
inline constexpr std::string_view kNvidiaLoopUnrollOff = "#pragma optionNV(unroll none)";

/// Whether a compile or link message is that NVIDIA failure (its error code C5025).
bool is_nvidia_unroll_failure(std::string_view message);

class ShaderProgram {
 public:
  /// Compiles and links. On a compile or link failure throws ShaderBuildError:
  ///   shader 'broken.comp' (compute) failed to compile:
  ///   0:7(12): error: syntax error, unexpected ...
  ///       broken.comp:7 | float x = ;
  /// i.e. the shader name, the driver's info log and, under each message that
  /// names a line, that line of the source (source-string numbers resolved
  /// through ShaderCode::files).
  /// With `binaries`, a compute program is taken from that cache when it holds
  /// one for this driver and text, and stored there after it links
  /// (render/gl/program_binary_cache.h).
  /// Both are ShaderBuild's start and finish at once (render/gl/shader_build.h):
  /// a caller that builds several programs can start them all first.
  static ShaderProgram compute(const ShaderCode& code, std::span<const ShaderDefine> defines = {},
                               ProgramBinaryCache* binaries = nullptr);
  static ShaderProgram graphics(const ShaderCode& vertex, const ShaderCode& fragment,
                                std::span<const ShaderDefine> defines = {});

  ShaderProgram() = default;  ///< no program (id 0)
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  unsigned id() const { return id_; }
  const std::string& name() const { return name_; }
  void use() const;

  /// -1 when the program has no such active uniform (absent, or optimized out
  /// by a variant).
  int uniform_location(std::string_view uniform) const;
  /// Set a uniform without binding the program (glProgramUniform*). Return false,
  /// and do nothing, when the uniform is not active (e.g. a variant dropped it).
  bool set_uniform(std::string_view uniform, int value) const;
  bool set_uniform(std::string_view uniform, unsigned value) const;
  bool set_uniform(std::string_view uniform, float value) const;
  bool set_uniform(std::string_view uniform, const std::array<float, 2>& value) const;
  bool set_uniform(std::string_view uniform, const std::array<float, 3>& value) const;
  bool set_uniform(std::string_view uniform, const std::array<float, 4>& value) const;
  /// A mat3, column-major (m[0..2] the first column).
  bool set_uniform(std::string_view uniform, const std::array<float, 9>& value) const;
  bool set_uniform(std::string_view uniform, const std::array<int, 2>& value) const;
  bool set_uniform(std::string_view uniform, const std::array<int, 3>& value) const;
  bool set_uniform(std::string_view uniform, const std::array<int, 4>& value) const;

  /// Compute programs: the layout(local_size_x/y/z) of the shader.
  std::array<int, 3> work_group_size() const;
  /// Compute programs: use() and glDispatchCompute(x, y, z).
  void dispatch(unsigned groups_x, unsigned groups_y = 1, unsigned groups_z = 1) const;
  /// Compute programs: enough work groups to cover width × height × depth
  /// invocations (the shader discards those outside its domain).
  void dispatch_covering(int width, int height = 1, int depth = 1) const;
  /// Graphics programs: use() and glDrawArrays(GL_TRIANGLES, 0, vertices),
  /// with the caller's framebuffer and vertex array bound.
  void draw_triangles(int vertices) const;
  /// Runs `hook` once, just before this program's first dispatch or draw,
  /// then drops it: where another thread may be generating the program's
  /// machine code (render/gl/first_dispatch_warmup.h), the hook waits for it.
  void set_before_first_dispatch(std::function<void()> hook) { before_first_dispatch_ = std::move(hook); }
  /// Whether dispatch() or draw_triangles() has run.
  bool dispatched() const { return dispatched_; }

 private:
  friend class ShaderBuild;
  /// Takes `id`, a linked program (for a compute program, reads its work group size).
  ShaderProgram(unsigned id, std::string name, bool compute);
  void release() noexcept;

  unsigned id_ = 0;
  std::string name_;
  bool compute_ = false;
  std::array<int, 3> local_size_ = {0, 0, 0};
  mutable std::function<void()> before_first_dispatch_;  // set_before_first_dispatch
  mutable bool dispatched_ = false;
};

}  // namespace zenith::render::gl
