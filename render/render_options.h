#pragma once
// What a Renderer (render/renderer.h) is asked to draw and how: the options of
// its constructor, and the atmosphere pass's features (which GpuAtmosphere,
// render/frame/gpu_atmosphere.h, compiles its programs for). A plain header:
// the commands, the cluster's nodes and the benchmarks fill these in without
// seeing the renderer's GL side.
#include <cstddef>
#include <filesystem>

#include "image/colour.h"

namespace zenith::render {

/// Which terms the atmosphere pass evaluates (each off drops code from the shader).
struct AtmospherePassFeatures {
  bool multiple_scattering = true;  ///< orders ≥ 2 (off: single scattering only)
  bool eclipses = true;             ///< other bodies' shadows on the ground
  bool fp64 = false;                ///< table mappings and interpolation in double (slower; see docs/rendering.md)
};

/// Whether an atmosphere whose shell holds the camera reads the in-scattering
/// (and the ground's light) along view rays from a per-frame sky-view table
/// (render/frame/sky_view_table.h, docs/rendering-performance.md) instead of the 4D tables.
enum class SkyViewTableUse {
  /// Where the table is accurate (one-pass tiles of an atmosphere the camera
  /// is inside, where no other body inside the shell can be) in frames of at
  /// least SkyViewTable::kMinFramePixels (a smaller frame's 4D lookups cost
  /// less than filling the table), and at any size in a scene whose Moon can
  /// eclipse the sun (a sky clock and NightSkyRenderOptions::moon: an
  /// eclipsed sky is drawn from it).
  automatic,
  always,  ///< where it is accurate, in frames of any size (the table's own tests and benchmarks)
  off,     ///< never: the 4D tables for every pixel (the reference the table is tested against)
};

/// Which program draws a list of one atmosphere's tiles (atmosphere_tile.comp,
/// compiled for what the tiles can hold: render/frame/tile_classification.h).
enum class TilePrograms {
  own,  ///< each list's own program, built by the frame that first needs it
  /// Where the renderer's programs build one at a time on a second thread
  /// (llvmpipe: render/gl/program_builds.h), a shell's tiles draw with its
  /// general program (general_tile_variant: one program for its ground,
  /// horizon and sky tiles, the same pixels) until their kinds' own programs,
  /// started after the first frame that lacked them, are built and their
  /// first dispatches warmed: a cold start builds one program where it would
  /// build three, and the frames meanwhile cost what the general program
  /// costs. Elsewhere (a GPU driver compiles them at once on its own threads)
  /// as `own`. What the commands' renderers use (offline shows, nodes, windows).
  own_once_built,
  general,  ///< always the general programs (their frame cost: render_bench --general-tiles; their pixels: tested)
};

/// How the band's output is zeroed on the tiles the sun's pass leaves black
/// (RenderOptions::skip_hidden_sunlight).
enum class UnlitTileZeroing {
  automatic,     ///< buffer_clear on a CPU rasterizer, compute_pass on a GPU
  buffer_clear,  ///< the band's whole output cleared by the driver (glClearNamedBufferSubData)
  compute_pass,  ///< zeros stored by a pass over those tiles only (shaders/render/zero_tiles.comp)
};

/// The sky-view table's use for each output of a dome or wall whose largest
/// output has `largest_output_pixels`: `always` where that one is large enough
/// to fill the table (SkyViewTable::kMinFramePixels), so that a small output
/// beside it takes the same path and no seam runs between projectors; else
/// `automatic` (every output small: the 4D lookups, or the table for eclipses).
SkyViewTableUse sky_view_use_for_outputs(std::size_t largest_output_pixels);

/// The night sky's light (render/night/star_pass.h, docs/night-sky.md,
/// "Rendering the night sky"), drawn for scenes with a "time" and "site" (the
/// stars) or a "night_sky"/"light_pollution" (the floor and the glow).
struct NightSkyRenderOptions {
  bool stars = true;        ///< the catalogue's stars as point sources
  bool night_floor = true;  ///< the natural night sky and light pollution
  bool moon = true;  ///< the Moon's disc by its phase (Lommel–Seeliger), with the stars' sky clock; it covers the sun
                     ///< in an eclipse
  /// The Earth's shadow on the Moon in a lunar eclipse (render/night/moon_in_shadow.h): its disc and its
  /// light on the sky take the sunlight refracted through the Earth's air; false: the Moon stays full.
  bool lunar_eclipses = true;
  /// The Moon lights the atmospheres (render/night/moon_light.h): the sky and the
  /// ground by moonlight, from the same tables, where its own test finds it visible.
  bool moonlight = true;
  /// Skip the stars when the frame's sky hides them all (render/night/star_visibility.h);
  /// false: place and draw them whenever they are on (the frame the test is checked against).
  bool skip_hidden_stars = true;
  /// Skip the night floor and the glow when the frame's sky hides them
  /// (render/night/star_pass.h); false: against a black sky only (the frame the
  /// test is checked against).
  bool skip_hidden_floor = true;
  /// The catalogue (astro/star_catalogue.h): stellarium-data's directory and
  /// the faintest V kept, [−2, 10.5]. Loaded once per renderer, on the first
  /// frame that needs it; a missing catalogue logs a warning and draws no stars.
  std::filesystem::path star_directory = "/usr/share/stellarium/stars/default";
  double star_magnitude_limit = 7.0;
  /// The Moon's albedo map (render/night/moon_albedo_map.h): stellarium-data's
  /// equirectangular texture, loaded once per renderer with the first disc; a
  /// missing or unreadable file logs one warning and draws a uniform albedo.
  std::filesystem::path moon_albedo_map = "/usr/share/stellarium/textures/moon.png";  // astro::kStellariumMoonMap
};

struct RenderOptions {
  bool atmospheres = true;            ///< false: bodies lit by the sun only (the benchmarks' baseline)
  bool sun_disc = true;               ///< draw the sun's disc
  bool limb_darkening = true;         ///< darken the disc toward its limb (off: uniform disc)
  AtmospherePassFeatures atmosphere;  ///< multiple scattering, eclipses, shader precision
  image::ColourMapping colour = image::ColourMapping::automatic;
  /// Pixels per band; the frame is split into bands of whole 16-pixel tile rows.
  std::size_t max_band_pixels = std::size_t{4} << 20;
  /// Tiles with no atmosphere or with one are drawn in one pass straight to
  /// the output (direct_light.comp, atmosphere_tile.comp). false: every tile
  /// goes through the G-buffer, atmosphere and resolve passes (the path the
  /// one-pass tiles are tested against).
  bool one_pass_tiles = true;
  /// Zero an atmosphere's sky-and-ground tiles instead of drawing the sun's
  /// pass over them where the sun's light could not move a display value
  /// (render/frame/sun_light.h: the sun far below the horizon); false: the
  /// sun's passes always run (the frame the test is checked against).
  bool skip_hidden_sunlight = true;
  /// How those tiles are zeroed: `automatic` is a buffer clear on a CPU
  /// rasterizer (a memset there) and a pass of zero stores on a GPU
  /// (shaders/render/zero_tiles.comp says why); either may be asked for.
  UnlitTileZeroing unlit_tile_zeroing = UnlitTileZeroing::automatic;
  SkyViewTableUse sky_view_table = SkyViewTableUse::automatic;
  TilePrograms tile_programs = TilePrograms::own;
  /// Time every pass (GL_TIME_ELAPSED queries; CPU steps by the wall clock) into
  /// FrameStats::pass_ms. Serialises the frame: for profiling, not for frame times.
  bool time_passes = false;
  /// Build the frame's programs one at a time, each where first used, the
  /// driver's compiler threads off (render/gl/program_builds.h); false: all
  /// of a frame's started together, on the driver's threads where it has
  /// them (GL_KHR_parallel_shader_compile). To compare, as `zenith precompute
  /// --serial-compile` does for the precompute.
  bool serial_compile = false;
  /// Where the driver generates a program's machine code at its first
  /// dispatch and keeps it in its shader cache (Mesa's llvmpipe), dispatch the
  /// frame's started programs once on a second thread so two cores generate
  /// code at once (render/gl/first_dispatch_warmup.h). Off with serial_compile.
  bool warm_first_dispatches = true;
  /// In a solar eclipse, build a new Moon's shadow on the air
  /// (render/frame/eclipse_sky_table.h; seconds of CPU) on a worker thread
  /// while frames go on with the one held, moved with the Moon: live frames
  /// (a window, a cluster's node) never wait for it. false: the frame waits
  /// (offline renders, tests: the same frames every run). The first shadow of
  /// an eclipse is waited for either way where the penumbra already reaches
  /// the air in view.
  bool background_shadow_builds = false;
  /// Live frames (a window, a cluster's node) never wait for a program
  /// variant's compile (render/frame/live_variants.h): a frame whose leaner
  /// variant is not built yet draws with the one in use, which gives the same
  /// pixels, while the leaner one builds on a second thread; the general
  /// variant is built ahead too. false: every frame builds and draws its own
  /// variant (offline renders, tests).
  bool background_variant_builds = false;
  /// Where generated albedo maps are kept between runs
  /// (scene/albedo_map_cache.h; the commands give it the table cache's
  /// directory); empty: each renderer generates its maps.
  std::filesystem::path albedo_cache_directory;
  /// Where the renderer's linked programs are kept between runs
  /// (render/gl/program_binary_cache.h; the commands give it the table
  /// cache's "programs" folder, the precompute's); empty: compiled each run.
  std::filesystem::path program_cache_directory;
  NightSkyRenderOptions night_sky;
};

}  // namespace zenith::render
