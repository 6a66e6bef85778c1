#include "render/frame/frame_programs.h"

#include <utility>

#include "render/shader_programs.h"

namespace zenith::render {

FramePrograms::FramePrograms(bool sun_disc, bool limb_darkening)
    : sun_defines_{{"SUN_DISC", sun_disc ? "1" : "0"}, {"LIMB_DARKENING", limb_darkening ? "1" : "0"}},
      sun_disc_(sun_disc),
      limb_darkening_(limb_darkening) {}

const FramePasses& FramePrograms::passes_for(const FrameVariant& frame) {
  auto it = passes_.find(frame.key());
  if (it != passes_.end()) return it->second;
  const std::vector<gl::ShaderDefine> frame_defines = frame.defines();
  std::vector<gl::ShaderDefine> resolve_defines = sun_defines_;
  resolve_defines.insert(resolve_defines.end(), frame_defines.begin(), frame_defines.end());
  auto direct_defines = [&](bool sun, bool one_body) {
    std::vector<gl::ShaderDefine> d = {{"SUN", sun ? "1" : "0"},
                                       {"ONE_BODY", one_body ? "1" : "0"},
                                       {"LIMB_DARKENING", limb_darkening_ ? "1" : "0"},
                                       {"TILES_PER_GROUP", std::to_string(kDirectLightTilesPerGroup)}};
    d.insert(d.end(), frame_defines.begin(), frame_defines.end());
    return d;
  };
  FrameVariant no_eclipses = frame;  // the G-buffer pass shades nothing
  no_eclipses.eclipses = false;
  const std::vector<gl::ShaderDefine> gbuffer_defines = no_eclipses.defines();
  // All five started before any is finished: a driver with parallel shader
  // compile (NVIDIA) builds them on its threads at once (render/gl/shader_build.h).
  gl::ShaderBuild gbuffer = start_compute_program("render/gbuffer.comp", gbuffer_defines);
  gl::ShaderBuild resolve = start_compute_program("render/resolve.comp", resolve_defines);
  gl::ShaderBuild direct_one = start_compute_program("render/direct_light.comp", direct_defines(false, true));
  gl::ShaderBuild direct = start_compute_program("render/direct_light.comp", direct_defines(false, false));
  gl::ShaderBuild direct_sun;
  if (sun_disc_) direct_sun = start_compute_program("render/direct_light.comp", direct_defines(true, false));
  FramePasses p;
  p.gbuffer = gbuffer.finish();
  p.resolve = resolve.finish();
  p.direct_light_one = direct_one.finish();
  p.direct_light = direct.finish();
  if (sun_disc_) p.direct_light_sun = direct_sun.finish();
  return passes_.emplace(frame.key(), std::move(p)).first->second;
}

}  // namespace zenith::render
