#pragma once
// The renderer: scenes of analytic planets with precomputed atmospheres, seen
// through any projection (paper section 5.2, Algorithm 1). Per frame and band,
// the 16×16 tiles are sorted by what can be in them (render/frame/tile_culling.h)
// and each kind is drawn by its own pass straight into the band's RGB output
// (render/band/band_passes.h; docs/rendering-performance.md):
//
//   - no atmosphere (shaders/render/direct_light.comp): bodies lit by the sun,
//     the sun's disc, every wavelength at once; tiles with neither are not
//     dispatched (black);
//   - exactly one atmosphere's shell (atmosphere_tile.comp), per group of 4
//     wavelengths: ray, nearest body, the atmosphere's in-scattering and
//     transmittance, what lies behind it. A camera inside the shell reads a
//     per-frame sky-view table (render/frame/sky_view_table.h) filled once from
//     the 4D tables, except where another body inside the shell can be; other
//     cameras (space, the limb) read the 4D tables per pixel;
//   - two or more shells, composited front to back: the G-buffer path — body
//     pass (gbuffer.comp: nearest sphere, albedo → G-buffer), per group one pass
//     per atmosphere front to back (atmosphere_pass.comp: running radiance and
//     transmittance) and resolve.comp (airless surfaces, the sun's disc, colour);
//   - where the Moon could light the sky visibly (render/night/moon_light.h),
//     the atmosphere tiles again with the Moon as the light, added;
//   - where the sun could not (render/frame/sun_light.h: far below the
//     horizon), an atmosphere's one-pass tiles of sky and ground are left at
//     zero (the band's output cleared first) instead of drawn by the sun's pass;
//
// then the night sky's pass (render/night/star_pass.h: the catalogue's stars as
// point sources of flux, the night floor, light pollution) adds its light to
// the band's radiance, skipped by its own test where nothing would show;
// then the band is read back and its rows handed to the caller (EXR/PNG writers
// stream them), or left on the GPU (render/band/band_resources.h holds the
// band's buffers and images from frame to frame).
//
// Large frames are rendered in horizontal bands of at most
// RenderOptions::max_band_pixels so GPU memory stays bounded (8K dome masters).
// Needs a current GL 4.5 context (gl::HeadlessContext or a window).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "atmosphere/lut/lookup_tables.h"
#include "image/image_io.h"
#include "render/band/gpu_band.h"
#include "render/night/night_sky_stats.h"
#include "render/render_options.h"
#include "scene/scene.h"
#include "warp/projection.h"

