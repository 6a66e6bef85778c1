#include "render/frame/frame_programs.h"

#include <utility>

#include "render/shader_programs.h"

namespace zenith::render {

FramePrograms::FramePrograms(bool sun_disc, bool limb_darkening)
    : sun_defines_{{"SUN_DISC", sun_disc ? "1" : "0"}, {"LIMB_DARKENING", limb_darkening ? "1" : "0"}},
      sun_disc_(sun_disc),
      limb_darkening_(limb_darkening) {}

std::vector<FramePrograms::Source> FramePrograms::sources(const FrameVariant& frame) const {
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
  std::vector<Source> s = {{"render/gbuffer.comp", no_eclipses.defines()},
                           {"render/resolve.comp", resolve_defines},
                           {"render/direct_light.comp", direct_defines(false, true)},
                           {"render/direct_light.comp", direct_defines(false, false)}};
  if (sun_disc_) s.push_back({"render/direct_light.comp", direct_defines(true, false)});
  if (zero_tiles_) s.push_back({"render/zero_tiles.comp", frame_defines});
  return s;
}

void FramePrograms::start(gl::ProgramBuilds& builds, const FrameVariant& frame, gl::BuildFor build_for) const {
  if (passes_.contains(frame.key())) return;
  for (const Source& s : sources(frame)) start_built_program(builds, s.file, s.defines, build_for);
}

bool FramePrograms::built(const gl::ProgramBuilds& builds, const FrameVariant& frame) const {
  if (passes_.contains(frame.key())) return true;
  for (const Source& s : sources(frame))
    if (!program_built(builds, s.file, s.defines)) return false;
  return true;
}

const FramePasses& FramePrograms::passes_for(gl::ProgramBuilds& builds, const FrameVariant& frame) {
  auto it = passes_.find(frame.key());
  if (it != passes_.end()) return it->second;
  // Started together (start()): a driver with parallel shader compile
  // (NVIDIA) builds them on its threads at once (render/gl/shader_build.h).
  start(builds, frame);
  const std::vector<Source> s = sources(frame);
  FramePasses p;
  p.gbuffer = &built_program(builds, s[0].file, s[0].defines);
  p.resolve = &built_program(builds, s[1].file, s[1].defines);
  p.direct_light_one = &built_program(builds, s[2].file, s[2].defines);
  p.direct_light = &built_program(builds, s[3].file, s[3].defines);
  if (sun_disc_) p.direct_light_sun = &built_program(builds, s[4].file, s[4].defines);
  if (zero_tiles_) p.zero_tiles = &built_program(builds, s.back().file, s.back().defines);
  return passes_.emplace(frame.key(), p).first->second;
}

}  // namespace zenith::render
