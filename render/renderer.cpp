#include "render/renderer.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "atmosphere/model_hash.h"
#include "core/parallel_for.h"
#include "render/band/band_passes.h"
#include "render/band/band_resources.h"
#include "render/band/band_to_texture.h"
#include "render/frame/air_shadows.h"
#include "render/frame/albedo_array.h"
#include "render/frame/frame_conditions.h"
#include "render/frame/frame_constants.h"
#include "render/frame/frame_in_progress.h"
#include "render/frame/frame_programs.h"
#include "render/frame/frame_tiles.h"
#include "render/frame/gpu_atmosphere.h"
#include "render/frame/gpu_body.h"
#include "render/frame/live_variants.h"
#include "render/frame/pass_timer.h"
#include "render/frame/sky_view_table.h"
#include "render/frame/sun_light.h"
#include "render/frame/sun_refraction.h"
#include "render/frame/tile_classification.h"
#include "render/frame/tile_culling.h"
#include "render/gl/buffer.h"
#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/gl_error.h"
#include "render/gl/program_binary_cache.h"
#include "render/gl/program_builds.h"
#include "render/gl/shader_cache_writes.h"
#include "render/gl/shader_program.h"
#include "render/gl/software_rasterizer.h"
#include "render/gl/texture.h"
#include "render/night/moon_in_shadow.h"
#include "render/night/moon_light.h"
#include "render/night/star_pass.h"
#include "render/shader_bindings.h"
#include "scene/albedo_map.h"

namespace zenith::render {
namespace {

using gl::TextureFormat;
using scene::kMaxBodies;

/// The rows of the band's images: a band's rows, whole tiles of a shorter image.
int band_texture_rows(const FrameInProgress& frame) {
  return std::min(frame.band_rows, (frame.projection.height() + kTileSize - 1) / kTileSize * kTileSize);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::array<float, 4> vec4_of(const glm::dvec3& v, double w) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z), static_cast<float>(w)};
}

}  // namespace

struct Renderer::Impl {
  explicit Impl(const RenderOptions& options)
      : frame_programs(options.sun_disc, options.limb_darkening),
        night_sky(options.night_sky, refractions),
        albedo(options.albedo_cache_directory) {}
  // Every program of the renderer, by text (created by the first frame, with a
  // current context): a frame starts all it needs before finishing any.
  std::optional<gl::ProgramBinaryCache> binaries;  // RenderOptions::program_cache_directory, with the builds
  std::unique_ptr<gl::ProgramBuilds> builds;
  FramePrograms frame_programs;  // gbuffer, resolve and direct light, per FrameVariant
  LiveVariants live_variants;    // RenderOptions::background_variant_builds
  int frames_held = 0;           // frames in a row drawn with a variant other than the one wanted
  int general_tile_frames = 0;   // frames in a row some atmosphere's tiles drew with their general program
  RefractionCache refractions;   // the air's refraction at the camera: stars, the Moon, the Sun's disc
  NightSkyPass night_sky;        // stars, the night floor, light pollution (render/night/star_pass.h)
  MoonInShadow moon_shadow;      // the Earth's shadow on the Moon in a lunar eclipse
  AirShadows air_shadows;        // the scene's bodies' shadows through their air (the red Moon from space)
  std::map<std::string, std::unique_ptr<GpuAtmosphere>> atmospheres;  // by table hash + features
  AlbedoArray albedo;  // the bodies' maps, one layer per body (render/frame/albedo_array.h)
  std::string projection_key;
  std::unique_ptr<TileCones> cones;
  FrameTiles frame_tiles;         // every band's tiles, kept while the scene holds still
  BandResources band;             // the bodies, tile lists, band images and rays on the GPU
  BandToTexture band_to_texture;  // render_to_texture()'s band copy
  // First dispatches on a second thread (RenderOptions::warm_first_dispatches):
  // last, so that it stops before the programs and textures go.
  std::unique_ptr<gl::FirstDispatchWarmup> warmup;
  bool warmup_tried = false;
  WarmupQueue band_sink_warmup;  // set_band_sink_warmup: render_on_gpu's sink's programs
};

Renderer::Renderer(const RenderOptions& options, TableSource tables)
    : options_(options), table_source_(std::move(tables)), impl_(std::make_unique<Impl>(options_)) {
  if (options_.max_band_pixels < std::size_t{kTileSize} * kTileSize)
    throw std::invalid_argument("RenderOptions::max_band_pixels must be at least 256");
}

Renderer::~Renderer() = default;

void Renderer::set_albedo_source(AlbedoMapSource source) { impl_->albedo.set_source(std::move(source)); }

void Renderer::set_band_sink_warmup(WarmupQueue queue) { impl_->band_sink_warmup = std::move(queue); }

std::string Renderer::program_builds_summary() const {
  if (!impl_->builds) return "";
  std::string summary = impl_->builds->summary();
  if (impl_->warmup) {
    const gl::FirstDispatchWarmup::Statistics w = impl_->warmup->statistics();
    summary += fmt::format(
        "; first dispatches: {} of {} warmed on a second thread ({:.2f} s there), {} dispatched here first, "
        "{:.2f} s waited for it",
        w.warmed, w.queued, w.warm_s, w.taken_back, w.wait_s);
  }
  return summary;
}

std::vector<float> Renderer::render_image(const scene::Scene& scene, const warp::Projection& projection) {
  std::vector<float> image(static_cast<std::size_t>(projection.width()) * projection.height() * 3);
  render(scene, projection, [&](int first_row, int rows, std::span<const float> rgb) {
    std::copy(rgb.begin(), rgb.begin() + static_cast<std::ptrdiff_t>(rows) * projection.width() * 3,
              image.begin() + static_cast<std::ptrdiff_t>(first_row) * projection.width() * 3);
  });
  return image;
}

/// One frame in progress (render/frame/frame_in_progress.h).
struct Renderer::Frame : FrameInProgress {
  using FrameInProgress::FrameInProgress;
};