namespace zenith::render {

class PassTimer;        // render/frame/pass_timer.h
struct BandTiles;       // render/frame/tile_classification.h
struct AtmospherePass;  // render/frame/frame_in_progress.h
class MoonInShadow;     // render/night/moon_in_shadow.h
struct FrameVariant;    // render/frame/gpu_atmosphere.h
enum class BandReader;  // render/band/band_resources.h
namespace gl {
class Texture;              // render/gl/texture.h
struct DispatchShapes;      // render/gl/first_dispatch_warmup.h
class FirstDispatchWarmup;  // render/gl/first_dispatch_warmup.h
class ShaderProgram;        // render/gl/shader_program.h
enum class BuildFor;        // render/gl/program_builds.h
}  // namespace gl

/// Tables for an atmosphere model (e.g. from the cache, else precomputed):
/// called only for table sets the renderer does not hold yet.
using TableSource = std::function<atmosphere::lut::LookupTables(const atmosphere::AtmosphereModel&)>;
/// Where a renderer gets a body's albedo map the first time a frame needs it
/// (Renderer::set_albedo_source); the same contract as scene::load_albedo_map.
using AlbedoMapSource = std::function<image::LinearImage(const scene::AlbedoSource&)>;

/// Receives finished rows, top first: `row_count` rows from `first_row`, linear
/// sRGB radiance × exposure, 3 floats per pixel, x fastest.
using RowSink = std::function<void(int first_row, int row_count, std::span<const float> rgb)>;

/// Called once per band (render/band/gpu_band.h) while its buffers are bound: draws what it needs from them.
using GpuBandSink = std::function<void(const GpuBand& band)>;

/// Queues the first use of the caller's own programs on the renderer's
/// warm-up thread (Renderer::set_band_sink_warmup).
using WarmupQueue = std::function<void(gl::FirstDispatchWarmup& warmup)>;

/// What the last frame did, for logs, tests and benchmarks.
struct FrameStats {
  struct Atmosphere {
    std::string body;
    std::size_t tiles = 0;           ///< tiles its shell can touch (all bands)
    std::size_t sky_view_tiles = 0;  ///< of those, the one-pass tiles read from its sky-view table
    std::size_t gbuffer_tiles = 0;   ///< of those, the tiles of the G-buffer path (shells overlap)
    std::size_t tiles_total = 0;     ///< tiles in the frame
  };
  std::vector<Atmosphere> atmospheres;  ///< in the order the passes ran
  int table_sets_requested = 0;         ///< TableSource calls during the frame
  int table_sets_uploaded = 0;
  int bands = 0;
  std::size_t tiles_gbuffer = 0;         ///< tiles of the G-buffer path (two or more shells; all bands)
  std::size_t tiles_one_atmosphere = 0;  ///< tiles one shell touches, drawn by atmosphere_tile.comp
  std::size_t tiles_direct = 0;          ///< tiles drawn by direct_light.comp (a body or the sun, no atmosphere)
  std::size_t tiles_black = 0;           ///< tiles with nothing to draw: not dispatched
  /// The tiles were the frame before's (nothing they depend on moved:
  /// render/frame/frame_tiles.h); the counts above are the same.
  bool tiles_reused = false;
  /// Drawn with the program variant in use while the leaner one its scene
  /// allows builds on a second thread (RenderOptions::background_variant_builds).
  bool variant_held = false;
  /// Atmospheres whose one-pass tiles drew with their general program while
  /// their kinds' own programs build (RenderOptions::tile_programs).
  int general_tile_atmospheres = 0;
  double seconds = 0.0;  ///< wall time of render(), readback included
  /// Of `seconds`: obtaining and uploading table sets (the TableSource's
  /// calls and the upload: the first frame with a set), and building programs
  /// (the first frame of a variant), with how many were built.
  double tables_s = 0.0, programs_s = 0.0;
  int programs_built = 0;
  /// Of those, the programs made from a stored binary (RenderOptions::program_cache_directory).
  int programs_from_binaries = 0;
  /// Of those, the programs handed to the warm-up thread for their first
  /// dispatch (RenderOptions::warm_first_dispatches).
  int programs_warmed = 0;
  /// Of `seconds`: the bodies' albedo maps read or generated (the first
  /// frame with a map; scene/albedo_map_cache.h) and uploaded.
  double albedo_s = 0.0;
  /// Of `seconds`: the Moon's shadow on an atmosphere in a solar eclipse
  /// (render/frame/eclipse_sky_table.h): its tables' first request, following
  /// it, building a new one; how many were built and uploaded (0 where the
  /// one held still fit or a new one is still being built on a worker thread).
  double moon_shadow_s = 0.0;
  int moon_shadows_built = 0;
  /// An atmosphere's sky read the eclipse-sky table (the Moon's shadow on its air).
  bool eclipse_sky = false;
  /// Sky-view tables filled (one per atmosphere and light): none where each
  /// held this frame's camera and light already (an output of the same frame
  /// before this one, a still sky; render/frame/sky_view_table.h).
  int sky_view_tables_filled = 0;
  /// The night sky's pass (render/night/star_pass.h): whether it drew, its
  /// stars, the floor, the Moon's disc and the stars' own test.
  NightSkyStats night_sky;
  /// The Moon lit the atmospheres (render/night/moon_light.h): false where its
  /// own test found nothing it could show (daylight, the Moon far below the horizon).
  bool moonlight = false;
  /// The test's bound: the largest linear display value the Moon's light could
  /// add through one atmosphere (the largest over them; 0 without a Moon).
  double moonlight_bound = 0.0;
  /// The sun's light of the atmospheres (render/frame/sun_light.h): the
  /// largest linear display value it could add through one of them, and
  /// whether the test zeroed some atmosphere's sky-and-ground tiles instead of
  /// drawing the sun's pass (the sun far below the horizon).
  double sunlight_bound = 0.0;
  bool sunlight_skipped = false;
  /// With RenderOptions::time_passes: milliseconds per pass or CPU step, summed over bands and groups.
  std::map<std::string, double> pass_ms;
};

class Renderer {
 public:
  Renderer(const RenderOptions& options, TableSource tables);
  ~Renderer();

