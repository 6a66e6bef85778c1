#pragma once
// A frame's render flags (scene::RenderFlag bits, scene/frame_description.h)
// and the renderer options they select. Shows, recordings and the cluster
// protocol carry the bits; the renderer takes the options.
#include <cstdint>

#include "render/renderer.h"

namespace zenith::render {

/// The bits for `options`: sun disc, limb darkening, multiple scattering,
/// eclipses, and kRenderBodies always (bodies are always drawn).
std::uint32_t render_flags_of(const RenderOptions& options);
/// Default RenderOptions with the features of `render_flags` switched on or off.
RenderOptions render_options_of(std::uint32_t render_flags);

}  // namespace zenith::render