void Renderer::render(const scene::Scene& scene, const warp::Projection& projection, const RowSink& sink) {
  render_frame(scene, projection, BandReader::cpu, [&](const BandTiles& band, PassTimer& timer) {
    const std::span<const float> rows_rgb = impl_->band.read_back(band, timer);
    timer.cpu("sink", [&] { sink(band.first_row, band.rows, rows_rgb); });
  });
}

void Renderer::render_frame(const scene::Scene& scene, const warp::Projection& projection, BandReader reader,
                            const BandOutput& output, const WarmupQueue& output_warmup) {
  const auto start = std::chrono::steady_clock::now();
  stats_ = FrameStats{};
  PassTimer timer(options_.time_passes);
  gl::check_gl_error("Renderer::render: an earlier GL call left an error");

  check_scene(scene);
  Impl& im = *impl_;
  if (!im.builds) {
    im.builds = std::make_unique<gl::ProgramBuilds>(options_.serial_compile ? gl::CompileMode::serial
                                                                            : gl::CompileMode::parallel);
    if (!options_.program_cache_directory.empty()) {
      im.binaries.emplace(options_.program_cache_directory);
      im.builds->set_binary_cache(&*im.binaries);
    }
    im.frame_programs.set_zero_tiles(
        options_.unlit_tile_zeroing == UnlitTileZeroing::compute_pass ||
        (options_.unlit_tile_zeroing == UnlitTileZeroing::automatic && !gl::current_renderer_is_software()));
  }
  const gl::ProgramBuilds::Statistics builds_before = im.builds->statistics();
  const int binaries_before = im.binaries ? im.binaries->statistics().loaded : 0;
  Frame frame = frame_constants(scene, projection);
  const MoonInShadow* moon_shadow = nullptr;  // a lunar eclipse this frame (render/night/moon_in_shadow.h)
  if (options_.night_sky.moon && options_.night_sky.lunar_eclipses && scene.sky_clock) {
    timer.cpu("earth's shadow on the moon", [&] { im.moon_shadow.update(scene, frame.sky); });
    moon_shadow = &im.moon_shadow;
  }
  if (options_.sun_disc) frame.sun_lift = sun_disc_lift(scene, sun_reach_rad(frame), impl_->refractions);
  frame.lights = {frame.sun_light()};
  update_tile_cones(frame);
  prepare_bodies(frame);
  prepare_air_shadows(frame, timer);
  prepare_programs(frame);
  start_frame_programs(frame);
  read_tables(frame);
  light_by_the_moon(frame, moon_shadow, timer);
  light_by_the_sun(frame, timer);
  choose_sky_view(frame);
  classify_bands(frame, timer);
  choose_variant(frame);
  choose_tile_programs(frame);
  start_programs(frame);
  upload_tables(frame);
  fill_sky_view_tables(frame, timer);
  frame.programs = &im.frame_programs.passes_for(*im.builds, frame.variant);
  stats_.programs_warmed = warm_first_dispatches(frame, output_warmup);
  build_variants_ahead(frame);
  set_direct_light_uniforms(frame);
  impl_->night_sky.prepare(frame, moon_shadow, timer);
  stats_.night_sky = impl_->night_sky.stats();
  stats_.moonlight = frame.moon() != nullptr;
  render_bands(frame, reader, output, timer);
  build_tile_programs_ahead(frame);
  const gl::ProgramBuilds::Statistics& builds_after = im.builds->statistics();
  stats_.programs_built = builds_after.built - builds_before.built;
  stats_.programs_s = builds_after.seconds() - builds_before.seconds();
  stats_.programs_from_binaries = im.binaries ? im.binaries->statistics().loaded - binaries_before : 0;
  stats_.pass_ms = timer.milliseconds();
  stats_.seconds = seconds_since(start);
}

void Renderer::check_scene(const scene::Scene& scene) const {
  const std::size_t n = scene.wavelengths_nm.size();
  if (n == 0) throw std::invalid_argument("scene '" + scene.name + "' has no working wavelengths");
  if (scene.bodies.size() > kMaxBodies)
    throw std::invalid_argument(fmt::format("scene '{}' has {} bodies; the renderer draws at most {}", scene.name,
                                            scene.bodies.size(), kMaxBodies));
  if (scene.sun.irradiance_W_m2_nm.size() != n)
    throw std::invalid_argument(fmt::format("scene '{}': the sun has {} irradiance values for {} wavelengths",
                                            scene.name, scene.sun.irradiance_W_m2_nm.size(), n));
}

Renderer::Frame Renderer::frame_constants(const scene::Scene& scene, const warp::Projection& projection) const {
  Frame f(scene, projection);
  static_cast<FrameConstants&>(f) =
      compute_frame_constants(scene, f.sky, projection, options_.colour, options_.limb_darkening,
                              options_.night_sky.moon, options_.atmosphere.eclipses);
  return f;
}

void Renderer::update_tile_cones(Frame& frame) {
  Impl& im = *impl_;
  const warp::Projection& projection = frame.projection;
  const warp::GpuProjection g = projection.gpu();
  std::ostringstream key;
  key << projection.describe() << ' ' << projection.width() << 'x' << projection.height() << ' '
      << static_cast<int>(g.kind);
  for (const auto& v : g.params)
    for (float f : v) key << ' ' << f;
  if (key.str() != im.projection_key || !im.cones) {
    im.cones = std::make_unique<TileCones>(projection);
    im.projection_key = key.str();
    im.band.forget_rays();
    im.frame_tiles.forget();
  }
  frame.cones = im.cones.get();
  frame.tiles_total = static_cast<std::size_t>(frame.cones->columns()) * frame.cones->rows();
}

