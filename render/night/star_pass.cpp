#include "render/night/star_pass.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "astro/moon_orientation.h"
#include "astro/moon_photometry.h"
#include "astro/star_catalogue.h"
#include "core/units.h"
#include "render/night/moon_in_shadow.h"
#include "render/night/night_sky_table.h"
#include "render/night/star_visibility.h"
#include "render/shader_bindings.h"
#include "render/shader_programs.h"
#include "scene/local_horizon.h"

namespace zenith::render {
namespace {

/// The atmospheres a star's light can cross: those resident this frame.
std::vector<StarAtmosphere> star_atmospheres(const FrameInProgress& frame) {
  std::vector<StarAtmosphere> out;
  for (const AtmospherePass& pass : frame.passes) {
    if (!pass.gpu) continue;
    const scene::Body& body = frame.scene.bodies[static_cast<std::size_t>(pass.body)];
    out.push_back(
        {body.position_m, pass.gpu->ground_radius_m(), pass.gpu->top_radius_m(), &pass.gpu->cpu_transmittance()});
  }
  return out;
}

/// The Moon's body axes in the world: from GCRS to the site's (east, north, up),
/// then turned with the disc by refraction's lift (`geometric` → `apparent`).
MoonWorldAxes moon_world_axes(const astro::MoonAxes& axes, const astro::SkyPositions& positions, const StarFrame& sky,
                              const glm::dvec3& geometric, const glm::dvec3& apparent) {
  const auto world = [&](const glm::dvec3& v) {
    const glm::dvec3 e = positions.gcrs_direction_enu(v);
    return glm::normalize(e.x * sky.east + e.y * sky.north + e.z * sky.up);
  };
  MoonWorldAxes out{world(axes.x), glm::dvec3(0.0), world(axes.z)};
  // Rodrigues' rotation about geometric × apparent by the angle between them.
  const glm::dvec3 k = glm::cross(geometric, apparent);
  const double s = glm::length(k), c = glm::dot(geometric, apparent);
  if (s > 0.0) {
    const glm::dvec3 axis = k / s;
    for (glm::dvec3* v : {&out[0], &out[2]})
      *v = *v * c + glm::cross(axis, *v) * s + axis * glm::dot(axis, *v) * (1.0 - c);
  }
  // Each axis came through ERFA alone: re-orthogonalized.
  out[2] = glm::normalize(out[2] - out[0] * glm::dot(out[0], out[2]));
  out[1] = glm::cross(out[2], out[0]);
  return out;
}

}  // namespace

StarFrame star_frame(const scene::Scene& scene, const warp::Projection& projection, const glm::dmat3& camera_to_world,
                     std::vector<StarAtmosphere> atmospheres, const std::vector<std::array<double, 3>>& rgb_weights,
                     RefractionCache& refractions) {
  const scene::SkyClock& clock = scene.sky_clock.value();
  const astro::AstroTime time = astro::AstroTime::from_utc(clock.time);
  const std::size_t site_body = scene.night_sky ? scene.night_sky->body : clock.body;
  const scene::Body& planet = scene.bodies.at(site_body);
  bool in_air = false;  // the camera inside the site body's atmosphere
  for (const StarAtmosphere& a : atmospheres)
    in_air = in_air ||
             (a.centre_m == planet.position_m && glm::length(scene.camera.position_m - a.centre_m) <= a.top_radius_m);
  StarFrame f;
  const scene::LocalHorizon horizon = scene::local_horizon_at(scene.camera.position_m, scene.bodies.at(clock.body));
  f.projection = &projection;
  f.closed_form_solid_angle = true;
  f.camera_m = scene.camera.position_m;
  f.world_to_camera = glm::transpose(camera_to_world);
  f.east = horizon.east;
  f.north = horizon.north;
  f.up = horizon.up;
  if (in_air && clock.body == site_body && planet.atmosphere) {
    const double altitude_m = std::max(0.0, glm::length(scene.camera.position_m - planet.position_m) - planet.radius_m);
    f.refraction = refractions.get(*planet.atmosphere, altitude_m);
    if (f.refraction && scene.night_sky && scene.night_sky->scintillation && scene.night_sky->body == clock.body) {
      // One draw per star and integration interval of the sky's clock (seconds from J2000 UTC).
      const astro::ScintillationOptions& twinkle = *scene.night_sky->scintillation;
      const double seconds = ((time.utc().day1 - 2451545.0) + time.utc().day2) * 86400.0;
      f.set_twinkling(twinkle, static_cast<std::int64_t>(std::floor(seconds / twinkle.integration_s)), altitude_m,
                      f.refraction->ground_refractivity());
    }
  }
  f.atmospheres = std::move(atmospheres);
  for (const StarAtmosphere& a : f.atmospheres) f.transmittances.emplace_back(a, f.camera_m);
  for (const scene::Body& b : scene.bodies) f.occluders.emplace_back(b.position_m, b.radius_m);
  f.rgb_weights = rgb_weights;
  f.exposure = scene.camera.exposure;
  // Rejections before the per-star work: the view's cone widened by refraction's
  // largest lift (under 1°) and a splat's reach (two pixels, at most 5°), and the ground.
  const double margin = 1.0 * core::kDeg + std::min(2.0 * projection.max_pixel_angle_rad(), 5.0 * core::kDeg);
  const auto [axis, cos_limit] = view_cone(projection, margin);
  f.view_axis = glm::normalize(camera_to_world * axis);
  f.view_cos_limit = cos_limit;
  const double r = glm::length(scene.camera.position_m - scene.bodies.at(clock.body).position_m);
  const double dip = std::acos(std::min(1.0, scene.bodies.at(clock.body).radius_m / r));  // the horizon's depression
  f.lowest_sin_altitude = std::sin(std::max(-0.5 * core::kPi, -dip - 2.0 * core::kDeg));
  return f;
}

NightSkyPass::NightSkyPass(const NightSkyRenderOptions& options, RefractionCache& refractions)
    : options_(options), refractions_(refractions) {}
NightSkyPass::~NightSkyPass() = default;

bool NightSkyPass::ensure_field(const scene::Scene& scene) {
  if (field_ && field_->wavelengths_nm() == scene.wavelengths_nm) return true;
  if (catalogue_failed_) return false;
  try {
    astro::StarCatalogueOptions o;
    o.directory = options_.star_directory;
    o.magnitude_limit = options_.star_magnitude_limit;
    astro::StarCatalogue catalogue = field_ ? field_->catalogue() : astro::load_star_catalogue(o);
    spdlog::info("night sky: {} stars to V {} from {} (identity {})", catalogue.stars.size(), catalogue.magnitude_limit,
                 options_.star_directory.string(), catalogue.identity_sha256.substr(0, 16));
    field_ = std::make_unique<StarField>(std::move(catalogue), scene.wavelengths_nm);
    return true;
  } catch (const std::exception& e) {
    spdlog::warn("night sky: no stars drawn: {} (scripts/bootstrap installs stellarium-data)", e.what());
    catalogue_failed_ = true;
    return false;
  }
}

void NightSkyPass::prepare(const FrameInProgress& frame, const MoonInShadow* moon_shadow, PassTimer& timer) {
  stats_ = NightSkyStats{};
  moon_shadow_ = moon_shadow;
  splats_.clear();
  floor_ = false;
  const scene::Scene& scene = frame.scene;
  const bool want_stars = (options_.stars || options_.moon) && scene.sky_clock.has_value();
  const bool want_floor = options_.night_floor && (scene.night_sky.has_value() || scene.sky_clock.has_value());
  if (!want_stars && !want_floor) return;
  const std::size_t site_body = scene.night_sky ? scene.night_sky->body : scene.sky_clock->body;
  const scene::Body& planet = scene.bodies.at(site_body);
  const double exposure = scene.camera.exposure;
  std::vector<StarAtmosphere> atmospheres = star_atmospheres(frame);
  const StarAtmosphere* air = nullptr;  // the site body's atmosphere, when the camera is inside it
  for (const StarAtmosphere& a : atmospheres)
    if (a.centre_m == planet.position_m && glm::length(scene.camera.position_m - a.centre_m) <= a.top_radius_m)
      air = &a;

  // ---- the night floor and the glow: a table of the frame's camera.
  if (want_floor && air && planet.atmosphere) {
    const astro::NightSkyFloorOptions floor_options =
        scene.night_sky ? scene.night_sky->floor : astro::NightSkyFloorOptions{};
    const astro::LightPollutionOptions glow_options =
        scene.night_sky ? scene.night_sky->light_pollution : astro::LightPollutionOptions{};
    const std::string key =
        fmt::format("{} {} {} {} {}", air->transmittance->hash, floor_options.zenith_v_mag_arcsec2,
                    floor_options.airglow_height_m, glow_options.zenith_mcd_m2, glow_options.colour_temperature_K);
    if (key != floor_key_) {
      const atmosphere::AtmosphereModel& model = planet.atmosphere->loaded.model;
      night_floor_ = std::make_unique<astro::NightSkyFloor>(model, floor_options);
      light_pollution_ =
          glow_options.zenith_mcd_m2 > 0.0 ? std::make_unique<astro::LightPollution>(model, glow_options) : nullptr;
      floor_key_ = key;
    }
    timer.cpu("night sky table", [&] {
      const NightSkyTable t = night_sky_table(*air, scene.camera.position_m, night_floor_.get(), light_pollution_.get(),
                                              frame.rgb_weights, exposure);
      // The test: could the brightest direction move a display value by half
      // a code step, on the darkest sky the atmosphere passes draw (the floor
      // goes on pixels of sky only; zeros where that bound does not apply:
      // then on black)?
      // A channel can go below its background only through a negative colour weight.
      const bool may_subtract = !colour_weights_non_negative(frame.rgb_weights);
      const std::array<double, 3> sky = options_.skip_hidden_floor
                                            ? darkest_sky(frame, site_body, exposure, frame.rgb_weights)
                                            : std::array<double, 3>{0.0, 0.0, 0.0};
      if (largest_code_change(sky, t.largest, may_subtract) >= kInvisibleCodeChange) {
        floor_ = true;
        floor_table_ = t.rgb;
        floor_up_ = t.up;
        floor_horizon_mu_ = t.horizon_mu;
      }
    });
  }

  // ---- the stars and the Moon: the sky clock's frame.
  moon_disc_ = false;
  if (want_stars) {
    const scene::SkyClock& clock = *scene.sky_clock;
    const astro::AstroTime time = astro::AstroTime::from_utc(clock.time);
    StarFrame f =
        star_frame(scene, frame.projection, frame.camera_to_world, atmospheres, frame.rgb_weights, refractions_);
    if (options_.stars && ensure_field(scene) && field_->size() > 0) {
      timer.cpu("star test",
                [&] { stats_.star_test = star_visibility(frame, *field_, f, time, clock.site, directions_); });
      if (stats_.star_test.could_show || !options_.skip_hidden_stars) {
        timer.cpu("star placement", [&] {
          // The test's directions where its second stage turned the catalogue to the instant.
          if (directions_.empty()) field_->directions_enu(time, clock.site, directions_);
          // The star test's deviates for the interval, where it drew them.
          if (f.scintillation) f.scintillation_normals = field_->scintillation_normals(f.scintillation_interval);
          splats_ = star_splats(*field_, directions_, f);
        });
        stats_.catalogue_identity = field_->catalogue().identity_sha256;
        stats_.moon_map_identity = moon_map().identity_sha256();  // the sky data a cluster compares
      }
    }
    stats_.stars = splats_.size();
    if (options_.moon) timer.cpu("moon", [&] { place_moon(frame, f); });
  }
  stats_.night_floor = floor_;
  stats_.drawn = !splats_.empty() || floor_ || moon_disc_;
}

void NightSkyPass::place_moon(const FrameInProgress& frame, const StarFrame& sky) {
  const astro::SkyPositions& positions = frame.sky.positions();
  const astro::MoonPlace moon = positions.moon();
  const glm::dvec3 enu = moon.horizontal.east_north_up();
  glm::dvec3 d = enu.x * sky.east + enu.y * sky.north + enu.z * sky.up;
  const glm::dvec3 geometric = glm::normalize(d);
  if (sky.refraction) {
    const double apparent = sky.refraction->apparent_from_true_rad(moon.horizontal.altitude_rad);
    const glm::dvec3 level = enu[0] * sky.east + enu[1] * sky.north;
    if (glm::length(level) > 0.0) d = glm::normalize(level) * std::cos(apparent) + sky.up * std::sin(apparent);
  }
  d = glm::normalize(d);
  for (const auto& [centre, radius] : sky.occluders) {  // the ground, another body
    const glm::dvec3 p = sky.camera_m - centre;
    const double b = glm::dot(p, d), c = glm::dot(p, p) - radius * radius;
    if (c > 0.0 && b < 0.0 && b * b >= c) return;
  }
  const std::size_t n = frame.rgb_weights.size();
  std::vector<double> transmittance(n, 1.0), one(n);
  for (const StarAtmosphere& a : sky.atmospheres) {
    star_transmittance(a, sky.camera_m, d, one.data());
    for (std::size_t k = 0; k < n; ++k) transmittance[k] *= one[k];
  }
  const auto pixel = frame.projection.pixel(frame.world_to_camera * d);
  if (!pixel) return;
  const double omega = frame.projection.pixel_solid_angle_by_rays_sr(pixel->x, pixel->y);
  if (!(omega > 0.0)) return;
  const double radius_px = moon.angular_radius_rad / std::sqrt(omega);
  const double w = frame.projection.width(), h = frame.projection.height();
  if (pixel->x < -radius_px - 2 || pixel->x > w + radius_px + 2 || pixel->y < -radius_px - 2 ||
      pixel->y > h + radius_px + 2)
    return;
  const std::vector<double>& wavelengths = frame.scene.wavelengths_nm;
  if (radius_px < 1.0) {
    // Smaller than a pixel: a point source of the whole Moon's irradiance, as a star.
    const glm::dvec2 at = on_splat_grid(*pixel);  // as the stars (star_placement.h)
    if (!splat_touches_image(at, w, h)) return;
    const double omega_at = frame.projection.pixel_solid_angle_by_rays_sr(at.x, at.y);
    if (!(omega_at > 0.0)) return;
    std::vector<double> e = astro::moon_irradiance_W_m2_nm(moon, wavelengths);
    if (moon_shadow_ && moon_shadow_->shadowed())  // a lunar eclipse: the face's mean light left
      for (std::size_t k = 0; k < n; ++k) e[k] *= moon_shadow_->face()[k];
    StarSplat s;
    s.x_px = static_cast<float>(at.x);
    s.y_px = static_cast<float>(at.y);
    for (std::size_t c = 0; c < 3; ++c) {
      double v = 0.0;
      for (std::size_t k = 0; k < n; ++k) v += frame.rgb_weights[k][c] * e[k] * transmittance[k];
      s.rgb[c] = static_cast<float>(v * sky.exposure / omega_at);
    }
    splats_.insert(std::upper_bound(splats_.begin(), splats_.end(), s,
                                    [](const StarSplat& a, const StarSplat& b) { return a.y_px < b.y_px; }),
                   s);
    stats_.moon = true;
    return;
  }
  // A disc: L = 2 L_LS(1, 1) · μ0/(μ0 + μ) per point (the shape factor is grey).
  moon_rgb_ = {0, 0, 0};
  double largest = 0.0;
  std::vector<double> radiance(n);
  for (std::size_t k = 0; k < n; ++k) {
    radiance[k] = 2.0 *
                  astro::moon_disc_radiance(1.0, 1.0, moon.phase_angle_rad, wavelengths[k], moon.sun_distance_au) *
                  transmittance[k];
    for (std::size_t c = 0; c < 3; ++c) moon_rgb_[c] += frame.rgb_weights[k][c] * radiance[k] * sky.exposure;
  }
  // The face: the map's albedo relative to its photometric mean over the lit
  // disc, so the disc keeps the Moon's irradiance (moon_albedo_map.h).
  const MoonAlbedoMap& map = moon_map();
  moon_axes_ = moon_world_axes(astro::moon_orientation(positions).axes, positions, sky, geometric, d);
  const double mean = moon_disc_mean_albedo(map, moon_axes_, d, frame.sun);
  for (double& v : moon_rgb_) v /= mean;
  // A pixel spans 1/radius_px of the Moon's radius at the centre; a texel 2π/width.
  moon_map_lod_ = std::max(0.0, std::log2(map.width() / (2.0 * core::kPi * radius_px)));
  moon_shadow_table_.clear();
  if (moon_shadow_ && moon_shadow_->shadowed()) {
    // A lunar eclipse: the disc's colour by a point's distance from the shadow's axis, over [0, reach].
    const MoonInShadow& shadow = *moon_shadow_;
    for (int j = 0; j < kMoonShadowEntries; ++j) {
      const double y = shadow.reach_m() * j / (kMoonShadowEntries - 1);
      std::array<double, 3> rgb{};
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t c = 0; c < 3; ++c)
          rgb[c] += frame.rgb_weights[k][c] * radiance[k] * shadow.illumination(y, k) * sky.exposure / mean;
      moon_shadow_table_.push_back({float(rgb[0]), float(rgb[1]), float(rgb[2]), 0.0f});
      for (double v : rgb) largest = std::max(largest, std::abs(v) * map.largest());
    }
  } else {
    for (double v : moon_rgb_) largest = std::max(largest, std::abs(v) * map.largest());
  }
  if (largest < kInvisibleDisplayStep) return;
  stats_.moon_map_identity = map.identity_sha256();
  stats_.moon_mean_albedo = mean;
  moon_disc_ = true;
  stats_.moon = true;
  moon_direction_ = d;
  moon_radius_rad_ = moon.angular_radius_rad;
  moon_radius_px_ = radius_px;
  moon_pixel_ = *pixel;
}

