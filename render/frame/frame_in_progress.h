#pragma once
// One frame in progress in the renderer (render/renderer.cpp): its constants
// in double on the CPU (render/frame/frame_constants.h), the projection's tile
// cones, the bodies and atmosphere passes, the uniforms every pass shares,
// the programs, and which programs have their frame and band uniforms set.
#include <array>
#include <cstddef>
#include <set>
#include <vector>

#include <glm/vec3.hpp>

#include "render/frame/frame_constants.h"
#include "render/frame/frame_programs.h"
#include "render/frame/frame_sky.h"
#include "render/frame/gpu_atmosphere.h"
#include "render/frame/gpu_body.h"
#include "render/frame/sun_refraction.h"
#include "render/frame/tile_classification.h"
#include "render/frame/tile_culling.h"
#include "render/gl/shader_program.h"
#include "scene/scene.h"
#include "warp/projection.h"

namespace zenith::render {

/// One atmosphere the frame draws: its body, where its shell is from the
/// camera, its tables on the GPU.
struct AtmospherePass {
  int body = 0;
  double distance_m = 0.0, top_radius_m = 0.0, power_m2 = 0.0;
  glm::dvec3 direction_camera{0.0};
  GpuAtmosphere* gpu = nullptr;
  bool sky_view = false;       // the camera is inside: the sky-view variant where it can
  bool sunlit = true;          // the sun lights it visibly this frame (render/frame/sun_light.h)
  bool moonlit = false;        // the Moon lights it this frame (render/night/moon_light.h)
  bool moon_sky_view = false;  // and the Moon's sky-view table is filled too
  bool eclipse_sky = false;    // the Moon's shadow lies on its air: the sun's one-pass tiles read the eclipse-sky table
  bool general_tiles = false;  // the sun's one-pass tiles draw with the general programs (RenderOptions::tile_programs)
};

/// A light of the atmosphere passes: the scene's sun, or the Moon
/// (render/night/moon_light.h). The tables are per unit irradiance of their
/// source, so a second source is the same passes with its direction and
/// irradiance, added to what the sun's passes drew.
struct FrameLight {
  enum class Source { sun, moon };
  Source source = Source::sun;
  glm::dvec3 direction{0.0, 0.0, 1.0};     ///< unit, world frame (geometric: the tables' rays are straight)
  double angular_radius_rad = 0.0;         ///< its disc: the fading at the horizon, the eclipses
  std::vector<double> irradiance_W_m2_nm;  ///< at the top of the atmosphere, per wavelength
  /// The disc's radiance at its centre per wavelength, for the passes that
  /// draw the disc; empty for the Moon, whose disc is the night sky's pass's.
  std::vector<double> centre_radiance_W_m2_sr_nm;

  bool is_sun() const { return source == Source::sun; }
  /// Its sky-view table among an atmosphere's (GpuAtmosphere::bind: 0 the sun's, 1 the Moon's).
  std::size_t sky_view_slot() const { return is_sun() ? 0 : 1; }
  /// Whether its passes draw `pass`'s atmosphere: the sun every one (its own
  /// test leaves some tiles unlit: render/frame/sun_light.h), the Moon those it lights.
  bool lights(const AtmospherePass& pass) const;
};

/// One frame in progress: its constants in double on the CPU, the bodies and
/// atmosphere passes, the uniforms every pass shares, the programs, and which
/// programs have their frame and band uniforms set.
struct FrameInProgress : FrameConstants {
  FrameInProgress(const scene::Scene& s, const warp::Projection& p) : scene(s), projection(p), sky(s) {}

  const scene::Scene& scene;
  const warp::Projection& projection;
  FrameSky sky;  // the sky clock's ephemeris, made once for the frame's readers

  // ---- the projection's tile cones (update_tile_cones)
  const TileCones* cones = nullptr;
  std::size_t tiles_total = 0;