void Renderer::prepare_bodies(Frame& frame) {
  Impl& im = *impl_;
  const scene::Scene& scene = frame.scene;
  std::vector<GpuBody>& bodies = frame.bodies;
  std::vector<AtmospherePass>& passes = frame.passes;
  bodies.resize(scene.bodies.size());
  std::vector<std::string> albedo_layers;  // body b's map is layer b
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const scene::Body& body = scene.bodies[b];
    const glm::dvec3 c = body.position_m - scene.camera.position_m;
    const double D = glm::length(c);
    const glm::dvec3 dir = c / D;
    const double R = body.radius_m;
    const glm::dmat3 world_to_body = glm::transpose(glm::mat3_cast(glm::normalize(body.orientation)));
    GpuBody& g = bodies[b];
    g.centre = vec4_of(dir, D);
    g.shape = {static_cast<float>(R), static_cast<float>((D - R) * (D + R)), -1.0f, static_cast<float>(b)};
    for (int row = 0; row < 3; ++row)
      g.world_to_body[row] =
          vec4_of(glm::dvec3(world_to_body[0][row], world_to_body[1][row], world_to_body[2][row]), 0.0);

    const auto albedo_start = std::chrono::steady_clock::now();
    albedo_layers.push_back(im.albedo.load(body.albedo));
    stats_.albedo_s += seconds_since(albedo_start);

    if (!body.atmosphere || !options_.atmospheres) continue;
    const atmosphere::AtmosphereModel& model = body.atmosphere->loaded.model;
    if (model.wavelengths_nm != scene.wavelengths_nm)
      throw std::invalid_argument(
          fmt::format("scene '{}': the atmosphere of '{}' is resolved at other wavelengths "
                      "than the scene's",
                      scene.name, body.name));
    AtmospherePass pass;
    pass.body = static_cast<int>(b);
    pass.distance_m = D;
    pass.top_radius_m = model.top_radius_m;
    pass.power_m2 = (D - model.top_radius_m) * (D + model.top_radius_m);
    pass.direction_camera = frame.world_to_camera * dir;
    g.shape[2] = static_cast<float>(passes.size());
    passes.push_back(std::move(pass));
  }
  // Front to back: for disjoint shells the camera's power with respect to each
  // sphere (D² − R²) orders them along every ray (the radical plane separates them).
  std::sort(passes.begin(), passes.end(),
            [](const AtmospherePass& a, const AtmospherePass& b) { return a.power_m2 < b.power_m2; });
  for (AtmospherePass& pass : passes) {
    FrameStats::Atmosphere s;
    s.body = scene.bodies[static_cast<std::size_t>(pass.body)].name;
    s.tiles_total = frame.tiles_total;
    stats_.atmospheres.push_back(s);
  }
  const auto albedo_start = std::chrono::steady_clock::now();
  im.albedo.ensure(albedo_layers);
  stats_.albedo_s += seconds_since(albedo_start);
  for (GpuBody& g : bodies) g.albedo_map = {static_cast<float>(im.albedo.texture().width()), 0, 0, 0};
  im.albedo.texture().bind(binding::kAlbedoMapsUnit);
  im.band.upload_bodies(bodies);
}

void Renderer::prepare_air_shadows(Frame& frame, PassTimer& timer) {
  Impl& im = *impl_;
  const scene::Scene& scene = frame.scene;
  frame.air_shadow_occluders.clear();
  frame.air_shadow_bodies.clear();
  // Without the atmospheres drawn (RenderOptions::atmospheres) the bodies are solid.
  if (!options_.atmospheres || !options_.atmosphere.eclipses || !eclipses_possible(scene)) return;
  timer.cpu("shadows through the air", [&] { im.air_shadows.update(scene); });
  const std::vector<AirShadow>& shadows = im.air_shadows.shadows();
  im.band.upload_air_shadows(air_shadow_buffer(shadows, frame, scene));
  const int values = static_cast<int>(air_shadow_values_per_entry(frame));
  for (std::size_t s = 0; s < shadows.size(); ++s) {
    const AirShadow& shadow = shadows[s];
    const glm::dvec3 c = scene.bodies[shadow.occluder].position_m - scene.camera.position_m;  // in double
    frame.air_shadow_occluders.push_back(vec4_of(c, shadow.reach_m));
    frame.air_shadow_bodies.push_back({static_cast<int>(shadow.occluder), static_cast<int>(shadow.receiver),
                                       static_cast<int>(s * kAirShadowEntries) * values, values});
  }
}

void Renderer::read_tables(Frame& frame) {
  Impl& im = *impl_;
  const scene::Scene& scene = frame.scene;
  for (AtmospherePass& pass : frame.passes) {
    if (!frame.touches_view(pass)) continue;  // an atmosphere outside the view costs nothing
    const atmosphere::AtmosphereModel& model =
        scene.bodies[static_cast<std::size_t>(pass.body)].atmosphere->loaded.model;
    const std::string key =
        fmt::format("{} mult={} ecl={} fp64={}", atmosphere::lookup_table_hash(model),
                    options_.atmosphere.multiple_scattering, options_.atmosphere.eclipses, options_.atmosphere.fp64);
    auto it = im.atmospheres.find(key);
    if (it == im.atmospheres.end()) {
      const auto start = std::chrono::steady_clock::now();
      ++stats_.table_sets_requested;
      it = im.atmospheres
               .emplace(key, std::make_unique<GpuAtmosphere>(model, table_source_(model), options_.atmosphere,
                                                             im.frame_programs.sun_defines(), *im.builds))
               .first;
      stats_.tables_s += seconds_since(start);
    }
    pass.gpu = it->second.get();
  }
}

void Renderer::upload_tables(const Frame& frame) {
  for (const AtmospherePass& pass : frame.passes) {
    if (!pass.gpu || pass.gpu->tables_uploaded()) continue;
    const auto start = std::chrono::steady_clock::now();
    pass.gpu->upload_tables();
    ++stats_.table_sets_uploaded;
    stats_.tables_s += seconds_since(start);
    spdlog::debug("renderer: atmosphere of '{}' resident ({:.1f} MB of tables)",
                  frame.scene.bodies[static_cast<std::size_t>(pass.body)].name,
                  static_cast<double>(pass.gpu->table_bytes()) / 1e6);
  }
}

