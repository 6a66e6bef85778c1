#include "render/render_flags.h"

#include "scene/frame_description.h"

namespace zenith::render {

std::uint32_t render_flags_of(const RenderOptions& o) {
  std::uint32_t flags = 0;
  if (o.sun_disc) flags |= scene::kRenderSunDisc;
  if (o.limb_darkening) flags |= scene::kRenderLimbDarkening;
  if (o.atmosphere.multiple_scattering) flags |= scene::kRenderMultipleScattering;
  if (o.atmosphere.eclipses) flags |= scene::kRenderEclipses;
  flags |= scene::kRenderBodies;  // bodies are always drawn
  return flags;
}

RenderOptions render_options_of(std::uint32_t flags) {
  RenderOptions o;
  o.sun_disc = (flags & scene::kRenderSunDisc) != 0;
  o.limb_darkening = (flags & scene::kRenderLimbDarkening) != 0;
  o.atmosphere.multiple_scattering = (flags & scene::kRenderMultipleScattering) != 0;
  o.atmosphere.eclipses = (flags & scene::kRenderEclipses) != 0;
  return o;
}

}  // namespace zenith::render
