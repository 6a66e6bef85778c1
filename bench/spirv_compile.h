#pragma once
// One program's build from GLSL and from SPIR-V on the current context's
// driver, timed (bench/startup_bench.cpp, part 3; docs/shows.md, "SPIR-V,
// measured"): what GL_ARB_gl_spirv would save a start where the driver's GLSL
// front end is on the critical path.
#include <filesystem>
#include <string>

namespace zenith::bench {

struct CompileTimes {
  double glsl_build_ms = 0.0;         ///< glCompileShader + glLinkProgram of the GLSL text (median)
  double spirv_build_ms = 0.0;        ///< glShaderBinary + glSpecializeShaderARB + glLinkProgram (median)
  double glsl_dispatch_ms = 0.0;      ///< the GLSL program's first dispatch (one work group, glFinish); 0 if not asked
  double spirv_dispatch_ms = 0.0;     ///< the SPIR-V program's
  double glsl_first_build_ms = 0.0;   ///< the first round's GLSL build: the one no cache of the process has seen
  double spirv_first_build_ms = 0.0;  ///< the first round's SPIR-V build
};

/// Whether the current context offers GL_ARB_gl_spirv.
bool has_gl_spirv();

/// Builds the compute program of `glsl` (a text as given to glShaderSource)
/// and of `spirv` (the same made into SPIR-V for OpenGL), each `rounds`
/// times, alternating, and with `dispatch` dispatches each build once: the
/// median of each time, and the first round's builds. Each round's GLSL text
/// ends in a comment of its own, so that a driver keying its in-process cache
/// by the text compiles it again. Needs a current context with the driver's
/// disk cache off (Mesa's MESA_SHADER_CACHE_DISABLE, NVIDIA's
/// __GL_SHADER_DISK_CACHE=0; else later rounds measure the cache).
/// `dispatch` is for drivers that generate code at the first dispatch
/// (llvmpipe); it runs the program with nothing bound, which only a software
/// driver is sure to survive. Throws std::runtime_error naming the file where
/// either does not build.
CompileTimes time_glsl_and_spirv(const std::filesystem::path& glsl, const std::filesystem::path& spirv, int rounds,
                                 bool dispatch);

}  // namespace zenith::bench