  /// Where the bodies' albedo maps come from: by default the cache of
  /// RenderOptions::albedo_cache_directory (else generated) on the frame's
  /// thread; a caller that reads them ahead — the offline renderer, while the
  /// tables load — hands them over here. Each map is asked for once.
  void set_albedo_source(AlbedoMapSource source);
  /// The programs render_on_gpu's sink runs on each band after the
  /// renderer's passes (a display pass), queued by `queue` on the renderer's
  /// warm-up thread (RenderOptions::warm_first_dispatches;
  /// render/gl/first_dispatch_warmup.h) ahead of the renderer's own, since
  /// the thread takes a frame's last passes first. Called in each frame that
  /// hands the warm-up new programs (the first, mostly); never without a
  /// warm-up (a GPU). render_to_texture warms its own copy pass alike.
  void set_band_sink_warmup(WarmupQueue queue);
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders `scene` through `projection` (its camera, sun and bodies), handing
  /// rows to `sink` as bands finish. Throws std::invalid_argument for scenes it
  /// cannot render (more than 64 bodies, an atmosphere at other wavelengths than
  /// the scene's) and std::runtime_error for GL failures.
  void render(const scene::Scene& scene, const warp::Projection& projection, const RowSink& sink);
  /// The whole frame in memory: width · height · 3 floats.
  std::vector<float> render_image(const scene::Scene& scene, const warp::Projection& projection);
  /// Renders as render() does but leaves the frame on the GPU: each band is
  /// drawn into `target` (a fragment pass, shaders/render/band_to_texture.frag)
  /// instead of being read back, black tiles as 0. `target`: a 2D texture of
  /// format rgba32f or rgba16f and the projection's size; texel (x, y) is pixel
  /// (x, y) with row 0 at the top (as render_image), rgb the linear sRGB
  /// radiance × exposure, alpha 1. A live frame goes on to the display encoding
  /// (render/display/display_encoder.h) and a window; pixels leave the GPU only
  /// where a file, thumbnail or test reads them. Leaves the default draw
  /// framebuffer bound. Throws std::invalid_argument for another format or
  /// size, and what render() throws.
  void render_to_texture(const scene::Scene& scene, const warp::Projection& projection, gl::Texture& target);
  /// Renders as render() does and hands each band, still on the GPU, to
  /// `sink` (GpuBand): a live frame that needs no radiance texture goes
  /// straight to its display texture (DisplayEncoder::encode_band).
  void render_on_gpu(const scene::Scene& scene, const warp::Projection& projection, const GpuBandSink& sink);

  const FrameStats& last_frame() const { return stats_; }
  /// What building the renderer's programs took so far and how they were
  /// built (gl::ProgramBuilds::summary: "14 programs, 2.310 s building them
  /// (…), at most 14 at once on the driver's compiler threads …"); empty before the first frame.
  std::string program_builds_summary() const;
  const RenderOptions& options() const { return options_; }

 private:
  struct Impl;
  struct Frame;  ///< one frame in progress: constants, bodies, atmospheres, programs (renderer.cpp)

  // The steps of render(), in this order. Each issues its GL calls in the
  // order the one function did, so the images stay the same bit for bit.

