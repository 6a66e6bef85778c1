#pragma once
// GL debug messages (KHR_debug, core since GL 4.3) routed to spdlog's default
// logger. HeadlessContext installs it for ContextOptions::debug = true.

namespace zenith::render::gl {

/// Enables GL_DEBUG_OUTPUT on the current context with a callback that logs each
/// message as "GL <type> [<source> #<id>]: <message>" at a level following its
/// severity: high → error, medium → warn, low → info, notification → debug.
/// `synchronous`: messages arrive inside the offending GL call (slower, but the
/// stack is the caller's). Needs a current context; the callback keeps no state.
void enable_debug_output(bool synchronous = true);

}  // namespace zenith::render::gl
