#pragma once
// Environment hooks on every shader stage that ShaderProgram compiles, for
// checks, tests and driver bug reports (docs/gpu-precompute.md, "What NVIDIA's
// compiler refuses"). None is set in normal use; each costs one getenv per stage.
//
//   ZENITH_SHADER_DUMP_DIR=DIR  writes each stage's final text, exactly as given to
//       glShaderSource (includes expanded, #defines injected), to
//       DIR/<name>.<first 16 hex digits of its SHA-256>.<comp|vert|frag>, and the
//       file names of its source-string numbers (ShaderCode::files, one a line)
//       beside it with ".files" appended. tests/render/glsl_nvidia_rules_test.cpp
//       parses every variant so written with glslangValidator.
//   ZENITH_SHADER_DEFINES=N=V,… defines N as V (or to nothing) in every stage,
//       after the #version line: test-only switches of the shaders, such as
//       ULP_PERTURBATION (atmosphere_common.glsl), reaching the programs that
//       the precompute and the renderer build.
//   ZENITH_FAIL_SHADER=NAME     the stage of the shader named NAME
//       ("transmittance.comp", "render/present.frag") fails to compile: an #error
//       line after its #version line. Tests use it to exercise what happens when a
//       driver refuses a program (the precompute's fallback to the CPU).
//   ZENITH_FAIL_SHADER_C5025=NAME  the stage of the shader named NAME fails to
//       compile with a message naming NVIDIA's C5025, unless its text carries
//       kNvidiaLoopUnrollOff: what NVIDIA's compiler does to a loop it cannot
//       unroll, so that the retry (ShaderBuild::finish) runs on any driver.
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/shader_program.h"

namespace zenith::render::gl {

/// `text` with the ZENITH_SHADER_DEFINES after its #version line, and an #error
/// line when ZENITH_FAIL_SHADER names `name`; `text` unchanged when neither is set.
/// Throws std::invalid_argument for a malformed ZENITH_SHADER_DEFINES.
std::string with_test_hooks(std::string_view name, std::string text);

/// Writes `text` (and `files`) under ZENITH_SHADER_DUMP_DIR when it is set;
/// a failure to write is logged, never thrown.
void dump_shader_source(std::string_view name, ShaderStage stage, std::string_view text,
                        const std::vector<std::string>& files);

}  // namespace zenith::render::gl
