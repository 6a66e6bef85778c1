#pragma once
// What tests make of the shader stages this process compiles, through the
// production seam render/gl/shader_text_hook.h: extra #defines, the arithmetic
// of a driver whose fp64 sqrt is not correctly rounded, a stage that a driver
// refuses, NVIDIA's C5025. Tests in-process install a ScopedShaderFaults;
// CLI tests run tests/cli/zenith_with_shader_faults, the zenith command line
// with the faults of its environment:
//
//   ZENITH_SHADER_DEFINES=N=V,…    #define N V (or nothing) in every stage
//   ZENITH_ULP_PERTURBATION=U      ShaderFaults::ulp_perturbation
//   ZENITH_FAIL_SHADER=NAME        ShaderFaults::fail_shader
//   ZENITH_FAIL_SHADER_C5025=NAME  ShaderFaults::fail_shader_c5025
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "render/gl/shader_program.h"
#include "render/gl/shader_text_hook.h"

namespace zenith::render::testing {

struct ShaderFaults {
  /// #defines after the #version line of every stage.
  std::vector<gl::ShaderDefine> defines;
  /// sqrt, exp_r and log_r of double this many ulps away from zero (toward
  /// zero when negative; 0: exact), in every stage that includes
  /// atmosphere/maths.glsl (tests/shaders/ulp_perturbation.glsl).
  int ulp_perturbation = 0;
  /// The stage of this name ("transmittance.comp", "render/present.frag")
  /// fails to compile: an #error line after its #version line, as a driver
  /// refusing it.
  std::string fail_shader;
  /// The stage of this name fails with a message naming NVIDIA's C5025 unless
  /// its text carries gl::kNvidiaLoopUnrollOff: what NVIDIA's compiler does
  /// to a loop it cannot unroll, so that the retry (ShaderBuild::finish) runs
  /// on any driver.
  std::string fail_shader_c5025;

  /// Only sqrt, exp_r and log_r `ulps` off.
  static ShaderFaults ulps_off(int ulps) {
    ShaderFaults f;
    f.ulp_perturbation = ulps;
    return f;
  }
  /// Only the stage `name` failing as NVIDIA's C5025.
  static ShaderFaults c5025_in(std::string name) {
    ShaderFaults f;
    f.fail_shader_c5025 = std::move(name);
    return f;
  }
};

/// The text of stage `name` with `faults`. Throws std::logic_error where a
/// perturbation is asked of a stage that includes maths.glsl without its
/// insertion point, and std::invalid_argument for a malformed define.
std::string with_shader_faults(const ShaderFaults& faults, std::string_view name, std::string text);

/// The faults the environment asks for (the variables above). Throws
/// std::invalid_argument naming the variable for a malformed value.
ShaderFaults shader_faults_from_environment();

/// `faults` on every stage compiled during the object's lifetime; the hook
/// installed before it back afterwards.
class ScopedShaderFaults {
 public:
  explicit ScopedShaderFaults(ShaderFaults faults);
  ~ScopedShaderFaults();
  ScopedShaderFaults(const ScopedShaderFaults&) = delete;
  ScopedShaderFaults& operator=(const ScopedShaderFaults&) = delete;

 private:
  gl::ShaderTextHook previous_;
};

}  // namespace zenith::render::testing
