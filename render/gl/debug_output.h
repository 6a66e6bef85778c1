#pragma once
// GL debug messages (KHR_debug, core since GL 4.3) routed to spdlog's default
// logger. HeadlessContext installs it for ContextOptions::debug = true, and
// for every context it makes when ZENITH_GL_DEBUG is set (not "0"): a support
// diagnostic, like ZENITH_SHADER_DUMP_DIR, for a machine in the field — with
// --log-level debug the driver's notifications show too (NVIDIA's say where
// each buffer lives: video or system memory).

namespace zenith::render::gl {

/// Enables GL_DEBUG_OUTPUT on the current context with a callback that logs each
/// message as "GL <type> [<source> #<id>]: <message>" at a level following its
/// severity: high → error, medium → warn, low → info, notification → debug.
/// `synchronous`: messages arrive inside the offending GL call (slower, but the
/// stack is the caller's). Needs a current context; the callback keeps no state.
void enable_debug_output(bool synchronous = true);

/// Whether ZENITH_GL_DEBUG asks for debug contexts (set, not empty, not "0").
bool debug_output_requested();

}  // namespace zenith::render::gl
