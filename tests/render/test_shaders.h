#pragma once
// The tests' own GLSL programs (tests/shaders/: test_pattern.comp,
// test_shader_model.comp, …), compiled into the test library
// zenith_test_shaders instead of the production zenith_render. They include
// production shaders (atmosphere_common.glsl, render/frame.glsl) by the same
// names as shaders/ files do: an include resolves among the test shaders
// first, then among the embedded shaders/ files.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/shader_program.h"
#include "render/shader_source.h"

namespace zenith::render::testing {

/// The text of tests/shaders/<name> as written. Throws std::out_of_range naming it.
std::string_view test_shader_source(std::string_view name);
/// Names of all test shaders, sorted.
std::vector<std::string> test_shader_names();
/// A test shader with its includes expanded (test shaders first, then shaders/).
ExpandedShader load_test_shader(std::string_view name);
/// load_test_shader compiled as a compute program by the engine's program
/// factory (render/shader_programs.h): the shared binding points and
/// constants, then `defines`. Needs a current GL context.
gl::ShaderProgram load_test_compute_program(std::string_view name, std::span<const gl::ShaderDefine> defines = {});

}  // namespace zenith::render::testing
