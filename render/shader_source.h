#pragma once
// GLSL sources compiled into the binary from shaders/ (see render/CMakeLists.txt),
// with `#include "file.glsl"` expanded at load time so common code is shared by
// several shaders.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace zenith::render {

/// The embedded text of `name`, a path under shaders/ ("render/gbuffer.comp",
/// "atmosphere_common.glsl"), as written: includes not expanded. Throws
/// std::out_of_range naming the shader when there is no such file.
std::string_view shader_source(std::string_view name);
/// Names of all embedded shaders, sorted.
std::vector<std::string> shader_names();

/// A shader's text with its includes expanded.
struct ExpandedShader {
  std::string name;  ///< the top-level file
  /// The GLSL to compile. Each included file is wrapped in `#line 1 <k>` …
  /// `#line <n> <parent>` directives, so compiler messages name the line within
  /// its own file and the file by its source-string number k: files[k].
  std::string text;
  std::vector<std::string> files;  ///< files[0] == name
};

/// Returns a file's text, or nothing when there is no such file.
using ShaderResolver = std::function<std::optional<std::string_view>(std::string_view name)>;

/// Expands every line `#include "path"` (optionally followed by a // comment) of
/// `source`. `path` is looked up relative to the including file's folder first,
/// then from the shader root. Each file is included once (later includes of it
/// expand to nothing); included files must not have a `#version` line.
/// Directives inside #if blocks are expanded regardless (no preprocessing here).
/// Throws std::runtime_error "<file>:<line>: ..." for a missing file, a cycle or
/// a malformed #include.
ExpandedShader expand_includes(std::string_view name, std::string_view source, const ShaderResolver& resolve);

/// expand_includes of an embedded shader, resolving includes among the embedded shaders.
ExpandedShader load_shader(std::string_view name);

}  // namespace zenith::render
