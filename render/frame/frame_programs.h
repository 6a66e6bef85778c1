#pragma once
// The programs of a frame's own passes, those that are no atmosphere's
// (an atmosphere's are GpuAtmosphere's, render/frame/gpu_atmosphere.h):
// the G-buffer (shaders/render/gbuffer.comp), the resolve (resolve.comp) and
// the direct light of tiles no shell touches (direct_light.comp) and, on a
// GPU, the zeros of tiles the sun's pass leaves black (zero_tiles.comp), for
// the frame's variant (FrameVariant: projection kind, eclipses, albedo level).
// They live in the renderer's ProgramBuilds (render/gl/program_builds.h):
// start() hands them to the driver with the frame's other programs,
// passes_for() finishes them where the frame first uses them.
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "render/frame/gpu_atmosphere.h"
#include "render/gl/program_builds.h"
#include "render/gl/shader_program.h"

namespace zenith::render {

/// Tiles per work group of direct_light.comp (its local size is 16 × 16 × this,
/// 1024 invocations, the most GL guarantees). Its pixels are cheap, so llvmpipe's
/// cost per work group showed: the no-atmosphere ground view's frame took
/// 7.4–7.6 ms instead of 7.5–8.0 ms with one tile per group.
inline constexpr std::size_t kDirectLightTilesPerGroup = 4;

/// One variant's programs (owned by the ProgramBuilds they came from).
struct FramePasses {
  const gl::ShaderProgram *gbuffer = nullptr, *resolve = nullptr;
  // Tiles no atmosphere touches: bodies (one body: ONE_BODY = 1; several), and
  // the sun's tiles (SUN = 1; null without RenderOptions::sun_disc).
  const gl::ShaderProgram *direct_light_one = nullptr, *direct_light = nullptr, *direct_light_sun = nullptr;
  // The unlit tiles' zeros (zero_tiles.comp; null unless FramePrograms::set_zero_tiles(true)).
  const gl::ShaderProgram* zero_tiles = nullptr;
};

class FramePrograms {
 public:
  /// RenderOptions::sun_disc (no sun program without it) and limb_darkening.
  FramePrograms(bool sun_disc, bool limb_darkening);
  /// Whether each variant has zero_tiles.comp too (UnlitTileZeroing::compute_pass):
  /// set before the first start().
  void set_zero_tiles(bool zero_tiles) { zero_tiles_ = zero_tiles; }
  /// SUN_DISC and LIMB_DARKENING, the sun's defines: of the resolve here and of
  /// atmosphere_tile.comp (GpuAtmosphere), which draw the disc behind an atmosphere.
  const std::vector<gl::ShaderDefine>& sun_defines() const { return sun_defines_; }
  /// Starts building the programs of `frame`'s variant that are not built yet
  /// (for this frame, or a later one: ProgramBuilds::start).
  void start(gl::ProgramBuilds& builds, const FrameVariant& frame,
             gl::BuildFor build_for = gl::BuildFor::this_frame) const;
  /// Whether every program of `frame`'s variant is built.
  bool built(const gl::ProgramBuilds& builds, const FrameVariant& frame) const;
  /// The programs of `frame`'s variant, finished (or built) now where not yet. Needs a current GL context.
  const FramePasses& passes_for(gl::ProgramBuilds& builds, const FrameVariant& frame);

 private:
  struct Source {
    const char* file;
    std::vector<gl::ShaderDefine> defines;
  };
  /// gbuffer, resolve, direct light of one body, of several, of the sun (without
  /// the sun's disc: none), the unlit tiles' zeros (with set_zero_tiles(true)).
  std::vector<Source> sources(const FrameVariant& frame) const;

  std::map<std::string, FramePasses> passes_;  // by FrameVariant::key
  std::vector<gl::ShaderDefine> sun_defines_;
  bool sun_disc_ = true, limb_darkening_ = true, zero_tiles_ = false;
};

}  // namespace zenith::render