  // ---- bodies and atmospheres (prepare_bodies)
  std::vector<GpuBody> bodies;
  std::vector<AtmospherePass> passes;
  // the bodies' shadows through their air (render/frame/air_shadows.h; their
  // values uploaded): frame.glsl's air_shadow_occluder[] and air_shadow_bodies[]
  std::vector<std::array<float, 4>> air_shadow_occluders;
  std::vector<std::array<int, 4>> air_shadow_bodies;

  // ---- uniforms shared by all passes and the programs (prepare_programs)
  std::array<float, 9> camera_matrix{};
  warp::GpuProjection gpu_projection;
  std::array<std::array<float, 3>, 3> world_ray{};
  FrameVariant variant;         // what the frame draws with
  FrameVariant wanted_variant;  // the leanest its scene allows (render/frame/live_variants.h)
  const FramePasses* programs = nullptr;
  double sun_reach = 0.0;  // where the sun can be drawn (prepare_programs)
  SunDiscLift sun_lift;    // the disc's refraction (refract_sun)

  // ---- every band's tiles (classify_bands): bands of band_rows rows
  int band_rows = 0;
  const std::vector<BandTiles>* bands = nullptr;

  // ---- the lights of the atmosphere passes, in the order they are drawn:
  // the sun, whose passes start the band's output, then the Moon where its
  // own test found it could show (render/night/moon_light.h), added
  std::vector<FrameLight> lights;
  /// The Moon among `lights`; null where it lights nothing this frame.
  const FrameLight* moon() const;

  // Frame uniforms on first use in the frame, band uniforms on first use in the band.
  std::set<const gl::ShaderProgram*> frame_ready, band_ready;
  std::array<int, 2> band_origin{0, 0}, band_size{0, 0};

  /// frame.glsl's the_body: body b's data as plain uniforms of a pass about it.
  void set_the_body(const gl::ShaderProgram& p, std::size_t b) const;

  /// The uniforms every pass of the frame shares: bodies, camera, sun, projection.
  void set_frame_uniforms(const gl::ShaderProgram& p) const;

  /// `p` with its frame uniforms (and exposure) set on its first use in the
  /// frame and its band uniforms on its first use in the band.
  const gl::ShaderProgram& prepare(const gl::ShaderProgram& p);

  /// Dispatches `p` over the tiles of `list` (prepared first).
  /// One work group per `tiles_per_group` tiles of `list` (the pass's TILES_PER_GROUP).
  void dispatch_tiles(const gl::ShaderProgram& p, TileList list, std::size_t tiles_per_group = 1);

  /// Per-group uniforms of the passes that turn a group's radiance into colour,
  /// and `light`'s (set_light_uniforms).
  void set_group_uniforms(const gl::ShaderProgram& p, std::size_t g, const FrameLight& light);
  /// `light`'s direction, angular radius, irradiance and disc radiance for group g
  /// (sun_direction, sun_angular_radius, sun_irradiance, sun_centre_radiance),
  /// the group (wavelength_group) and the air shadows it casts (the sun's only).
  void set_light_uniforms(const gl::ShaderProgram& p, std::size_t g, const FrameLight& light) const;
  /// The sun as the first light of the atmosphere passes.
  FrameLight sun_light() const;

  /// What the tiles of the frame can hold, for the classification of its bands
  /// (render/frame/frame_tiles.h); `sun_disc`, `one_pass_tiles`: RenderOptions'.
  TileScene tile_scene(bool sun_disc, bool one_pass_tiles) const;

  /// Whether an atmosphere's shell can touch any tile of the view.
  bool touches_view(const AtmospherePass& pass) const;
};

/// Lanes 4g..4g+3 of per-wavelength values (missing lanes 0), for a uniform of group g.
std::array<float, 4> group_lanes(const std::vector<double>& values, std::size_t group);
/// Column `channel` of per-wavelength RGB weights, lanes of group g.
std::array<float, 4> group_lanes(const std::vector<std::array<double, 3>>& weights, std::size_t channel,
                                 std::size_t group);

}  // namespace zenith::render