SkyViewTableUse sky_view_use_for_outputs(std::size_t largest_output_pixels) {
  return largest_output_pixels >= SkyViewTable::kMinFramePixels ? SkyViewTableUse::always : SkyViewTableUse::automatic;
}

void Renderer::choose_sky_view(Frame& frame) const {
  const scene::Scene& scene = frame.scene;
  // The Moon's shadow on a planet's air (render/frame/sun_occulter.h): on
  // the sky-view table's terms where the camera is inside the shell, on the
  // 4D tables' from orbit (eclipse_sky_table.h).
  for (AtmospherePass& pass : frame.passes)
    pass.eclipse_sky = pass.gpu && frame.occulter.shadow_on_the_air_of(pass.body);
  // A small frame's 4D lookups cost less than the table's fill. But the
  // Moon's shadow on the air is drawn from the table (eclipse_sky_table.h),
  // so a scene where the Moon can eclipse the sun keeps it at any size: its
  // sky does not switch paths (a jump) when the shadow comes near.
  const std::size_t pixels =
      static_cast<std::size_t>(frame.projection.width()) * static_cast<std::size_t>(frame.projection.height());
  const bool small = pixels < SkyViewTable::kMinFramePixels &&
                     !moon_can_eclipse_the_sun(scene, options_.night_sky.moon, options_.atmosphere.eclipses);
  if (options_.sky_view_table == SkyViewTableUse::off ||
      (options_.sky_view_table == SkyViewTableUse::automatic && small))
    return;
  std::vector<const GpuAtmosphere*> chosen;  // a table set's table is filled once
  for (AtmospherePass& pass : frame.passes) {
    if (!pass.gpu || pass.power_m2 > 0.0) continue;
    if (std::find(chosen.begin(), chosen.end(), pass.gpu) != chosen.end()) continue;
    const scene::Body& planet = scene.bodies[static_cast<std::size_t>(pass.body)];
    const glm::dvec3 up = glm::normalize(scene.camera.position_m - planet.position_m);
    pass.sky_view =
        sky_view_accurate(pass.distance_m, pass.gpu->ground_radius_m(), pass.top_radius_m, glm::dot(up, frame.sun));
    if (!pass.sky_view) continue;
    // The Moon's own table where it is as accurate for the Moon's cosine; else
    // its passes read the 4D tables in the sky-view tiles.
    pass.moon_sky_view = pass.moonlit && sky_view_accurate(pass.distance_m, pass.gpu->ground_radius_m(),
                                                           pass.top_radius_m, glm::dot(up, frame.moon()->direction));
    chosen.push_back(pass.gpu);
  }
}

void Renderer::fill_sky_view_tables(Frame& frame, PassTimer& timer) {
  for (std::size_t a = 0; a < frame.passes.size(); ++a) {
    AtmospherePass& pass = frame.passes[a];
    if (!pass.sky_view && !pass.eclipse_sky) continue;
    const scene::Body& planet = frame.scene.bodies[static_cast<std::size_t>(pass.body)];
    const glm::dvec3 up = glm::normalize(frame.scene.camera.position_m - planet.position_m);
    // The sun's table, unless no tile the sun's pass draws reads it (its sky
    // and ground left black: render/frame/sun_light.h); the eclipse-sky table
    // likewise, for the one-pass tiles of either kind.
    bool read = false, drawn = false;
    for (const BandTiles& band : *frame.bands)
      for (const auto& [variant, list] : band.lists[a].one_pass) {
        const bool lit = !sky_and_ground_unlit(pass, variant);
        read = read || (pass.sky_view && variant.sky_view && lit);
        drawn = drawn || lit;
      }
    if (read)
      timer.gpu("sky-view table", [&] {
        if (pass.gpu->fill_sky_view(pass.distance_m, glm::dot(up, frame.sun), frame.sun_radius))
          ++stats_.sky_view_tables_filled;
      });
    if (pass.eclipse_sky) {
      if (drawn)
        follow_moon_shadow(frame, pass, timer);
      else
        pass.eclipse_sky = false;  // no tile draws the sun's sky
    }
    if (pass.eclipse_sky) {
      timer.gpu("eclipse-sky table",
                [&] { pass.gpu->fill_eclipse_sky(frame.scene.camera.position_m - planet.position_m); });
      stats_.eclipse_sky = true;
    }
    if (pass.moon_sky_view)
      timer.gpu("sky-view table, moonlight", [&] {
        const FrameLight& moon = *frame.moon();
        if (pass.gpu->fill_sky_view(pass.distance_m, glm::dot(up, moon.direction), moon.angular_radius_rad,
                                    moon.sky_view_slot()))
          ++stats_.sky_view_tables_filled;
      });
  }
}

