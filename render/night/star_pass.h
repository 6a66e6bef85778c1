#pragma once
// The night sky's pass (docs/night-sky.md, "Rendering the
// night sky"): after a band's atmosphere passes and before the band leaves the
// renderer (a file's readback, render_to_texture's copy, or the live display
// pass of render_on_gpu), the stars and the night sky's own light are added
// to the band's radiance, so they go through the same tone mapping and
// display response as the sky and are seen where the sky lets them be.
//
// Per frame, on the CPU (render/night/star_placement.h): every star's pixel,
// colour and extinction; the night floor's table (render/night/night_sky_table.h).
// Per band, on the GPU: star_splat.comp spreads the band's stars over 2 × 2
// pixels into a 64-bit fixed-point accumulator of a constant step (integer
// atomics with an explicit carry: the same sum in any order, the same counts
// for a star on every node; shaders/render/star_accumulator.glsl),
// night_sky.comp adds the accumulator and the night floor to the band's output.
//
// Skipped by its own tests (prepare()): the stars when the brightest pixel
// they can make, against the least the sky behind them can be (from the
// tables: render/night/star_visibility.h), would change no display value by
// half a code step of 8-bit sRGB; the night floor when its brightest direction
// would not against the least the sky can be (the stars' first-stage bound,
// darkest_sky; on a black sky, 1.5e-4 of linear, where that does not apply).
// Then neither the CPU placement
// nor a GPU pass runs: a daylight exposure, and a twilight sky bright enough to
// hide every star, cost nothing.
#include <cstddef>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "astro/light_pollution.h"
#include "astro/night_sky_floor.h"
#include "astro/refraction.h"
#include "render/frame/frame_in_progress.h"
#include "render/frame/pass_timer.h"
#include "render/frame/refraction_cache.h"
#include "render/frame/tile_classification.h"
#include "render/gl/buffer.h"
#include "render/gl/program_builds.h"
#include "render/gl/shader_program.h"
#include "render/gl/texture.h"
#include "render/gl/upload_stream.h"
#include "render/night/moon_albedo_map.h"
#include "render/night/night_sky_stats.h"
#include "render/night/star_placement.h"
#include "render/night/star_visibility.h"
#include "render/render_options.h"

namespace zenith::render {

class MoonInShadow;  // render/night/moon_in_shadow.h

/// Half an 8-bit sRGB code step at black as linear display value: 0.5 / 255 /
/// 12.92 (the sRGB curve's slope there); the tone curve's slope at 0 is 1.
inline constexpr double kInvisibleDisplayStep = 0.5 / 255.0 / 12.92;

/// The star accumulator (shaders/render/star_accumulator.glsl, which defines
/// the same numbers): counts per unit of exposed radiance (2²⁸, a constant of
/// the renderer: every node and band quantizes a star alike), the largest
/// exposed radiance a star adds to a pixel (the largest half float) and the
/// uints a pixel takes (r, g, b as low and high words, two padding).
inline constexpr double kStarCountsPerUnit = 268435456.0;
inline constexpr double kStarRadianceLimit = 65504.0;
inline constexpr std::size_t kStarAccumulatorUintsPerPixel = 8;

/// The frame star_splats places `scene`'s stars in (render/night/star_placement.h;
/// the scene has a sky clock): the sky clock's body's horizon at the camera;
/// the refraction of the site body's air (from `refractions`) and its
/// twinkling where the camera is inside that air; every body as an occluder;
/// the view's cone and the ground's dip as rejections — through `projection`
/// turned into the world by `camera_to_world`, the resident atmospheres
/// `atmospheres`, the colour weights `rgb_weights` and the scene's exposure.
/// The pass's own and render_bench --stars-placement's.
StarFrame star_frame(const scene::Scene& scene, const warp::Projection& projection, const glm::dmat3& camera_to_world,
                     std::vector<StarAtmosphere> atmospheres, const std::vector<std::array<double, 3>>& rgb_weights,
                     RefractionCache& refractions);

/// What a list of tiles of night_sky.comp holds: the program is compiled for
/// it (its NIGHT_* defines), since llvmpipe runs every branch a program has.
struct NightSkyVariant {
  bool floor = false;   ///< the night floor's table
  bool moon = false;    ///< the Moon's disc can be in the tiles
  bool bodies = false;  ///< a body can be in the tiles: the ray's nearest body decides what is sky
  int key() const { return int{floor} | int{moon} << 1 | int{bodies} << 2; }
  static NightSkyVariant from_key(int key) { return NightSkyVariant{(key & 1) != 0, (key & 2) != 0, (key & 4) != 0}; }
};

class NightSkyPass {
 public:
  /// `refractions` (shared with the Sun's disc) outlives the pass.
  NightSkyPass(const NightSkyRenderOptions& options, RefractionCache& refractions);
  ~NightSkyPass();
  NightSkyPass(const NightSkyPass&) = delete;
  NightSkyPass& operator=(const NightSkyPass&) = delete;

