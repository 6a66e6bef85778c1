#pragma once
// The engine's program factory: a shader from the embedded shaders/ files,
// includes expanded (render/shader_source.h), compiled by the generic GL
// wrapper (render/gl/shader_program.h) with the binding points and constants
// the C++ side shares with every shader (render/shader_bindings.h:
// shader_interface_defines()) defined before the caller's own defines.
//
// The wrapper itself knows no engine constant: it takes GLSL text and plain
// #defines. Every program of the renderer, the GPU precompute and the window
// path is made here; the tests' own shaders (tests/shaders/) come through the
// overloads taking an ExpandedShader.
#include <span>
#include <string_view>

#include "render/gl/program_builds.h"
#include "render/gl/shader_build.h"
#include "render/gl/shader_program.h"
#include "render/shader_source.h"

namespace zenith::render {

/// A compute program from the embedded shader `name` ("render/gbuffer.comp");
/// with `binaries`, taken from (and stored into) that program-binary cache
/// (render/gl/program_binary_cache.h).
gl::ShaderProgram load_compute_program(std::string_view name, std::span<const gl::ShaderDefine> defines = {},
                                       gl::ProgramBinaryCache* binaries = nullptr);
/// load_compute_program's build, started and not finished
/// (render/gl/shader_build.h: finish() where the program is first used).
gl::ShaderBuild start_compute_program(std::string_view name, std::span<const gl::ShaderDefine> defines = {},
                                      gl::ProgramBinaryCache* binaries = nullptr);
/// A vertex + fragment program from two embedded shaders.
gl::ShaderProgram load_graphics_program(std::string_view vertex_name, std::string_view fragment_name,
                                        std::span<const gl::ShaderDefine> defines = {});
/// load_graphics_program's build, started and not finished.
gl::ShaderBuild start_graphics_program(std::string_view vertex_name, std::string_view fragment_name,
                                       std::span<const gl::ShaderDefine> defines = {});
/// A compute program of `builds` (render/gl/program_builds.h), keyed by its
/// text: the embedded shader's name and every define, so that equal texts
/// are built once whoever asks. start_built_program starts it (the driver
/// compiles it on its threads while the caller starts others);
/// built_program finishes it, or builds it now; both through the builds'
/// binary cache where they have one (ProgramBuilds::set_binary_cache). Throws what
/// ShaderBuild::finish throws. `build_for`: see ProgramBuilds::start.
void start_built_program(gl::ProgramBuilds& builds, std::string_view name,
                         std::span<const gl::ShaderDefine> defines = {},
                         gl::BuildFor build_for = gl::BuildFor::this_frame);
const gl::ShaderProgram& built_program(gl::ProgramBuilds& builds, std::string_view name,
                                       std::span<const gl::ShaderDefine> defines = {});
/// Whether built_program would return the program at once (it is built).
bool program_built(const gl::ProgramBuilds& builds, std::string_view name,
                   std::span<const gl::ShaderDefine> defines = {});
/// A compute program from an already expanded shader (one resolved among
/// other files than the embedded ones, e.g. the tests' shaders), with the same
/// shared defines.
gl::ShaderProgram compute_program(const ExpandedShader& shader, std::span<const gl::ShaderDefine> defines = {},
                                  gl::ProgramBinaryCache* binaries = nullptr);

}  // namespace zenith::render