void Renderer::follow_moon_shadow(const Frame& frame, AtmospherePass& pass, PassTimer& timer) {
  const scene::Body& planet = frame.scene.bodies[static_cast<std::size_t>(pass.body)];
  const glm::dvec3 camera = frame.scene.camera.position_m - planet.position_m;
  EclipseSkyTable& table = pass.gpu->eclipse_sky();
  const auto start = std::chrono::steady_clock::now();
  if (!table.has_tables()) {
    // Kept on the CPU for this eclipse's shadows: a worker thread may not call the TableSource.
    const atmosphere::AtmosphereModel& model = planet.atmosphere->loaded.model;
    ++stats_.table_sets_requested;
    timer.cpu("moon's shadow: tables", [&] {
      table.keep_tables(model, std::make_shared<const atmosphere::lut::LookupTables>(table_source_(model)));
    });
    const atmosphere::lut::TableSizes& sizes = table.tables()->sizes;
    const atmosphere::lut::TableSizes paper;
    if (sizes.scattering_r < paper.scattering_r || sizes.scattering_mu < paper.scattering_mu)
      spdlog::warn(
          "the Moon's shadow on the air of '{}': its tables ({}) are coarser than the paper's; from "
          "such tables the sky in totality came out 1.4-2.3x the path tracer's (docs/validation.md, "
          "\"Eclipses\"): use the paper tables or larger",
          planet.name, sizes.describe());
  }
  // Live frames never wait for a shadow (RenderOptions::background_shadow_builds), not even the
  // first where the penumbra is still far from the air in view (V̄ eased to within 1 % of 1 there).
  const bool background =
      options_.background_shadow_builds && (table.shadow() != nullptr || frame.occulter.air_from_axis_penumbrae >= 1.8);
  EclipseSkyTable::ShadowUpdate update{};
  timer.cpu("moon's shadow", [&] { update = table.update(*frame.occulter.shadow, camera, background); });
  if (update == EclipseSkyTable::ShadowUpdate::built || update == EclipseSkyTable::ShadowUpdate::swapped) {
    ++stats_.moon_shadows_built;
    spdlog::info("the Moon's shadow on the air of '{}' {} ({:.2f} s this frame)", planet.name,
                 update == EclipseSkyTable::ShadowUpdate::built ? "built" : "built in the background",
                 seconds_since(start));
  }
  stats_.moon_shadow_s += seconds_since(start);
  pass.eclipse_sky = table.shadow() != nullptr;
}

void Renderer::start_frame_programs(const Frame& frame) {
  Impl& im = *impl_;
  // llvmpipe compiles and links in the calling thread: there the programs
  // build on the warm-up thread while this one uploads the tables.
  im.builds->build_on(warmup_thread());
  im.frame_programs.start(*im.builds, frame.variant);
}

void Renderer::start_programs(const Frame& frame) {
  for (const AtmospherePass& pass : frame.passes) {
    if (pass.sky_view) pass.gpu->start_sky_view_program();
    if (pass.eclipse_sky) pass.gpu->eclipse_sky().start_program();
  }
  start_variant_programs(frame, frame.variant, gl::BuildFor::this_frame);
}

gl::FirstDispatchWarmup* Renderer::warmup_thread() {
  Impl& im = *impl_;
  if (!im.warmup_tried) {
    im.warmup_tried = true;
    if (options_.warm_first_dispatches && !options_.serial_compile)
      im.warmup = gl::FirstDispatchWarmup::if_worthwhile("renderer");
  }
  return im.warmup.get();
}

int Renderer::warm_first_dispatches(const Frame& frame, const WarmupQueue& output) {
  Impl& im = *impl_;
  if (warmup_thread() == nullptr || !im.builds->started_since_warm()) return 0;  // most frames: nothing new
  bool one_body = false, bodies = false, sun = false, gbuffer = false;
  for (const BandTiles& band : *frame.bands) {
    one_body = one_body || !band.one_body_tiles.empty();
    bodies = bodies || band.body_tiles.count > 0;
    sun = sun || band.sun_tiles.count > 0;
    gbuffer = gbuffer || band.gbuffer_tiles.count > 0;
  }
  // Where each program comes in the band's passes (render/band/band_passes.h):
  // the direct light, the one-pass tiles, the G-buffer path (g-buffer,
  // atmospheres, resolve). Passes whose tiles no band has are not run.
  const FramePasses& fp = *frame.programs;
  const auto order = [&](const gl::ShaderProgram& p) {
    if (&p == fp.direct_light_one) return one_body ? 0 : -1;
    if (&p == fp.direct_light) return bodies ? 1 : -1;
    if (&p == fp.direct_light_sun) return sun ? 2 : -1;
    if (&p == fp.gbuffer) return gbuffer ? 4 : -1;
    if (&p == fp.resolve) return gbuffer ? 6 : -1;
    if (p.name() == "render/atmosphere_pass.comp") return 5;
    return 3;  // the one-pass tiles (and any other)
  };
  const int before = im.warmup->statistics().queued;
  if (output) output(*im.warmup);  // the band's last pass: first
  im.builds->warm_started(*im.warmup, dispatch_shapes(frame), order);
  return im.warmup->statistics().queued - before;
}

bool Renderer::live_variants() const { return options_.background_variant_builds && !options_.serial_compile; }

bool Renderer::variant_built(const Frame& frame, const FrameVariant& variant) const {
  const Impl& im = *impl_;
  if (!im.frame_programs.built(*im.builds, variant) || !im.night_sky.programs_built(*im.builds, variant)) return false;
  for (const BandTiles& band : *frame.bands)
    for (std::size_t a = 0; a < band.lists.size(); ++a) {
      const GpuAtmosphere* gpu = frame.passes[a].gpu;
      if (band.lists[a].gbuffer.count > 0 && !gpu->gbuffer_path_program_built(variant)) return false;
    }
  for (std::size_t a = 0; a < frame.passes.size(); ++a)
    if (!own_tile_programs_built(frame, a, variant) &&
        !(general_tiles_first() && general_tile_programs_built(frame, a, variant)))
      return false;
  return true;
}

bool Renderer::general_tiles_first() const {
  // The warm-up thread is made, where worthwhile, before the frame's first programs start.
  return options_.tile_programs == TilePrograms::own_once_built && impl_->warmup != nullptr;
}

namespace {

/// Whether the tile program of every one-pass list of atmosphere `a` in
/// `frame`, its tiles' variant made into the one `kind` gives, is built for `variant`.
template <typename Kind>
bool tile_programs_built(const FrameInProgress& frame, std::size_t a, const FrameVariant& variant, Kind kind) {
  const AtmospherePass& pass = frame.passes[a];
  if (!pass.gpu) return true;  // outside the view: no tiles
  for (const BandTiles& band : *frame.bands)
    for (const auto& [tiles, list] : band.lists[a].one_pass)
      if (!pass.gpu->tile_program_built(variant, kind(tiles), pass.eclipse_sky)) return false;
  return true;
}

}  // namespace

