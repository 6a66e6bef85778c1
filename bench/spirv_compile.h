#pragma once
// One program's build from GLSL and from SPIR-V on the current context's
// driver, timed (bench/startup_bench.cpp, part 3; docs/shows.md, "SPIR-V,
// measured"): what GL_ARB_gl_spirv would save a start where the driver's GLSL
// front end is on the critical path.
#include <filesystem>
#include <string>

namespace zenith::bench {

struct CompileTimes {
  double glsl_build_ms = 0.0;      ///< glCompileShader + glLinkProgram of the GLSL text
  double spirv_build_ms = 0.0;     ///< glShaderBinary + glSpecializeShaderARB + glLinkProgram
  double glsl_dispatch_ms = 0.0;   ///< the GLSL program's first dispatch (one work group, glFinish)
  double spirv_dispatch_ms = 0.0;  ///< the SPIR-V program's
};

/// Whether the current context offers GL_ARB_gl_spirv.
bool has_gl_spirv();

/// Builds the compute program of `glsl` (a text as given to glShaderSource)
/// and of `spirv` (the same made into SPIR-V for OpenGL), each `rounds`
/// times, alternating, and dispatches each build once: the median of each
/// time. Needs a current context with Mesa's shader cache off (else the
/// second round measures the cache). Throws std::runtime_error naming the
/// file where either does not build.
CompileTimes time_glsl_and_spirv(const std::filesystem::path& glsl, const std::filesystem::path& spirv, int rounds);

}  // namespace zenith::bench