const MoonAlbedoMap& NightSkyPass::moon_map() {
  if (moon_map_) return *moon_map_;
  try {
    moon_map_ = std::make_unique<MoonAlbedoMap>(MoonAlbedoMap::load(options_.moon_albedo_map));
    spdlog::info("night sky: the Moon's albedo map {} ({} × {}, identity {})", options_.moon_albedo_map.string(),
                 moon_map_->width(), moon_map_->height(), moon_map_->identity_sha256().substr(0, 16));
  } catch (const std::exception& e) {
    spdlog::warn("night sky: the Moon's disc has a uniform albedo: {} (scripts/bootstrap installs stellarium-data)",
                 e.what());
    moon_map_ = std::make_unique<MoonAlbedoMap>(MoonAlbedoMap::uniform());
  }
  return *moon_map_;
}

namespace {

/// night_sky.comp's defines for one kind of tile of a frame variant.
std::vector<gl::ShaderDefine> night_sky_defines(const FrameVariant& frame, const NightSkyVariant& tiles) {
  std::vector<gl::ShaderDefine> defines = frame.defines();
  const auto flag = [](bool on) { return std::string(on ? "1" : "0"); };
  defines.push_back({"NIGHT_FLOOR", flag(tiles.floor)});
  defines.push_back({"NIGHT_MOON", flag(tiles.moon)});
  defines.push_back({"NIGHT_BODIES", flag(tiles.bodies)});
  return defines;
}

constexpr const char* kNightSky = "render/night_sky.comp";
constexpr const char* kStarPixels = "render/star_pixels.comp";

}  // namespace