bool Renderer::own_tile_programs_built(const Frame& frame, std::size_t a, const FrameVariant& variant) const {
  return tile_programs_built(frame, a, variant, [](const TileVariant& v) { return v; });
}

bool Renderer::general_tile_programs_built(const Frame& frame, std::size_t a, const FrameVariant& variant) const {
  return tile_programs_built(frame, a, variant, general_tile_variant);
}

void Renderer::choose_tile_programs(Frame& frame) {
  if (options_.tile_programs == TilePrograms::own) return;
  const bool always = options_.tile_programs == TilePrograms::general;
  if (!always && !general_tiles_first()) return;
  // Own programs built ahead are warmed by the warm-up thread (build_tile_programs_ahead):
  // drawn with before it is idle, a first dispatch would generate their code on this one.
  gl::FirstDispatchWarmup* warmup = warmup_thread();
  const bool warmed = warmup == nullptr || (warmup->idle() && gl::shader_cache_writes_done());
  for (std::size_t a = 0; a < frame.passes.size(); ++a) {
    AtmospherePass& pass = frame.passes[a];
    const bool one_pass_tiles = std::any_of(frame.bands->begin(), frame.bands->end(),
                                            [&](const BandTiles& band) { return !band.lists[a].one_pass.empty(); });
    if (!pass.gpu || !one_pass_tiles) continue;
    pass.general_tiles = always || !warmed || !own_tile_programs_built(frame, a, frame.variant);
    if (pass.general_tiles) ++stats_.general_tile_atmospheres;
  }
  Impl& im = *impl_;
  if (stats_.general_tile_atmospheres == 0 && im.general_tile_frames > 0)
    spdlog::debug(
        "the atmospheres' tiles draw with their own programs from now on, after {} frame{} with the general ones",
        im.general_tile_frames, im.general_tile_frames == 1 ? "" : "s");
  im.general_tile_frames = stats_.general_tile_atmospheres > 0 ? im.general_tile_frames + 1 : 0;
}

void Renderer::build_tile_programs_ahead(const Frame& frame) {
  if (options_.tile_programs != TilePrograms::own_once_built) return;
  const bool general = std::any_of(frame.passes.begin(), frame.passes.end(),
                                   [](const AtmospherePass& pass) { return pass.general_tiles; });
  if (!general) return;
  // Started after the frame's bands, not with its programs: the warm-up
  // thread takes builds before first dispatches, and this frame's come first.
  for (std::size_t a = 0; a < frame.passes.size(); ++a) {
    const AtmospherePass& pass = frame.passes[a];
    if (!pass.general_tiles) continue;
    for (const BandTiles& band : *frame.bands)
      for (const auto& [tiles, list] : band.lists[a].one_pass)
        pass.gpu->start_tile_program(frame.variant, tiles, pass.eclipse_sky, gl::BuildFor::a_later_frame);
  }
  Impl& im = *impl_;
  im.builds->finish_ahead(warmup_thread(), dispatch_shapes(frame));
}

void Renderer::choose_variant(Frame& frame) {
  if (!live_variants()) return;
  Impl& im = *impl_;
  // Built and warmed: the warm-up thread has nothing left of the variants
  // built ahead, and the code it generated is in the driver's shader cache,
  // where this context's first dispatches find it (gl/shader_cache_writes.h).
  gl::FirstDispatchWarmup* warmup = warmup_thread();
  const auto warmed = [&] { return warmup == nullptr || (warmup->idle() && gl::shader_cache_writes_done()); };
  frame.variant = im.live_variants.choose(frame.wanted_variant,
                                          [&](const FrameVariant& v) { return variant_built(frame, v) && warmed(); });
  stats_.variant_held = frame.variant.key() != frame.wanted_variant.key();
  if (im.frames_held > 0 && !stats_.variant_held)
    spdlog::debug("frames draw with variant {} from now on, after {} drawn with the one before", frame.variant.key(),
                  im.frames_held);
  im.frames_held = stats_.variant_held ? im.frames_held + 1 : 0;
}

void Renderer::build_variants_ahead(const Frame& frame) {
  if (!live_variants()) return;
  Impl& im = *impl_;
  const bool shadows_can_fall = options_.atmosphere.eclipses && frame.scene.bodies.size() > 1;
  if (const std::optional<FrameVariant> next =
          im.live_variants.drew(frame.variant, frame.wanted_variant, shadows_can_fall,
                                [&](const FrameVariant& v) { return variant_built(frame, v); }))
    spdlog::debug("programs of variant {} building on a second thread for later frames (this one drew with {})",
                  next->key(), frame.variant.key());
  const std::optional<FrameVariant>& ahead = im.live_variants.building();
  if (!ahead) return;
  // Every program this frame's tiles would need of it: started where not
  // built (tiles change), finished where built, and its first dispatch warmed.
  start_variant_programs(frame, *ahead, gl::BuildFor::a_later_frame);
  gl::FirstDispatchWarmup* warmup = warmup_thread();
  const gl::DispatchShapes shapes = dispatch_shapes(frame);
  if (!im.builds->finish_ahead(warmup, shapes) || !variant_built(frame, *ahead)) return;
  if (warmup != nullptr) im.builds->warm(*warmup, shapes, variant_programs(frame, *ahead));
  if (warmup != nullptr && !warmup->idle()) return;
  spdlog::debug("programs of variant {} built on a second thread: later frames draw with them", ahead->key());
  im.live_variants.built_ahead();
}

