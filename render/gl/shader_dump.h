#pragma once
// A support diagnostic for driver bug reports (docs/gpu-precompute.md, "What
// NVIDIA's compiler refuses"): with ZENITH_SHADER_DUMP_DIR=DIR set, each
// shader stage ShaderProgram compiles is written, exactly as given to
// glShaderSource (includes expanded, #defines injected), to
// DIR/<name>.<first 16 hex digits of its SHA-256>.<comp|vert|frag>, and the
// file names of its source-string numbers (ShaderCode::files, one a line)
// beside it with ".files" appended — what a driver vendor asks for, from a
// machine in the field without a rebuild. Unset in normal use; one getenv per
// stage. tests/render/glsl_nvidia_rules_test.cpp parses every variant so
// written with glslangValidator.
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/shader_program.h"

namespace zenith::render::gl {

/// Writes `text` (and `files`) under ZENITH_SHADER_DUMP_DIR when it is set;
/// a failure to write is logged, never thrown.
void dump_shader_source(std::string_view name, ShaderStage stage, std::string_view text,
                        const std::vector<std::string>& files);

}  // namespace zenith::render::gl