  /// Throws std::invalid_argument for a scene the renderer cannot draw
  /// (no wavelengths, too many bodies, a sun spectrum of another length).
  void check_scene(const scene::Scene& scene) const;
  /// The frame's constants in double on the CPU: camera and sun, pixel
  /// footprints, colour weights, the sun's centre radiance and limb darkening.
  Frame frame_constants(const scene::Scene& scene, const warp::Projection& projection) const;
  /// The projection's tile cones, rebuilt (and the ray tables dropped) when the projection changed.
  void update_tile_cones(Frame& frame);
  /// The bodies camera-relative for the GPU, the atmosphere passes front to
  /// back, the albedo array texture; uploads and binds the bodies buffer.
  void prepare_bodies(Frame& frame);
  /// Where a body's air can shadow another (a lunar eclipse seen from space),
  /// the sunlight left across its shadow (render/frame/air_shadows.h), uploaded.
  void prepare_air_shadows(Frame& frame, PassTimer& timer);
  /// The tables of every atmosphere the view touches, taken from the table
  /// source where not held; upload_tables uploads them.
  void read_tables(Frame& frame);
  /// Uploads the tables read_tables took, after start_programs: a driver
  /// that compiles on the warm-up thread compiles meanwhile.
  void upload_tables(const Frame& frame);
  /// The Moon as a second light of the atmospheres (render/night/moon_light.h)
  /// where its own test finds it could show: its direction and irradiance.
  /// `moon_shadow`: the Earth's shadow on the Moon this frame (a lunar eclipse), or null.
  void light_by_the_moon(Frame& frame, const MoonInShadow* moon_shadow, PassTimer& timer);
  void light_by_the_sun(Frame& frame, PassTimer& timer);
  /// Which atmospheres read a sky-view table: those whose shell holds the
  /// camera where the table is accurate (one table per table set); the Moon's
  /// own table too where it lights the pass and is as accurate for its cosine.
  void choose_sky_view(Frame& frame) const;
  /// The uniforms every pass shares, the frame's program variant and where the sun can be drawn.
  void prepare_programs(Frame& frame);
  /// Every band's tiles (render/frame/frame_tiles.h), before any is drawn.
  void classify_bands(Frame& frame, PassTimer& timer);
  /// Starts building the frame's own passes' programs (gbuffer, resolve,
  /// direct light) of its variant that are not built yet; they depend on
  /// nothing the tables decide, so they start before the uploads. Where
  /// there is a warm-up thread (a driver that compiles in the calling
  /// thread: llvmpipe) every program builds there from now on.
  void start_frame_programs(const Frame& frame);
  /// Starts building every other program the frame's bands use that is not
  /// built yet (the sky-view fills, each atmosphere's tile variants and
  /// G-buffer path), all before any is finished: a driver with parallel
  /// shader compile builds them at once (render/gl/program_builds.h;
  /// RenderOptions::serial_compile: one at a time, where first used).
  void start_programs(const Frame& frame);
  /// The warm-up thread (RenderOptions::warm_first_dispatches), made on the
  /// first call where worthwhile (render/gl/first_dispatch_warmup.h); null where not.
  gl::FirstDispatchWarmup* warmup_thread();
  /// Hands the programs start_programs started to the warm-up thread for
  /// their first dispatch; how many it queued.
  /// `output`: queues the programs that take each band after the frame's
  /// passes (the caller's display pass, render_to_texture's copy); may be empty.
  int warm_first_dispatches(const Frame& frame, const WarmupQueue& output);
  /// Live frames (RenderOptions::background_variant_builds): the variant
  /// built ahead finished and warmed where it is ready, and the next one to
  /// build started for later frames (render/frame/live_variants.h).
  void build_variants_ahead(const Frame& frame);
  bool live_variants() const;
  /// Live frames: the variant the frame draws with, once its tiles are known
  /// (render/frame/live_variants.h); before, the variant in use.
  void choose_variant(Frame& frame);
  /// Starts building the programs `frame` would draw with in `variant` (its
  /// own passes', each atmosphere's for its tiles) that are not built.
  void start_variant_programs(const Frame& frame, const FrameVariant& variant, gl::BuildFor build_for);
  /// Those programs, built (all must be: variant_built).
  std::vector<const gl::ShaderProgram*> variant_programs(const Frame& frame, const FrameVariant& variant);
  /// Whether every program `frame` would draw with in `variant` is built
  /// (a shell's tiles: their own programs, or their general ones where those serve).
  bool variant_built(const Frame& frame, const FrameVariant& variant) const;
  /// RenderOptions::tile_programs: whether tiles draw with their general
  /// programs until their own are built (own_once_built, with a warm-up thread).
  bool general_tiles_first() const;
  /// Whether the programs of atmosphere `a`'s one-pass tile lists are built for
  /// `variant`: each list's own, or the general ones (general_tile_variant).
  bool own_tile_programs_built(const Frame& frame, std::size_t a, const FrameVariant& variant) const;
  bool general_tile_programs_built(const Frame& frame, std::size_t a, const FrameVariant& variant) const;
  /// Which atmospheres' tiles draw with their general programs this frame
  /// (AtmospherePass::general_tiles, RenderOptions::tile_programs): those
  /// whose own are not all built and warmed.
  void choose_tile_programs(Frame& frame);
  /// After the frame's bands: the own programs of the tiles that drew with
  /// the general ones started for later frames, those ready finished and
  /// their first dispatches queued on the warm-up thread.
  void build_tile_programs_ahead(const Frame& frame);
  /// How this frame's passes will bind textures and images (render/gl/first_dispatch_warmup.h).
  gl::DispatchShapes dispatch_shapes(const Frame& frame) const;
  /// The sky-view table of each atmosphere choose_sky_view chose (the sun's;
  /// the Moon's where chosen), and the eclipse-sky table where the Moon's shadow lies on its air.
  void fill_sky_view_tables(Frame& frame, PassTimer& timer);
  /// The Moon's shadow on `pass`'s atmosphere for this frame's eclipse: the
  /// one held, moved, while it fits; else a new one from a CPU copy of the
  /// tables (the TableSource's, once), now or on a worker thread
  /// (RenderOptions::background_shadow_builds). Clears pass.eclipse_sky while
  /// there is none yet.
  void follow_moon_shadow(const Frame& frame, AtmospherePass& pass, PassTimer& timer);
  /// What becomes of a band once its tiles are drawn: read back for a RowSink
  /// (render()), or copied into a texture (render_to_texture()).
  using BandOutput = std::function<void(const BandTiles& band, PassTimer& timer)>;
  /// The steps of a frame, in the order below, each band handed to `output`,
  /// which reads it on the CPU or on the GPU (`reader`).
  /// `output_warmup`: what warm_first_dispatches queues for `output`'s programs.
  void render_frame(const scene::Scene& scene, const warp::Projection& projection, BandReader reader,
                    const BandOutput& output, const WarmupQueue& output_warmup = {});
  /// The frame band by band: each band's tiles drawn, then handed to `output`.
  void render_bands(Frame& frame, BandReader reader, const BandOutput& output, PassTimer& timer);

  // Of each band, before its passes (render/band/band_passes.h):

  /// A band's tile counts (one-pass atmosphere tiles by variant, G-buffer path
  /// tiles, direct tiles, black tiles) added to the frame's statistics.
  void add_tile_stats(const BandTiles& band);
  /// The band's output zeroed where the sun's pass leaves its tiles black
  /// (RenderOptions::unlit_tile_zeroing).
  void zero_unlit_tiles(Frame& frame, const BandTiles& band, PassTimer& timer);

  RenderOptions options_;
  TableSource table_source_;
  std::unique_ptr<Impl> impl_;
  FrameStats stats_;
};

}  // namespace zenith::render