void Renderer::start_variant_programs(const Frame& frame, const FrameVariant& variant, gl::BuildFor build_for) {
  Impl& im = *impl_;
  im.frame_programs.start(*im.builds, variant, build_for);
  // The night sky's, for a variant built ahead only: this frame's night pass
  // builds what it draws with, and a kind drawn long ago may not come back.
  if (build_for == gl::BuildFor::a_later_frame) im.night_sky.start_programs(*im.builds, variant, build_for);
  for (const BandTiles& band : *frame.bands)
    for (std::size_t a = 0; a < band.lists.size(); ++a) {
      const GpuAtmosphere* gpu = frame.passes[a].gpu;
      if (band.lists[a].gbuffer.count > 0) gpu->start_gbuffer_path_program(variant, build_for);
      // Where the Moon's shadow is near this air, its frames draw with the
      // shadow's tile programs or without them as it comes and goes (and as
      // its shadows build in the background): live, both are built, so that
      // no later frame builds one when it flips. Offline frames wait anyway.
      const bool flips = live_variants() && frame.occulter.shadow_on_the_air_of(frame.passes[a].body);
      // Tiles drawn with the general programs: their own build after the frame (build_tile_programs_ahead).
      const bool general = frame.passes[a].general_tiles && build_for == gl::BuildFor::this_frame;
      for (const auto& [list_tiles, list] : band.lists[a].one_pass) {
        const TileVariant tiles = general ? general_tile_variant(list_tiles) : list_tiles;
        gpu->start_tile_program(variant, tiles, frame.passes[a].eclipse_sky, build_for);
        if (flips) gpu->start_tile_program(variant, tiles, !frame.passes[a].eclipse_sky, build_for);
      }
    }
}

std::vector<const gl::ShaderProgram*> Renderer::variant_programs(const Frame& frame, const FrameVariant& variant) {
  Impl& im = *impl_;
  const FramePasses& p = im.frame_programs.passes_for(*im.builds, variant);
  std::vector<const gl::ShaderProgram*> programs = {p.gbuffer, p.resolve, p.direct_light_one, p.direct_light};
  if (p.direct_light_sun != nullptr) programs.push_back(p.direct_light_sun);
  for (const BandTiles& band : *frame.bands)
    for (std::size_t a = 0; a < band.lists.size(); ++a) {
      GpuAtmosphere* gpu = frame.passes[a].gpu;
      if (band.lists[a].gbuffer.count > 0) programs.push_back(&gpu->gbuffer_path_program(variant));
      for (const auto& [tiles, list] : band.lists[a].one_pass)
        programs.push_back(&gpu->tile_program(variant, tiles, frame.passes[a].eclipse_sky));
    }
  im.night_sky.add_programs(*im.builds, variant, programs);
  return programs;
}

gl::DispatchShapes Renderer::dispatch_shapes(const Frame& frame) const {
  const Impl& im = *impl_;
  gl::DispatchShapes shapes;
  for (const AtmospherePass& pass : frame.passes)
    if (pass.gpu) {
      pass.gpu->add_dispatch_shapes(shapes);
      break;  // one program serves every atmosphere: their tables are alike
    }
  if (im.albedo.texture().id() != 0) {
    const gl::TextureShape albedo = im.albedo.texture().shape();
    shapes.sampled[{static_cast<int>(binding::kAlbedoMapsUnit), albedo.kind}] = albedo;
  }
  BandResources::add_dispatch_shapes(shapes, frame.projection.width(),
                                     band_texture_rows(frame));  // as render_bands fits them
  return shapes;
}

void Renderer::light_by_the_moon(Frame& frame, const MoonInShadow* moon_shadow, PassTimer& timer) {
  if (!options_.night_sky.moonlight) return;
  MoonLight moon;
  timer.cpu("moonlight test", [&] { moon = moon_light(frame, moon_shadow); });
  for (std::size_t a = 0; a < frame.passes.size(); ++a) {
    frame.passes[a].moonlit = moon.lit[a];
    stats_.moonlight_bound = std::max(stats_.moonlight_bound, moon.bounds[a]);
  }
  if (moon.any()) frame.lights.push_back(std::move(moon.light));
}

void Renderer::light_by_the_sun(Frame& frame, PassTimer& timer) {
  if (!options_.skip_hidden_sunlight) return;
  std::vector<double> bounds;
  timer.cpu("sunlight test", [&] { bounds = sunlight_bounds(frame); });
  for (std::size_t a = 0; a < frame.passes.size(); ++a) {
    if (!frame.passes[a].gpu) continue;
    frame.passes[a].sunlit = bounds[a] >= kInvisibleDisplayStep;
    stats_.sunlight_bound = std::max(stats_.sunlight_bound, bounds[a]);
    stats_.sunlight_skipped = stats_.sunlight_skipped || !frame.passes[a].sunlit;
  }
}

void Renderer::prepare_programs(Frame& frame) {
  Impl& im = *impl_;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row)
      frame.camera_matrix[col * 3 + row] = static_cast<float>(frame.camera_to_world[col][row]);
  frame.gpu_projection = frame.projection.gpu();
  // Planar and cube-face projections: their affine ray's vectors in the world frame (frame.glsl).
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& v = frame.gpu_projection.params[k];
    const glm::dvec3 w = frame.camera_to_world * glm::dvec3(v[0], v[1], v[2]);
    frame.world_ray[k] = {static_cast<float>(w.x), static_cast<float>(w.y), static_cast<float>(w.z)};
  }
  // Programs are compiled per projection kind, and with the eclipse code only
  // when another body can cast a shadow (a CPU rasterizer runs all of it).
  FrameVariant& wanted = frame.wanted_variant;
  wanted.projection_kind = static_cast<int>(frame.gpu_projection.kind);
  wanted.eclipses = options_.atmosphere.eclipses && eclipses_possible(frame.scene);
  wanted.air_shadows = !frame.air_shadow_bodies.empty();  // its code costs a CPU rasterizer even unused
  wanted.albedo_lod0 = albedo_at_full_resolution(frame.scene, frame.pixel_angle, im.albedo.texture().width());
  frame.variant = live_variants() ? im.live_variants.provisional(wanted) : wanted;
  frame.sun_reach = sun_reach_rad(frame);
}