  /// The frame's CPU work (after the atmospheres are resident): whether there
  /// is anything to draw, the stars' splats, the night floor's table.
  /// `moon_shadow`: the Earth's shadow on the Moon this frame (a lunar eclipse,
  /// render/night/moon_in_shadow.h), or null; it outlives the frame's draw_band calls.
  void prepare(const FrameInProgress& frame, const MoonInShadow* moon_shadow, PassTimer& timer);
  /// Adds the stars and the floor to the band's output (bound at
  /// FRAME_RGB_BINDING); tiles nothing had drawn that now hold a star lose their
  /// black flag. Rebinds TILES_BINDING to its own list. Its programs come from
  /// `builds` (the frame's variant's, built now where they are not); the
  /// band's star and tile lists go through `uploads`.
  void draw_band(FrameInProgress& frame, gl::ProgramBuilds& builds, gl::UploadStream& uploads, BandTiles& band,
                 PassTimer& timer);

  /// The programs this pass has drawn with so far (each kind of tile its
  /// night_sky.comp, and star_pixels.comp), for the frame variant `variant`:
  /// started on `builds` for `build_for`, whether all are built, and the
  /// built ones (to warm their first dispatches). A live renderer switches to
  /// a leaner variant once these are built too (render/frame/live_variants.h),
  /// so that the switch builds nothing on the frame's thread.
  void start_programs(gl::ProgramBuilds& builds, const FrameVariant& variant, gl::BuildFor build_for) const;
  bool programs_built(const gl::ProgramBuilds& builds, const FrameVariant& variant) const;
  void add_programs(gl::ProgramBuilds& builds, const FrameVariant& variant,
                    std::vector<const gl::ShaderProgram*>& programs) const;

  const NightSkyStats& stats() const { return stats_; }

 private:
  bool ensure_field(const scene::Scene& scene);
  NightSkyRenderOptions options_;
  NightSkyStats stats_;
  bool catalogue_failed_ = false;
  std::unique_ptr<StarField> field_;
  std::vector<glm::dvec3> directions_;
  std::vector<StarSplat> splats_;
  // The Moon's disc (when larger than a pixel): direction, angular radius, and
  // the linear sRGB × exposure of its full-phase radiance at normal incidence
  // and emission (μ0 = μ = 1: 2 L_LS(1, 1)) through the line of sight.
  bool moon_disc_ = false;
  glm::dvec3 moon_direction_{0, 0, 1};
  double moon_radius_rad_ = 0.0, moon_radius_px_ = 0.0;
  glm::dvec2 moon_pixel_{0.0};
  std::array<double, 3> moon_rgb_{};
  /// In a lunar eclipse: the disc's linear sRGB × exposure (moon_rgb_ times the
  /// sunlight left, render/night/moon_in_shadow.h) at kMoonShadowEntries
  /// distances from the shadow's axis over [0, its reach]; empty otherwise.
  static constexpr int kMoonShadowEntries = 256;
  std::vector<std::array<float, 4>> moon_shadow_table_;
  const MoonInShadow* moon_shadow_ = nullptr;  // this frame's (prepare)
  /// The Moon at the frame's sky time: a disc, a star-like point, or nothing.
  void place_moon(const FrameInProgress& frame, const StarFrame& sky);
  // The Moon's face (render/night/moon_albedo_map.h): the map (loaded with the
  // first disc, the uniform one when missing), its texture (uploaded once), the
  // disc's body axes in the world and the texture's level.
  std::unique_ptr<MoonAlbedoMap> moon_map_;
  gl::Texture moon_texture_;
  MoonWorldAxes moon_axes_{};
  double moon_map_lod_ = 0.0;
  const MoonAlbedoMap& moon_map();
  // The night floor: its table and the frame's up and horizon.
  bool floor_ = false;
  std::vector<std::array<float, 4>> floor_table_;
  glm::dvec3 floor_up_{0, 0, 1};
  double floor_horizon_mu_ = 0.0;
  // Cached per atmosphere and options.
  RefractionCache& refractions_;
  std::string floor_key_;
  std::unique_ptr<astro::NightSkyFloor> night_floor_;
  std::unique_ptr<astro::LightPollution> light_pollution_;
  // GL objects.
  gl::ShaderProgram splat_;
  // The kinds of tile (NightSkyVariant keys) drawn so far, and whether stars were.
  std::set<int> kinds_drawn_;
  bool star_pixels_drawn_ = false;
  gl::Buffer accumulator_;
  // The band's pixels its splats reach, each once, and a flag per band pixel to list them once (all 0 between bands).
  std::vector<std::uint32_t> star_pixels_;
  std::vector<std::uint8_t> pixel_listed_;
  std::size_t accumulator_bytes_ = 0;
};

}  // namespace zenith::render
