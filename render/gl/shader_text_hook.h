#pragma once
// The one seam through which a test program changes what the GPU compiles:
// extra #defines, the arithmetic of a driver whose fp64 sqrt is 1 ulp off, a
// stage that fails as a driver refuses it (tests/render/shader_faults.h).
// Production never installs a hook. It is a process-wide slot rather than an
// option because programs are built deep inside the precompute, the renderer
// and the display, and by the `zenith` commands that CLI tests start as child
// processes (tests/cli/zenith_with_shader_faults.cpp).
#include <functional>
#include <string>
#include <string_view>

namespace zenith::render::gl {

/// The final text of the shader stage `name` (includes expanded, #defines
/// injected) → the text to compile.
using ShaderTextHook = std::function<std::string(std::string_view name, std::string text)>;

/// Installs `hook` on every stage this process compiles from now on (empty:
/// none); returns the hook it replaces. Thread-safe.
ShaderTextHook install_shader_text_hook(ShaderTextHook hook);

/// `text` of the stage `name` as the installed hook makes it; unchanged without one.
std::string apply_shader_text_hook(std::string_view name, std::string text);

}  // namespace zenith::render::gl