void Renderer::classify_bands(Frame& frame, PassTimer& timer) {
  Impl& im = *impl_;
  const int width = frame.projection.width(), height = frame.projection.height();
  const std::size_t rows_fit = std::max<std::size_t>(1, options_.max_band_pixels / static_cast<std::size_t>(width));
  frame.band_rows = static_cast<int>(std::max<std::size_t>(
      kTileSize, std::min<std::size_t>(static_cast<std::size_t>(height + kTileSize - 1) / kTileSize * kTileSize,
                                       rows_fit / kTileSize * kTileSize)));
  timer.cpu("tile classification", [&] {
    frame.bands =
        &im.frame_tiles.classify(frame.tile_scene(options_.sun_disc, options_.one_pass_tiles), height, frame.band_rows);
  });
  stats_.tiles_reused = im.frame_tiles.reused();
}

void Renderer::render_bands(Frame& frame, BandReader reader, const BandOutput& output, PassTimer& timer) {
  Impl& im = *impl_;
  const int width = frame.projection.width(), height = frame.projection.height(), band_rows = frame.band_rows;
  im.band.fit_bands(width, band_texture_rows(frame), reader);
  im.band.bind_bodies();
  im.band.end_frame();  // a no-op, unless a frame before stopped midway (an exception): its uploads are fenced now
  const std::vector<BandTiles>& bands = *frame.bands;

  for (int first_row = 0; first_row < height; first_row += band_rows) {
    const int rows = std::min(band_rows, height - first_row);
    ++stats_.bands;
    frame.band_origin = {0, first_row};
    frame.band_size = {width, rows};
    frame.band_ready.clear();

    if (frame.gpu_projection.kind == warp::ProjectionKind::ray_table)
      im.band.upload_rays(frame.projection, first_row, rows);
    // A copy: the night sky's pass clears the black flags of tiles it lights,
    // and the kept bands must stay as classified.
    BandTiles band = bands[static_cast<std::size_t>(first_row / band_rows)];
    add_tile_stats(band);
    im.band.upload_tile_lists(band);
    zero_unlit_tiles(frame, band, timer);
    draw_direct_tiles(frame, band, timer);
    for (const FrameLight& light : frame.lights) draw_atmosphere_tiles(frame, im.band, band, light, timer);
    // The stars and the night sky join the radiance before the band leaves
    // (readback, texture copy or the live display pass): one tone mapping for all.
    impl_->night_sky.draw_band(frame, *im.builds, im.band.uploads(), band, timer);
    output(band, timer);
    gl::check_gl_error(fmt::format("rendering rows {}–{} of '{}'", first_row, first_row + rows - 1, frame.scene.name));
  }
  im.band.end_frame();
}

void Renderer::zero_unlit_tiles(Frame& frame, const BandTiles& band, PassTimer& timer) {
  // Tiles the sun's pass leaves to black (render/frame/sun_light.h), zeroed
  // before the Moon's light, the night floor and the stars add to them:
  // on a CPU rasterizer the band's whole output by one buffer clear (a
  // memset), on a GPU by a pass over those tiles (UnlitTileZeroing).
  const gl::ShaderProgram* zero = frame.programs->zero_tiles;
  bool unlit = false;
  for (std::size_t a = 0; a < frame.passes.size(); ++a)
    for (const auto& [variant, list] : band.lists[a].one_pass) {
      if (!sky_and_ground_unlit(frame.passes[a], variant)) continue;
      unlit = true;
      if (zero != nullptr) timer.gpu("zero (sun below)", [&] { frame.dispatch_tiles(*zero, list); });
    }
  if (!unlit) return;
  if (zero == nullptr)
    timer.gpu("clear (sun below)", [&] { impl_->band.clear_output(band.rows); });
  else
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the later passes add to these pixels
}

void Renderer::add_tile_stats(const BandTiles& band) {
  for (std::size_t a = 0; a < band.lists.size(); ++a) {
    FrameStats::Atmosphere& st = stats_.atmospheres[a];
    st.sky_view_tiles += band.lists[a].sky_view_tiles;
    st.tiles += band.lists[a].tiles;
    st.gbuffer_tiles += band.lists[a].gbuffer_tiles;
  }
  stats_.tiles_gbuffer += band.gbuffer_tiles.count;
  stats_.tiles_one_atmosphere += band.one_pass_atmosphere_tiles;
  stats_.tiles_direct += band.direct_tiles();
  stats_.tiles_black += band.black_tiles();
}

// ---- the frame on the GPU (render_to_texture) ---------------------------------

void Renderer::render_to_texture(const scene::Scene& scene, const warp::Projection& projection, gl::Texture& target) {
  if (target.id() == 0 || target.is_3d() ||
      (target.format() != TextureFormat::rgba32f && target.format() != TextureFormat::rgba16f) ||
      target.width() != projection.width() || target.height() != projection.height())
    throw std::invalid_argument(fmt::format(
        "Renderer::render_to_texture: the target is a {} {}x{} texture; it must be a 2D rgba32f or rgba16f texture "
        "of the projection's size {}x{}",
        target.id() == 0 ? "missing" : gl::to_string(target.format()), target.width(), target.height(),
        projection.width(), projection.height()));
  render_frame(
      scene, projection, BandReader::gpu,
      [&](const BandTiles& band, PassTimer& timer) {
        impl_->band_to_texture.copy(impl_->band.bind_band_on_gpu(band), target, timer);
        impl_->band.end_band_on_gpu();  // the next band's passes rewrite what the copy read
      },
      [&](gl::FirstDispatchWarmup& warmup) { impl_->band_to_texture.warm(warmup, target.format()); });
}

void Renderer::render_on_gpu(const scene::Scene& scene, const warp::Projection& projection, const GpuBandSink& sink) {
  render_frame(
      scene, projection, BandReader::gpu,
      [&](const BandTiles& band, PassTimer& timer) {
        const GpuBand gpu_band = impl_->band.bind_band_on_gpu(band);
        timer.gpu("band output", [&] { sink(gpu_band); });
        impl_->band.end_band_on_gpu();  // the next band's passes rewrite what the sink read
      },
      impl_->band_sink_warmup);
}

}  // namespace zenith::render