void NightSkyPass::start_programs(gl::ProgramBuilds& builds, const FrameVariant& variant,
                                  gl::BuildFor build_for) const {
  for (const int kind : kinds_drawn_)
    start_built_program(builds, kNightSky, night_sky_defines(variant, NightSkyVariant::from_key(kind)), build_for);
  if (star_pixels_drawn_) start_built_program(builds, kStarPixels, variant.defines(), build_for);
}

bool NightSkyPass::programs_built(const gl::ProgramBuilds& builds, const FrameVariant& variant) const {
  for (const int kind : kinds_drawn_)
    if (!program_built(builds, kNightSky, night_sky_defines(variant, NightSkyVariant::from_key(kind)))) return false;
  return !star_pixels_drawn_ || program_built(builds, kStarPixels, variant.defines());
}

void NightSkyPass::add_programs(gl::ProgramBuilds& builds, const FrameVariant& variant,
                                std::vector<const gl::ShaderProgram*>& programs) const {
  for (const int kind : kinds_drawn_)
    programs.push_back(&built_program(builds, kNightSky, night_sky_defines(variant, NightSkyVariant::from_key(kind))));
  if (star_pixels_drawn_) programs.push_back(&built_program(builds, kStarPixels, variant.defines()));
}

void NightSkyPass::draw_band(FrameInProgress& frame, gl::ProgramBuilds& builds, gl::UploadStream& uploads,
                             BandTiles& band, PassTimer& timer) {
  if (!stats_.drawn) return;
  const int width = frame.band_size[0], rows = band.rows, columns = frame.cones->columns();
  // The band's stars: those whose 2 × 2 footprint reaches its rows (splats_ is sorted by y).
  const auto begin = std::lower_bound(splats_.begin(), splats_.end(), static_cast<float>(band.first_row) - 1.0f,
                                      [](const StarSplat& s, float y) { return s.y_px < y; });
  const auto end = std::lower_bound(begin, splats_.end(), static_cast<float>(band.first_row + rows) + 1.0f,
                                    [](const StarSplat& s, float y) { return s.y_px < y; });
  const std::size_t count = static_cast<std::size_t>(end - begin);
  if (count == 0 && !floor_ && !moon_disc_) return;

  // The pixels the band's splats reach, each once (band pixel y · width + x):
  // star_pixels.comp adds the accumulator there and nowhere else.
  const std::size_t tiles = band.tiles;
  const auto tile_of = [&](int x, int band_y) {
    return static_cast<std::size_t>(band_y / kTileSize) * static_cast<std::size_t>(columns) +
           static_cast<std::size_t>(x / kTileSize);
  };
  std::vector<std::uint8_t> star_touched(tiles, 0), moon_touched(tiles, 0);
  star_pixels_.clear();
  pixel_listed_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(rows), 0);
  for (auto s = begin; s != end; ++s) {
    const int x0 = static_cast<int>(std::floor(s->x_px - 0.5f)), y0 = static_cast<int>(std::floor(s->y_px - 0.5f));
    for (int y = y0; y <= y0 + 1; ++y)
      for (int x = x0; x <= x0 + 1; ++x) {
        const int by = y - band.first_row;
        if (x < 0 || x >= width || by < 0 || by >= rows) continue;
        const auto pixel = static_cast<std::uint32_t>(by * width + x);
        if (pixel_listed_[pixel]) continue;
        pixel_listed_[pixel] = 1;
        star_pixels_.push_back(pixel);
        star_touched[tile_of(x, by)] = 1;
      }
  }
  for (const std::uint32_t pixel : star_pixels_) pixel_listed_[pixel] = 0;
  if (moon_disc_) {  // the disc's tiles, with two pixels for its edge
    const double reach = moon_radius_px_ + 2.0;
    for (int y = std::max(0, static_cast<int>(moon_pixel_.y - reach) - band.first_row);
         y < std::min(rows, static_cast<int>(moon_pixel_.y + reach) + 1 - band.first_row); y += 1)
      for (int x = std::max(0, static_cast<int>(moon_pixel_.x - reach));
           x < std::min(width, static_cast<int>(moon_pixel_.x + reach) + 1); x += 1)
        moon_touched[tile_of(x, y)] = 1;
  }
  // Tiles for night_sky.comp: the band's drawn tiles (the floor goes on every
  // sky pixel), else only those the Moon's disc reaches; black tiles a star or
  // the disc reaches are overwritten (from zero: the stars add to them after).
  // Each list gets the program for what its tiles hold (NightSkyVariant): the
  // Moon's code only where the disc is, the ray's body test only where a body
  // can be, no floor-only tile whose every ray meets a body.
  // The lists by program and by overwrite, in a fixed order (the map's): every node dispatches alike.
  std::map<std::pair<int, bool>, std::vector<std::uint32_t>> by_list;
  for (std::size_t t = 0; t < tiles; ++t) {
    const bool moon = moon_touched[t] != 0;
    const TileCover bodies = band.bodies.empty() ? TileCover::some : band.bodies[t];
    const bool overwrite = band.black[t] != 0;
    if (overwrite ? !star_touched[t] && !moon : !moon && (!floor_ || bodies == TileCover::all))
      continue;  // nothing drawn there and nothing to add, or the floor only on no sky
    const NightSkyVariant v{floor_, moon, bodies != TileCover::none};
    by_list[{v.key(), overwrite}].push_back(
        pack_tile(static_cast<std::uint32_t>(t % static_cast<std::size_t>(columns)),
                  static_cast<std::uint32_t>(t / static_cast<std::size_t>(columns))));
    if (overwrite) band.black[t] = 0;  // drawn now
  }
  std::vector<std::uint32_t> lists;
  for (const auto& [key, list] : by_list) lists.insert(lists.end(), list.begin(), list.end());
  if (lists.empty() && star_pixels_.empty()) return;

  // The accumulator: a 64-bit fixed-point value per pixel and channel of a
  // constant step (star_accumulator.glsl), the same on every node and band.
  const std::size_t accumulator_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(rows) *
                                        kStarAccumulatorUintsPerPixel * sizeof(std::uint32_t);
  if (accumulator_bytes > accumulator_bytes_) {
    std::vector<std::uint32_t> zeros(accumulator_bytes / sizeof(std::uint32_t), 0);
    accumulator_ = gl::Buffer::from(std::span<const std::uint32_t>(zeros));
    accumulator_bytes_ = accumulator_bytes;
  }
  accumulator_.bind_storage(binding::kStarAccumulator);
  if (count > 0) {
    if (splat_.id() == 0) splat_ = load_compute_program("render/star_splat.comp");
    std::vector<std::array<float, 4>> data;
    data.reserve(2 * count);
    for (auto s = begin; s != end; ++s) {
      data.push_back({s->x_px, s->y_px, 0.0f, 0.0f});
      data.push_back({s->rgb[0], s->rgb[1], s->rgb[2], 0.0f});
    }
    uploads.upload(std::span<const std::array<float, 4>>(data)).bind_storage(binding::kStarSplats);
    splat_.set_uniform("star_count", static_cast<int>(count));
    splat_.set_uniform("band_origin", std::array<int, 2>{0, band.first_row});
    splat_.set_uniform("band_size", std::array<int, 2>{width, rows});
    timer.gpu("stars", [&] { splat_.dispatch(static_cast<unsigned>((count + 63) / 64)); });
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }

  uploads.upload(std::span<const std::uint32_t>(lists)).bind_storage(binding::kTiles);
  // The floor's table, then the eclipsed Moon's: one buffer at NIGHT_SKY_TABLE_BINDING.
  const std::size_t moon_shadow_first = floor_ ? floor_table_.size() : 0;
  if (floor_ || !moon_shadow_table_.empty()) {
    std::vector<std::array<float, 4>> tables = floor_ ? floor_table_ : std::vector<std::array<float, 4>>{};
    tables.insert(tables.end(), moon_shadow_table_.begin(), moon_shadow_table_.end());
    uploads.upload(std::span<const std::array<float, 4>>(tables)).bind_storage(binding::kNightSkyTable);
  }
  const auto vec = [](const glm::dvec3& v) {
    return std::array<float, 3>{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
  };
  std::size_t offset = 0;
  for (const auto& [key, list] : by_list) {
    const NightSkyVariant v = NightSkyVariant::from_key(key.first);
    const gl::ShaderProgram& p = frame.prepare(built_program(builds, kNightSky, night_sky_defines(frame.variant, v)));
    kinds_drawn_.insert(key.first);
    if (v.moon) {
      p.set_uniform("moon_direction", vec(moon_direction_));
      p.set_uniform("moon_radius", static_cast<float>(moon_radius_rad_));
      p.set_uniform("moon_rgb", std::array<float, 3>{static_cast<float>(moon_rgb_[0]), static_cast<float>(moon_rgb_[1]),
                                                     static_cast<float>(moon_rgb_[2])});
      const bool mapped = !moon_map().is_uniform();
      p.set_uniform("moon_mapped", mapped ? 1 : 0);
      p.set_uniform("moon_shadowed", moon_shadow_table_.empty() ? 0 : 1);
      if (!moon_shadow_table_.empty()) {
        const MoonInShadow& shadow = *moon_shadow_;
        p.set_uniform("moon_shadow_centre", vec(shadow.moon_centre_m()));
        p.set_uniform("moon_shadow_axis", vec(shadow.axis()));
        p.set_uniform("moon_shadow_radius", static_cast<float>(shadow.moon_radius_m()));
        p.set_uniform("moon_shadow_reach", static_cast<float>(shadow.reach_m()));
        p.set_uniform("moon_shadow_first", static_cast<int>(moon_shadow_first));
        p.set_uniform("moon_shadow_entries", kMoonShadowEntries);
      }
      if (mapped) {
        if (moon_texture_.id() == 0) {  // once per renderer
          moon_texture_ = gl::Texture::create_2d_mipmapped(gl::TextureFormat::r32f, moon_map().width(),
                                                           moon_map().height(), moon_map().texels());
          moon_texture_.set_repeat_s(true);
        }
        moon_texture_.bind(binding::kMoonAlbedoUnit);
        p.set_uniform("moon_axis_x", vec(moon_axes_[0]));
        p.set_uniform("moon_axis_y", vec(moon_axes_[1]));
        p.set_uniform("moon_axis_z", vec(moon_axes_[2]));
        p.set_uniform("moon_map_lod", static_cast<float>(moon_map_lod_));
      }
    }
    if (v.floor) {
      p.set_uniform("night_sky_entries", static_cast<int>(floor_table_.size()));
      p.set_uniform("night_up", vec(floor_up_));
      p.set_uniform("night_horizon_mu", static_cast<float>(floor_horizon_mu_));
    }
    p.set_uniform("overwrite", key.second ? 1 : 0);
    timer.gpu("night sky", [&] { frame.dispatch_tiles(p, TileList{offset, list.size()}); });
    offset += list.size();
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  if (star_pixels_.empty()) return;
  // Then the stars, on the pixels their splats reach (after the tiles' writes above).
  uploads.upload(std::span<const std::uint32_t>(star_pixels_)).bind_storage(binding::kStarPixelList);
  const gl::ShaderProgram& p = frame.prepare(built_program(builds, kStarPixels, frame.variant.defines()));
  star_pixels_drawn_ = true;
  p.set_uniform("star_pixel_count", static_cast<int>(star_pixels_.size()));
  timer.gpu("stars", [&] { p.dispatch(static_cast<unsigned>((star_pixels_.size() + 63) / 64)); });
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace zenith::render
