// The night sky's pass (render/night/star_pass.h, render/night/star_placement.h):
// stars placed by the rotating sky against ERFA, their extinction from the
// transmittance table, the same energy through a fisheye, a planar view and a
// warp mesh, the night floor's radiance at the zenith, the pass skipped by its
// own test, and the GPU path (render_to_texture) equal to the read-back frame.
//
// Small images (≤ 64²), stars to V 1.5 (the catalogue's first file), the
// shared small tables. Needs stellarium-data (scripts/bootstrap); skipped without it.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "../atmosphere/lut_fixture.h"
#include "astro/moon_orientation.h"
#include "astro/moon_photometry.h"
#include "astro/night_sky_floor.h"
#include "astro/refraction.h"
#include "astro/scintillation.h"
#include "astro/sky_positions.h"
#include "astro/star_catalogue.h"
#include "astro/star_photometry.h"
#include "atmosphere/lut/sky_radiance_lower_bound.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/photometry.h"
#include "core/units.h"
#include "image/colour.h"
#include "image/tone_mapping.h"
#include "render/frame/frame_conditions.h"
#include "render/frame/frame_sky.h"
#include "render/gl/texture.h"
#include "render/night/moon_albedo_map.h"
#include "render/night/moon_in_shadow.h"
#include "render/night/star_pass.h"
#include "render/night/star_placement.h"
#include "render/night/star_visibility.h"
#include "render/renderer.h"
#include "scene/local_horizon.h"
#include "tests/render/code_difference.h"
#include "tests/render/greenwich_night.h"
#include "tests/render/render_test_support.h"
#include "tests/render/variant_switch.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"
#include "warp/warped_projection.h"

namespace zenith::render {
namespace {

using atmosphere::lut::SmallTables;
using core::kDeg;

#define REQUIRE_CATALOGUE()                                                                        \
  if (!std::filesystem::exists(astro::kStellariumStarDirectory / "stars_0_0v0_8.cat"))             \
  GTEST_SKIP() << "stellarium-data is not installed (" << astro::kStellariumStarDirectory.string() \
               << "): scripts/bootstrap installs it"

constexpr double kLatitudeDeg = testing::kGreenwichLatitudeDeg, kLongitudeDeg = testing::kGreenwichLongitudeDeg;
const astro::UtcTime kTime{2026, 1, 15, 23, 0, 0.0};  // Sirius due south, 20° up at Greenwich

astro::StarCatalogue bright_stars() {
  astro::StarCatalogueOptions o;
  o.magnitude_limit = 1.5;
  return astro::load_star_catalogue(o);
}

/// The Earth at the origin, the sky clock at Greenwich on kTime (testing::greenwich).
scene::Scene greenwich(const std::string& preset, const glm::dvec3& look_enu, double exposure) {
  return testing::greenwich(preset, look_enu, exposure, kTime);
}

RenderOptions options(bool stars, bool floor) {
  RenderOptions o;
  o.colour = image::ColourMapping::direct;  // channel c = radiance at 680, 550, 440 nm × exposure
  o.sun_disc = false;
  o.night_sky.stars = stars;
  o.night_sky.night_floor = floor;
  o.night_sky.star_magnitude_limit = 1.5;
  o.night_sky.moon = false;
  return o;
}

/// options() without the Moon's light: the twilight sky of the sun alone.
RenderOptions twilight_options(bool stars, bool floor) {
  RenderOptions o = options(stars, floor);
  o.night_sky.moonlight = false;
  return o;
}

/// `o` with one of the night sky's tests against the sky off: the frame that
/// draws that pass wherever the test against a black sky lets it.
RenderOptions without_sky_test(RenderOptions o, bool NightSkyRenderOptions::*skip_hidden) {
  o.night_sky.*skip_hidden = false;
  return o;
}

using testing::TestRenderer;

/// Sirius (the catalogue's brightest) in the site's east-north-up frame at kTime, geometric.
glm::dvec3 sirius_enu(const astro::StarCatalogue& c) {
  const astro::SkyPositions sky(astro::AstroTime::from_utc(kTime), astro::Site{kLatitudeDeg, kLongitudeDeg, 46.0});
  return sky.star(c.stars.front()).east_north_up();
}

/// Σ (L − L_background) Ω over the pixels within `radius_px` of `centre`, per
/// channel; Ω from each pixel's corner rays.
std::array<double, 3> energy_near(const std::vector<float>& image, const std::vector<float>& background,
                                  const warp::Projection& p, glm::dvec2 centre, double radius_px) {
  std::array<double, 3> sum{0, 0, 0};
  for (int y = 0; y < p.height(); ++y)
    for (int x = 0; x < p.width(); ++x) {
      if (glm::length(glm::dvec2(x + 0.5, y + 0.5) - centre) > radius_px) continue;
      const auto a = p.ray(x, y), b = p.ray(x + 1, y), c = p.ray(x, y + 1), d = p.ray(x + 1, y + 1);
      if (!a || !b || !c || !d) continue;
      const glm::dvec3 na = glm::normalize(*a), nb = glm::normalize(*b), nc = glm::normalize(*c),
                       nd = glm::normalize(*d);
      const double omega =
          0.5 * (glm::length(glm::cross(nb - na, nc - na)) + glm::length(glm::cross(nb - nd, nc - nd)));
      for (int k = 0; k < 3; ++k) {
        const std::size_t i = (static_cast<std::size_t>(y) * p.width() + x) * 3 + k;
        sum[k] += (double(image[i]) - background[i]) * omega;
      }
    }
  return sum;
}

// ------------------------------------------------------------------------- CPU

TEST(StarField, TheTurningSkyFollowsErfaWithinAnArcsecondOverSixHours) {
  REQUIRE_CATALOGUE();
  StarField field(bright_stars(), {680.0, 550.0, 440.0});
  const astro::Site site{kLatitudeDeg, kLongitudeDeg, 46.0};
  const astro::AstroTime t0 = astro::AstroTime::from_utc(kTime);
  std::vector<glm::dvec3> epoch, later;
  field.directions_enu(t0, site, epoch);
  for (double dt_s : {600.0, 3600.0, 6.0 * 3600.0 - 1.0}) {
    field.directions_enu(t0.plus_seconds(dt_s), site, later);  // rotated from the epoch
    const astro::SkyPositions erfa(t0.plus_seconds(dt_s), site);
    double worst = 0.0, moved = 0.0;
    for (std::size_t i = 0; i < field.size(); ++i) {
      const glm::dvec3 e = erfa.star(field.catalogue().stars[i]).east_north_up();
      worst = std::max(worst, std::acos(std::min(1.0, glm::dot(later[i], e))));
      moved = std::max(moved, std::acos(std::min(1.0, glm::dot(later[i], epoch[i]))));
    }
    EXPECT_LT(worst / kDeg * 3600.0, 1.0) << dt_s << " s after the epoch";
    EXPECT_GT(moved / kDeg, 0.9 * dt_s / 240.0) << "stars near the equator turn 15° an hour";
  }
}

TEST(StarField, TransmittanceIsTheTablesAndZeroThroughTheGroundAndOneOutside) {
  const SmallTables& t = SmallTables::get("earth-advanced");
  const atmosphere::lut::TableQueries q(t.model, t.tables);
  const StarAtmosphere a{{0, 0, 0}, t.model.ground_radius_m, t.model.top_radius_m, &t.tables};
  const glm::dvec3 camera(0, 0, t.model.ground_radius_m + 2.0);
  std::array<double, 8> got{}, want{};
  for (double elevation_deg : {90.0, 30.0, 5.0, 1.0}) {
    const glm::dvec3 d(std::cos(elevation_deg * kDeg), 0, std::sin(elevation_deg * kDeg));
    star_transmittance(a, camera, d, got.data());
    q.transmittance_to_top(glm::length(camera), d.z, want.data());
    for (std::size_t k = 0; k < t.tables.channels; ++k) EXPECT_NEAR(got[k], want[k], 1e-12) << elevation_deg << "°";
  }
  star_transmittance(a, camera, {std::cos(1 * kDeg), 0, -std::sin(1 * kDeg)}, got.data());
  EXPECT_EQ(got[0], 0.0) << "below the horizon: the ground";
  // From far away, a ray missing the shell keeps all its light; one through it
  // past the limb at the top's height less 20 km is dimmed.
  const glm::dvec3 far(0, 0, 10.0 * t.model.top_radius_m);
  star_transmittance(a, far, {1, 0, 0}, got.data());
  EXPECT_EQ(got[1], 1.0);
  const double grazing = (t.model.top_radius_m - 20e3) / glm::length(far);
  star_transmittance(a, far, {grazing, 0, -std::sqrt(1 - grazing * grazing)}, got.data());
  EXPECT_GT(got[1], 0.0);
  EXPECT_LT(got[1], 1.0);
}

TEST(StarField, TheCameraTransmittanceIsTheTablesReadWithinRounding) {
  // The pass reads every star's transmittance from one row per atmosphere and
  // frame (CameraTransmittance): the same bilinear filter as
  // star_transmittance with its sum reordered, so within a few ulps of it —
  // from the zenith through the horizon to below it (where a star still shows
  // from altitude) and the ground, for Earth's and Mars's tables, a camera 2 m
  // up, 10 km up, just above the shell and in orbit (rays entering the shell).
  for (const char* preset : {"earth-advanced", "mars"}) {
    const SmallTables& t = SmallTables::get(preset);
    const StarAtmosphere a{{0, 0, 0}, t.model.ground_radius_m, t.model.top_radius_m, &t.tables};
    for (const double altitude_m : {2.0, 10e3, t.model.top_radius_m - t.model.ground_radius_m + 1e3,
                                    2.0 * t.model.top_radius_m - t.model.ground_radius_m}) {
      const glm::dvec3 camera(0, 0, t.model.ground_radius_m + altitude_m);
      const CameraTransmittance fast(a, camera);
      std::array<double, 8> got{}, want{};
      double worst = 0.0;
      std::size_t ground = 0, outside = 0, through = 0;
      for (int k = 0; k <= 20000; ++k) {
        // Elevations from 90° up to 90° down, dense near the horizon; three azimuths.
        const double x = -1.0 + k / 10000.0;
        const double elevation = 0.5 * core::kPi * x * x * x;
        const double azimuth = 2.0 * k;
        const glm::dvec3 d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                           std::sin(elevation));
        fast(d, got.data());
        star_transmittance(a, camera, d, want.data());
        for (std::size_t c = 0; c < t.tables.channels; ++c) {
          worst = std::max(worst, std::abs(got[c] - want[c]));
          ASSERT_EQ(got[c] == 0.0, want[c] == 0.0) << preset << ' ' << altitude_m << " m " << elevation / kDeg;
          ASSERT_EQ(got[c] == 1.0, want[c] == 1.0) << preset << ' ' << altitude_m << " m " << elevation / kDeg;
        }
        ground += want[0] == 0.0;
        outside += want[0] == 1.0;
        through += want[0] > 0.0 && want[0] < 1.0;
      }
      EXPECT_LT(worst, 1e-15) << preset << ' ' << altitude_m << " m";
      EXPECT_GT(ground, 0u) << "rays into the ground";
      const bool in_orbit = altitude_m > 1.5 * t.model.top_radius_m - t.model.ground_radius_m;
      EXPECT_GT(through, in_orbit ? 10u : 1000u) << preset << ' ' << altitude_m << " m: rays through the air";
      if (altitude_m > t.model.top_radius_m - t.model.ground_radius_m) {
        EXPECT_GT(outside, 0u) << "rays missing the shell";
      }
    }
  }
}

TEST(StarField, TheClosedFormSolidAngleIsTheRaysWithinItsBound) {
  // The projections' closed forms (warp::Projection::pixel_solid_angle_sr)
  // against the rays' difference quotient (pixel_solid_angle_by_rays_sr) on
  // positions of the splat grid over the whole image (centre, rim, corners):
  // within solid_angle_relative_bound() (a²/6 for the
  // fisheye, max(t_x, t_y)²/4 for the planar view) and the same zeros (no
  // ray).
  const warp::FisheyeProjection dome(64, 64), master(1024, 1024);
  warp::FisheyeParameters wide;
  wide.fov_deg = 220.0;
  warp::FisheyeParameters whole;
  whole.fov_deg = 360.0;
  warp::FisheyeParameters quadrant;  // the upper left of a 1024² master
  quadrant.centre_x_px = 512.0;
  quadrant.centre_y_px = 512.0;
  quadrant.radius_px = 512.0;
  const warp::FisheyeProjection fisheye_220(512, 512, wide), fisheye_360(64, 64, whole),
      master_quadrant(512, 512, quadrant);
  const warp::PlanarProjection ground_view = warp::PlanarProjection::symmetric(1280, 720, 79.0),
                               small = warp::PlanarProjection::symmetric(48, 40, 90.0),
                               turned(64, 48, warp::PlanarFrustum{-10.0, 50.0, -30.0, 5.0, 30.0, 20.0, 10.0});
  const std::pair<const warp::Projection*, double> cases[] = {{&dome, 0.5 * core::kPi / 32.0},
                                                              {&master, 0.5 * core::kPi / 512.0},
                                                              {&fisheye_220, 110.0 * kDeg / 256.0},
                                                              {&fisheye_360, core::kPi / 32.0},
                                                              {&master_quadrant, 0.5 * core::kPi / 512.0},
                                                              {&ground_view, 0.0},
                                                              {&small, 0.0},
                                                              {&turned, 0.0}};
  for (const auto& [projection, a] : cases) {
    if (a > 0.0) {
      EXPECT_NEAR(projection->solid_angle_relative_bound(), a * a / 6.0, 1e-12 * a * a) << projection->describe();
    }
    EXPECT_GT(projection->solid_angle_relative_bound(), 0.0) << projection->describe();
    const int w = projection->width(), h = projection->height();
    double worst = 0.0;
    std::size_t zeros = 0;
    for (int j = 0; j <= 400; ++j)
      for (int i = 0; i <= 400; ++i) {
        const glm::dvec2 at = on_splat_grid({-0.5 + (w + 1.0) * i / 400.0, -0.5 + (h + 1.0) * j / 400.0});
        const double want = projection->pixel_solid_angle_by_rays_sr(at.x, at.y),
                     got = projection->pixel_solid_angle_sr(at.x, at.y);
        ASSERT_EQ(got == 0.0, want == 0.0) << projection->describe() << " at " << at.x << ", " << at.y;
        zeros += want == 0.0;
        if (want > 0.0) worst = std::max(worst, std::abs(got / want - 1.0));
      }
    EXPECT_LE(worst, projection->solid_angle_relative_bound()) << projection->describe();
    EXPECT_GT(worst, 0.01 * projection->solid_angle_relative_bound())
        << projection->describe() << ": the bound is tight";
    if (a > 0.0 && projection != &master_quadrant) {
      EXPECT_GT(zeros, 0u) << "the square's corners have no ray";
    }
  }
}

TEST(StarField, TheTwinkleTableIsTheFormulaWithinItsOwnBound) {
  // TwinkleSigmaTable's s at 64 points of every interval, from the horizon
  // (σ_I² capped at 1 for the eye on Earth) to the zenith, against the
  // formula: within the interval's bound from the table's second differences;
  // the eye on Earth at 2 m and at 10 km, a 20 cm telescope (uncapped down to
  // a few degrees) and the eye on Mars (~1e-4 of Earth's variance).
  const astro::ScintillationOptions eye;
  astro::ScintillationOptions telescope;
  telescope.pupil_mm = 200.0;
  const double mars = astro::ground_refractivity(atmosphere::load_preset("mars"), 550.0);
  const std::pair<const astro::ScintillationOptions*, std::pair<double, double>> cases[] = {
      {&eye, {2.0, astro::kEarthGroundRefractivity550}},
      {&eye, {10e3, astro::kEarthGroundRefractivity550}},
      {&telescope, {2.0, astro::kEarthGroundRefractivity550}},
      {&eye, {2.0, mars}}};
  for (const auto& [options, where] : cases) {
    const TwinkleSigmaTable table(
        astro::scintillation_variance_per_cubed_air_mass(*options, where.first, where.second));
    double worst = 0.0, worst_ratio = 0.0;
    for (std::size_t j = 0; j < TwinkleSigmaTable::kNodes; ++j)
      for (int k = 0; k <= 64; ++k) {
        const double mu = (double(j) + k / 64.0) / double(TwinkleSigmaTable::kNodes);
        const double error = std::abs(table(mu) - table.exact(mu));
        ASSERT_LE(error, table.bound_at(std::min(mu, 1.0 - 1e-12))) << "μ " << mu << ", " << where.first << " m";
        worst = std::max(worst, error);
        worst_ratio = std::max(worst_ratio, error / table.bound_at(std::min(mu, 1.0 - 1e-12)));
      }
    EXPECT_LE(worst, table.error_bound());
    EXPECT_LT(table.error_bound(), 1e-5) << "a small bound: " << where.first << " m";
    EXPECT_GT(worst_ratio, 0.05) << "the bound follows the error";
  }
}

TEST(StarField, TheFastPlacementIsTheExactOneWithinItsBoundAndHalfACode) {
  // The pass's frame (star_frame: the transmittance's rows, the solid angle's
  // closed form, the twinkle's table) against the same frame with the exact
  // reads (star_transmittance, the rays' pixel_solid_angle_by_rays_sr, the twinkle's
  // formula): the stars to V 6 over Greenwich on a 256² dome and a 79° planar
  // view, twinkling through earth-advanced from 2 m. The same stars at the
  // same pixels, and each one's rgb within the parts' bounds: the solid
  // angle's solid_angle_relative_bound(), the twinkle's exp(ε (|g| + s + ε)) − 1 for its
  // table's error_bound() ε, 1e-12 for the transmittance's few ulps (≥ 1e-5
  // of light kept) and two float roundings. A pixel's code then moves by at
  // most r · max_x D′(x) x (D concave: a relative change r of a star's part of
  // x moves the code by ≤ D′(x) · r x): below half a code. With the star
  // test's deviates of the interval (StarField::scintillation_normals) the
  // splats are the same bit for bit.
  REQUIRE_CATALOGUE();
  astro::StarCatalogueOptions o;
  o.magnitude_limit = 6.0;
  StarField field(astro::load_star_catalogue(o), {440.0, 550.0, 680.0});
  scene::Scene s = greenwich("earth-advanced", {0, 0, 1}, 2e5);
  s.night_sky = scene::NightSky{};
  s.night_sky->scintillation = astro::ScintillationOptions{};
  const SmallTables& t = SmallTables::get("earth-advanced");
  const std::vector<StarAtmosphere> air = {
      {s.bodies[0].position_m, t.model.ground_radius_m, t.model.top_radius_m, &t.tables}};
  const std::vector<std::array<double, 3>> weights = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  RefractionCache refractions;
  std::vector<glm::dvec3> enu;
  field.directions_enu(astro::AstroTime::from_utc(kTime), s.sky_clock->site, enu);
  const warp::FisheyeProjection dome(256, 256);
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(320, 180, 79.0);
  double worst_code = 0.0;
  for (const warp::Projection* p : std::initializer_list<const warp::Projection*>{&dome, &planar}) {
    const StarFrame fast =
        star_frame(s, *p, glm::mat3_cast(glm::normalize(s.camera.orientation)), air, weights, refractions);
    ASSERT_TRUE(fast.twinkle_sigma && fast.closed_form_solid_angle && fast.transmittances.size() == 1);
    StarFrame exact = fast;
    exact.transmittances.clear();
    exact.closed_form_solid_angle = false;
    exact.twinkle_sigma.reset();
    const std::vector<StarSplat> a = star_splats(field, enu, fast), b = star_splats(field, enu, exact);
    ASSERT_EQ(a.size(), b.size()) << p->describe();
    ASSERT_GT(a.size(), p == &dome ? 1000u : 100u) << p->describe();
    const double e = fast.twinkle_sigma->error_bound();
    const double bound = (1.0 + p->solid_angle_relative_bound()) *
                             std::exp(e * (8.572 + std::sqrt(std::log(2.0)) + e)) * (1.0 + 1e-12) *
                             (1.0 + 2.0 * 0x1.0p-24) -
                         1.0;
    double worst = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_EQ(a[k].x_px, b[k].x_px);
      ASSERT_EQ(a[k].y_px, b[k].y_px);
      for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(a[k].rgb[c]) / b[k].rgb[c] - 1.0));
    }
    EXPECT_LE(worst, bound) << p->describe();
    EXPECT_GT(worst, 0.0) << p->describe() << ": the fast parts are used";
    // The star test's deviates of the interval, kept by the field, are the ones drawn per star: bit for bit.
    field.largest_scintillation_normal(fast.scintillation_interval);
    StarFrame cached = fast;
    cached.scintillation_normals = field.scintillation_normals(fast.scintillation_interval);
    ASSERT_NE(cached.scintillation_normals, nullptr);
    const std::vector<StarSplat> c = star_splats(field, enu, cached);
    ASSERT_EQ(c.size(), a.size());
    for (std::size_t k = 0; k < a.size(); ++k)
      for (std::size_t ch = 0; ch < 3; ++ch) ASSERT_EQ(c[k].rgb[ch], a[k].rgb[ch]) << k;
    double slope_times_x = 0.0;
    for (double x = 1e-6; x < 1e3; x *= 1.01)
      slope_times_x = std::max(slope_times_x, image::display_code_slope_bound(x) * x);
    worst_code = std::max(worst_code, bound * slope_times_x);
  }
  EXPECT_LT(worst_code, 0.5) << "codes";
}

// ------------------------------------------------------------------------- GPU

TEST(NightSkyPass, AStarHasTheSameEnergyOnADomeMasterAFlatScreenAndThroughAWarpMesh) {
  // No atmosphere: the star's light arrives whole, E(λ) × exposure per channel.
  REQUIRE_CATALOGUE();
  const astro::StarCatalogue c = bright_stars();
  const glm::dvec3 sirius = sirius_enu(c);
  ASSERT_GT(sirius.z, 0.2) << "Sirius is up at the test's time";
  const double exposure = 1e6;
  const auto e = astro::star_irradiance_W_m2_nm(c.stars.front().v_mag, c.stars.front().b_minus_v,
                                                std::vector<double>{680.0, 550.0, 440.0});
  // The flat view looks 10° to one side of Sirius, so it is off the centre;
  // the dome looks at the horizon (its centre is the zenith).
  const scene::Scene flat_scene = greenwich("", glm::normalize(sirius + glm::dvec3(0.17, 0, 0)), exposure);
  const scene::Scene dome_scene = greenwich("", {0, -1, 0}, exposure);
  TestRenderer stars(options(true, false)), none(options(false, false));
  const auto dome = std::make_shared<warp::FisheyeProjection>(64, 64);
  const warp::PlanarProjection flat = warp::PlanarProjection::symmetric(48, 40, 60.0);
  const auto where = [&](const scene::Scene& s, const warp::Projection& p) {
    return *p.pixel(glm::conjugate(s.camera.orientation) *
                    glm::normalize(sirius.x * scene::local_horizon_at(s.camera.position_m, s.bodies[0]).east +
                                   sirius.y * scene::local_horizon_at(s.camera.position_m, s.bodies[0]).north +
                                   sirius.z * scene::local_horizon_at(s.camera.position_m, s.bodies[0]).up));
  };
  // A 48² projector showing the dome master around Sirius at 0.6 of a base pixel per projector pixel.
  const glm::dvec2 at_dome = where(dome_scene, *dome);
  std::vector<warp::WarpNode> nodes;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 9; ++i)
      nodes.push_back(
          {(at_dome.x + 0.6 * (48.0 * i / 8 - 24)) / 64, (at_dome.y + 0.6 * (48.0 * j / 8 - 24)) / 64, 1.0, true});
  const warp::WarpedProjection projector(
      48, 48, warp::WarpMesh(9, 9, std::move(nodes), "around Sirius", warp::WarpInterpolation::catmull_rom), dome);
  for (const warp::Projection* p : std::initializer_list<const warp::Projection*>{dome.get(), &flat, &projector}) {
    const scene::Scene& s = p == &flat ? flat_scene : dome_scene;
    const auto image = stars.renderer.render_image(s, *p);
    EXPECT_TRUE(stars.renderer.last_frame().night_sky.drawn) << p->describe();
    EXPECT_EQ(stars.renderer.last_frame().night_sky.catalogue_identity, c.identity_sha256);
    const auto background = none.renderer.render_image(s, *p);
    const auto energy = energy_near(image, background, *p, where(s, *p), 3.0);
    std::printf("%s: Sirius's energy / E × exposure = %.5f, %.5f, %.5f\n", p->describe().c_str(),
                energy[0] / (e[0] * exposure), energy[1] / (e[1] * exposure), energy[2] / (e[2] * exposure));
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(energy[static_cast<std::size_t>(k)], e[static_cast<std::size_t>(k)] * exposure,
                  0.01 * e[static_cast<std::size_t>(k)] * exposure)
          << p->describe() << ", channel " << k;
  }
}

TEST(NightSkyPass, TheQuadrantsOfADomeMasterCarryItsStarsWithoutASeam) {
  // No atmosphere, no floor: the image is the stars alone. A cluster's nodes
  // render a dome master's quadrants (configs/viewports/dome-quadrants.json);
  // where they meet, a star within half a pixel beyond a quadrant's edge must
  // still light the edge's pixels (star_placement.h, splat_touches_image), and
  // every pixel must carry what it carries in the whole dome master, bit for
  // bit: the splat positions sit on the same 1/256-pixel grid, and the star
  // accumulator's step is a constant (star_accumulator.glsl), so a star adds
  // the same counts in a quadrant's band as in the whole image's, whatever
  // other stars each band holds (the step once followed a band's stars: up to
  // one count of the whole image per star in a pixel apart).
  REQUIRE_CATALOGUE();
  RenderOptions o = options(true, false);
  o.night_sky.star_magnitude_limit = 4.5;  // ~900 stars, ~450 up: dozens within a pixel of the seams
  TestRenderer t(o);
  const scene::Scene s = greenwich("", {0, -1, 0}, 1e9);
  const int n = 64, half = n / 2;
  const std::vector<float> whole = t.renderer.render_image(s, warp::FisheyeProjection(n, n));
  std::size_t lit_at_seams = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float* v = &whole[(static_cast<std::size_t>(y) * n + x) * 3];
      lit_at_seams += v[1] > 0.0f && (x == half - 1 || x == half || y == half - 1 || y == half);
    }
  ASSERT_GT(lit_at_seams, 8u) << "stars light the pixels along the seams";
  for (int q = 0; q < 4; ++q) {
    const int x0 = (q % 2) * half, y0 = (q / 2) * half;
    warp::FisheyeParameters f;
    f.centre_x_px = 0.5 * n - x0;
    f.centre_y_px = 0.5 * n - y0;
    f.radius_px = 0.5 * n;
    const std::vector<float> quadrant = t.renderer.render_image(s, warp::FisheyeProjection(half, half, f));
    std::size_t differing = 0;
    double worst = 0.0;
    for (int y = 0; y < half; ++y)
      for (int x = 0; x < half * 3; ++x) {
        const float a = quadrant[static_cast<std::size_t>(y) * half * 3 + x],
                    b = whole[static_cast<std::size_t>(y0 + y) * n * 3 + x0 * 3 + x];
        differing += a != b;
        worst = std::max(worst, std::abs(double(a) - b));
      }
    EXPECT_EQ(differing, 0u) << "quadrant " << q << ": values not bit for bit the whole image's (largest "
                             << "difference " << worst << ")";
  }
}

TEST(NightSkyPass, AStarIsDimmedByTheTransmittanceAlongItsLineOfSightAndTheFloorLightsTheZenith) {
  REQUIRE_CATALOGUE();
  const astro::StarCatalogue c = bright_stars();
  const glm::dvec3 sirius = sirius_enu(c);
  const SmallTables& t = SmallTables::get("earth-advanced");
  const double exposure = 1e6;
  const scene::Scene s = greenwich("earth-advanced", {0, -1, 0}, exposure);
  TestRenderer stars(options(true, true)), floor_only(options(false, true)), none(options(false, false));
  const auto dome = std::make_shared<warp::FisheyeProjection>(64, 64);
  const auto image = stars.renderer.render_image(s, *dome);
  const auto background = floor_only.renderer.render_image(s, *dome);
  // Sirius's apparent place: lifted by refraction (~2.6′ at 20°: a tenth of a pixel, ignored here).
  const scene::LocalHorizon h = scene::local_horizon_at(s.camera.position_m, s.bodies[0]);
  const glm::dvec3 d = glm::normalize(sirius.x * h.east + sirius.y * h.north + sirius.z * h.up);
  const glm::dvec2 at = *dome->pixel(glm::conjugate(s.camera.orientation) * d);
  const auto energy = energy_near(image, background, *dome, at, 3.0);
  const atmosphere::lut::TableQueries q(t.model, t.tables);
  std::array<double, 8> transmittance{};
  q.transmittance_to_top(glm::length(s.camera.position_m), glm::dot(d, h.up), transmittance.data());
  const auto e = astro::star_irradiance_W_m2_nm(c.stars.front().v_mag, c.stars.front().b_minus_v,
                                                std::vector<double>{680.0, 550.0, 440.0});
  for (int k = 0; k < 3; ++k) {
    const double want = e[static_cast<std::size_t>(k)] * transmittance[static_cast<std::size_t>(k)] * exposure;
    EXPECT_NEAR(energy[static_cast<std::size_t>(k)], want, 0.02 * want) << "channel " << k;
  }
  EXPECT_LT(transmittance[2], transmittance[0]) << "blue is dimmed more than red";

  // The zenith's night floor: the calibrated spectrum through the zenith's transmittance.
  const scene::Scene& up = s;  // the dome's centre is the zenith
  const auto lit = floor_only.renderer.render_image(up, *dome);
  EXPECT_TRUE(floor_only.renderer.last_frame().night_sky.drawn);
  const auto dark = none.renderer.render_image(up, *dome);
  q.transmittance_to_top(glm::length(up.camera.position_m), 1.0, transmittance.data());
  const astro::NightSkyFloor floor(t.model);
  const std::vector<double> want =
      floor.observed_radiance(0.0, std::vector<double>(transmittance.begin(), transmittance.begin() + 3));
  const std::size_t centre = (32u * 64u + 32u) * 3u;
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(double(lit[centre + k]) - dark[centre + k], want[k] * exposure, 0.02 * want[k] * exposure)
        << "channel " << k;
}

TEST(NightSkyPass, TheMoonCarriesItsIrradianceAsADiscAndAsAPointBelowAPixel) {
  // The full Moon of 2026-01-03, high in the south-east at Greenwich, no
  // atmosphere: Σ L Ω over the disc = the Moon's irradiance (its Lommel–Seeliger
  // disc integrates to it within 1 %, docs/night-sky.md; 2 % for the edge's
  // antialiasing on a 17-pixel disc), and the same as a point on a 64² dome.
  const astro::UtcTime time{2026, 1, 3, 23, 0, 0.0};
  const astro::Site site{kLatitudeDeg, kLongitudeDeg, 46.0};
  const astro::MoonPlace moon = astro::SkyPositions(astro::AstroTime::from_utc(time), site).moon();
  ASSERT_GT(moon.horizontal.altitude_rad, 20 * kDeg);
  const glm::dvec3 at = moon.horizontal.east_north_up();
  const auto e = astro::moon_irradiance_W_m2_nm(moon, std::vector<double>{680.0, 550.0, 440.0});
  RenderOptions with = options(false, false), without = options(false, false);
  with.night_sky.moon = true;
  without.night_sky.moon = false;
  TestRenderer moonlit(with), dark(without);
  // The sun where the ephemeris puts it (the disc's phase comes from its direction).
  const auto at_time = [&](scene::Scene sc) {
    sc.sky_clock->time = time;
    sc.sun.direction =
        scene::ephemeris_sun(sc, *sc.sky_clock, astro::AstroTime::from_utc(time), sc.camera.position_m).direction;
    return sc;
  };
  const scene::Scene narrow = at_time(greenwich("", at, 1.0));
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(64, 64, 2.0);
  const auto image = moonlit.renderer.render_image(narrow, planar);
  EXPECT_TRUE(moonlit.renderer.last_frame().night_sky.drawn);
  const auto disc = energy_near(image, dark.renderer.render_image(narrow, planar), planar, {32.0, 32.0}, 20.0);
  const scene::Scene dome = at_time(greenwich("", {0, -1, 0}, 1.0));
  const warp::FisheyeProjection fisheye(64, 64);
  const scene::LocalHorizon h = scene::local_horizon_at(dome.camera.position_m, dome.bodies[0]);
  const glm::dvec2 px =
      *fisheye.pixel(glm::conjugate(dome.camera.orientation) * (at.x * h.east + at.y * h.north + at.z * h.up));
  const auto point = energy_near(moonlit.renderer.render_image(dome, fisheye),
                                 dark.renderer.render_image(dome, fisheye), fisheye, px, 3.0);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(disc[k], e[k], 0.02 * e[k]) << "disc, channel " << k;
    EXPECT_NEAR(point[k], e[k], 0.01 * e[k]) << "point, channel " << k;
  }
  std::printf("the Moon's energy / irradiance: disc %.4f %.4f %.4f, point %.4f %.4f %.4f\n", disc[0] / e[0],
              disc[1] / e[1], disc[2] / e[2], point[0] / e[0], point[1] / e[1], point[2] / e[2]);
}

/// The full Moon of 2026-01-03 23:00 UTC at Greenwich (the test above's).
const astro::UtcTime kFullMoon{2026, 1, 3, 23, 0, 0.0};

/// Where a selenographic point of the Moon at kFullMoon lies in the world (the
/// camera → point direction of scene `s`, no refraction), by the orientation
/// of astro/moon_orientation.h, and the Moon's centre.
struct MoonGeometry {
  glm::dvec3 centre;  ///< world, unit
  glm::dvec3 point;   ///< world, unit
  glm::dvec3 normal;  ///< world: the surface's normal there
  double mu;          ///< the point's cosine toward the observer
};
MoonGeometry moon_point(const scene::Scene& s, double latitude_deg, double longitude_deg) {
  const astro::SkyPositions sky(astro::AstroTime::from_utc(kFullMoon), astro::Site{kLatitudeDeg, kLongitudeDeg, 46.0});
  const astro::MoonPlace moon = sky.moon();
  const astro::MoonAxes axes = astro::moon_orientation(sky).axes;
  const scene::LocalHorizon h = scene::local_horizon_at(s.camera.position_m, s.bodies[0]);
  const auto world = [&](const glm::dvec3& e) { return e.x * h.east + e.y * h.north + e.z * h.up; };
  const glm::dvec3 centre = glm::normalize(world(moon.horizontal.east_north_up()));
  const glm::dvec3 x = world(sky.gcrs_direction_enu(axes.x)), z = world(sky.gcrs_direction_enu(axes.z));
  const glm::dvec3 y = glm::cross(z, x);
  const double phi = latitude_deg * kDeg, lambda = longitude_deg * kDeg;
  const glm::dvec3 n = std::cos(phi) * (std::cos(lambda) * x + std::sin(lambda) * y) + std::sin(phi) * z;
  return {centre, glm::normalize(centre * moon.distance_km + n * astro::kMoonRadius_km), n, -glm::dot(n, centre)};
}

/// The mean of channel 1 (550 nm) over the 3 × 3 pixels around `px`.
double around(const std::vector<float>& image, int width, glm::dvec2 px) {
  double sum = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      sum += image[(static_cast<std::size_t>(std::floor(px.y) + dy) * width + std::floor(px.x) + dx) * 3 + 1];
  return sum / 9.0;
}

TEST(NightSkyPass, TheMoonsFaceShowsMareCrisiumInTheSkysWestAndTychoInTheSouth) {
  // A 128² view 1.2° wide on the full Moon of 2026-01-03 (a disc 58 px across),
  // no atmosphere. Mare Crisium (17° N, 59° E) is dark against the highlands
  // south-east of it (30° S, 65° E: a point of the same μ, near Petavius), at
  // the pixels the orientation predicts; on the sky it lies west of the disc's
  // centre (selenographic east faces the sky's west: the IAU convention), Tycho
  // (43° S, 11° W) south of it. Without the map the same two points are equal.
  if (!std::filesystem::exists(kStellariumMoonMap)) GTEST_SKIP() << "stellarium-data is not installed";
  RenderOptions with = options(false, false), without = options(false, false), uniform = options(false, false);
  with.night_sky.moon = true;
  uniform.night_sky.moon = true;
  uniform.night_sky.moon_albedo_map = "/nonexistent/moon.png";
  TestRenderer mapped(with), dark(without), plain(uniform);
  const glm::dvec3 look = moon_point(greenwich("", {0, -1, 0}, 1.0), 0.0, 0.0).centre;
  const scene::Scene probe = greenwich("", {0, -1, 0}, 1.0);
  const scene::LocalHorizon h0 = scene::local_horizon_at(probe.camera.position_m, probe.bodies[0]);
  scene::Scene s = testing::greenwich("", {glm::dot(look, h0.east), glm::dot(look, h0.north), glm::dot(look, h0.up)},
                                      1.0, kFullMoon);
  s.sun.direction =
      scene::ephemeris_sun(s, *s.sky_clock, astro::AstroTime::from_utc(kFullMoon), s.camera.position_m).direction;
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(128, 128, 1.2);
  const auto image = mapped.renderer.render_image(s, planar);
  const std::string identity = mapped.renderer.last_frame().night_sky.moon_map_identity;
  const double mean = mapped.renderer.last_frame().night_sky.moon_mean_albedo;
  const auto flat = plain.renderer.render_image(s, planar);
  EXPECT_EQ(plain.renderer.last_frame().night_sky.moon_map_identity, "");
  const auto black = dark.renderer.render_image(s, planar);
  EXPECT_EQ(identity.size(), 64u);
  const auto pixel = [&](const MoonGeometry& g) {
    return *planar.pixel(glm::conjugate(s.camera.orientation) * g.point);
  };
  const MoonGeometry crisium = moon_point(s, 17.0, 59.0), highland = moon_point(s, -30.0, 65.0),
                     tycho = moon_point(s, -43.3, -11.2);
  ASSERT_GT(crisium.mu, 0.3);
  ASSERT_GT(highland.mu, 0.3);
  const glm::dvec2 at_crisium = pixel(crisium), at_highland = pixel(highland);
  const double c = around(image, 128, at_crisium) - around(black, 128, at_crisium),
               b = around(image, 128, at_highland) - around(black, 128, at_highland);
  const double c_flat = around(flat, 128, at_crisium), b_flat = around(flat, 128, at_highland);
  // The map's own contrast between the two places (its 1.4° copy).
  const MoonAlbedoMap map = MoonAlbedoMap::load(kStellariumMoonMap);
  const double map_ratio = map.coarse_at(59.0 * kDeg, 17.0 * kDeg) / map.coarse_at(65.0 * kDeg, -30.0 * kDeg);
  std::printf(
      "Crisium at (%.1f, %.1f) px, highland at (%.1f, %.1f) px: rendered %.3g / %.3g = %.3f (map %.3f), "
      "uniform albedo %.3f; the map's mean over the lit disc %.4f\n",
      at_crisium.x, at_crisium.y, at_highland.x, at_highland.y, c, b, c / b, map_ratio, c_flat / b_flat, mean);
  // Without the map the two places differ by Lommel–Seeliger's μ0/(μ0 + μ) alone
  // (the phase angle is 7°: the limb's points differ by 10 %), evaluated at
  // the predicted places: 2 % for the 3 × 3 pixels' spread of μ0 and μ.
  const auto lommel_seeliger = [&](const MoonGeometry& g) {
    const double mu0 = glm::dot(g.normal, s.sun.direction);
    return mu0 / (mu0 + g.mu);
  };
  EXPECT_NEAR(c_flat / b_flat, lommel_seeliger(crisium) / lommel_seeliger(highland), 0.02);
  // With it, the mare is dark, as dark as the map makes it: the GPU reads the
  // map's level of the pixel's footprint (2.5 texel levels, ~3° texels, across
  // the limb's foreshortening) where the CPU's copy has 1.4° texels, so the
  // 18°-wide mare's bright rim comes in: within 30 %.
  EXPECT_NEAR(map_ratio, 0.47, 0.05);  // the maria reflect about half the highlands' light
  EXPECT_LT(c / b, 0.6);
  EXPECT_NEAR(c / b, map_ratio * (c_flat / b_flat), 0.3 * map_ratio);
  EXPECT_NEAR(mean, 1.0, 0.05);  // normalized on the near side: the lit disc's mean is near 1
  // On the sky: east = the direction of increasing right ascension (pole × line of sight).
  const glm::dvec3 pole = std::cos(kLatitudeDeg * kDeg) * h0.north + std::sin(kLatitudeDeg * kDeg) * h0.up;
  const glm::dvec3 east = glm::normalize(glm::cross(pole, crisium.centre)), north = glm::cross(crisium.centre, east);
  EXPECT_LT(glm::dot(crisium.point - crisium.centre, east), -0.5 * std::sin(59 * kDeg) * 0.9 * 2.5e-3)
      << "Mare Crisium lies toward the sky's west";
  EXPECT_LT(glm::dot(tycho.point - tycho.centre, north), -0.5 * 2.5e-3 * std::sin(43.3 * kDeg))
      << "Tycho lies toward the sky's south";
}

TEST(NightSkyPass, AMissingMoonMapDrawsAUniformDiscWithTheSameEnergy) {
  // The first test's disc with no map file: the uniform albedo (one warning),
  // the same energy within its 2 %.
  const astro::Site site{kLatitudeDeg, kLongitudeDeg, 46.0};
  const astro::MoonPlace moon = astro::SkyPositions(astro::AstroTime::from_utc(kFullMoon), site).moon();
  const auto enu = moon.horizontal.east_north_up();
  const auto e = astro::moon_irradiance_W_m2_nm(moon, std::vector<double>{680.0, 550.0, 440.0});
  RenderOptions with = options(false, false), without = options(false, false);
  with.night_sky.moon = true;
  with.night_sky.moon_albedo_map = "/nonexistent/moon.png";
  TestRenderer moonlit(with), dark(without);
  scene::Scene s = greenwich("", enu, 1.0);
  s.sky_clock->time = kFullMoon;
  s.sun.direction =
      scene::ephemeris_sun(s, *s.sky_clock, astro::AstroTime::from_utc(kFullMoon), s.camera.position_m).direction;
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(64, 64, 2.0);
  const auto image = moonlit.renderer.render_image(s, planar);
  EXPECT_TRUE(moonlit.renderer.last_frame().night_sky.drawn);
  EXPECT_EQ(moonlit.renderer.last_frame().night_sky.moon_map_identity, "");
  EXPECT_EQ(moonlit.renderer.last_frame().night_sky.moon_mean_albedo, 1.0);
  const auto disc = energy_near(image, dark.renderer.render_image(s, planar), planar, {32.0, 32.0}, 20.0);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(disc[k], e[k], 0.02 * e[k]) << "channel " << k;
}

TEST(NightSkyPass, TheEclipsedMoonKeepsTheLightTheEarthsShadowLeavesIt) {
  // The total lunar eclipse of 2019-01-21 at mid-totality from Greenwich (the Moon ~20° up in the west),
  // earth-advanced's air, a uniform face (no map): the disc's light over the same disc without the
  // Earth's shadow (RenderOptions::night_sky.lunar_eclipses off; the transmittance cancels) is, per
  // channel, the mean over the face of the sunlight the shadow leaves (render/night/moon_in_shadow.h,
  // astro/lunar_eclipse.h), within 3 % (the disc's antialiased edge); and red: 680 nm keeps ~100× the
  // share 440 nm keeps.
  const astro::UtcTime time{2019, 1, 21, 5, 12, 16.0};
  const astro::MoonPlace moon =
      astro::SkyPositions(astro::AstroTime::from_utc(time), astro::Site{kLatitudeDeg, kLongitudeDeg, 46.0}).moon();
  ASSERT_GT(moon.horizontal.altitude_rad, 10 * kDeg);
  scene::Scene s = testing::greenwich("earth-advanced", moon.horizontal.east_north_up(), 1.0, time);
  s.sun.direction =
      scene::ephemeris_sun(s, *s.sky_clock, astro::AstroTime::from_utc(time), s.camera.position_m).direction;
  RenderOptions eclipsed = options(false, false);
  eclipsed.night_sky.moon = true;
  eclipsed.night_sky.moonlight = false;
  eclipsed.night_sky.moon_albedo_map = "/nonexistent/moon.png";
  RenderOptions full = eclipsed, dark = eclipsed;
  full.night_sky.lunar_eclipses = false;
  dark.night_sky.moon = false;
  TestRenderer in_shadow(eclipsed), outside(full), none(dark);
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(64, 64, 2.0);
  const auto background = none.renderer.render_image(s, planar);
  const auto a = energy_near(in_shadow.renderer.render_image(s, planar), background, planar, {32.0, 32.0}, 20.0);
  const auto b = energy_near(outside.renderer.render_image(s, planar), background, planar, {32.0, 32.0}, 20.0);
  MoonInShadow shadow;
  shadow.update(s, FrameSky(s));
  ASSERT_TRUE(shadow.shadowed());
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(a[k] / b[k], shadow.face()[k], 0.03 * shadow.face()[k]) << k;
  std::printf("the eclipsed Moon keeps %.3g %.3g %.3g of its light (the face's mean: %.3g %.3g %.3g)\n", a[0] / b[0],
              a[1] / b[1], a[2] / b[2], shadow.face()[0], shadow.face()[1], shadow.face()[2]);
  EXPECT_GT(shadow.face()[0], 30.0 * shadow.face()[2]);
}

/// render/frame/frame_sky.h: the frame's readers of the Moon share one
/// ephemeris of the sky clock, made at the first reading, the same places as
/// SkyPositions made anew; a scene without a clock has none to give.
TEST(FrameSky, TheFramesReadersShareOneEphemerisOfTheClock) {
  const astro::UtcTime time{2019, 1, 21, 5, 12, 16.0};
  const astro::Site site{kLatitudeDeg, kLongitudeDeg, 46.0};
  const scene::Scene s = testing::greenwich("earth-advanced", glm::dvec3(0, 0, 1), 1.0, time);
  ASSERT_TRUE(s.sky_clock);
  const FrameSky sky(s);
  const astro::SkyPositions& first = sky.positions();
  EXPECT_EQ(&sky.positions(), &first) << "made once";
  const astro::MoonPlace moon = first.moon(),
                         fresh = astro::SkyPositions(astro::AstroTime::from_utc(time), site).moon();
  EXPECT_EQ(moon.horizontal.azimuth_rad, fresh.horizontal.azimuth_rad);
  EXPECT_EQ(moon.horizontal.altitude_rad, fresh.horizontal.altitude_rad);
  EXPECT_EQ(moon.distance_km, fresh.distance_km);

  scene::Scene no_clock = s;
  no_clock.sky_clock.reset();
  EXPECT_THROW(FrameSky(no_clock).positions(), std::logic_error);
}

TEST(MoonAlbedoMap, StellariumsMapIsRelativeToItsNearSideMeanAndNamesItsFile) {
  if (!std::filesystem::exists(kStellariumMoonMap)) GTEST_SKIP() << "stellarium-data is not installed";
  const MoonAlbedoMap map = MoonAlbedoMap::load(kStellariumMoonMap);
  EXPECT_EQ(map.width(), 1024);
  EXPECT_EQ(map.height(), 512);
  EXPECT_FALSE(map.is_uniform());
  // The full Moon without libration, seen along the prime meridian: mean 1.
  MoonWorldAxes axes{glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)};
  // (The observer looks along −x at the near side, the Sun behind them.)
  EXPECT_NEAR(moon_disc_mean_albedo(map, axes, {-1, 0, 0}, {1, 0, 0}), 1.0, 0.01);
  // The far side (no maria but the South Pole–Aitken basin) is brighter than the near side's mean.
  const double far = moon_disc_mean_albedo(map, axes, {1, 0, 0}, {-1, 0, 0});
  std::printf("the map's mean over the far side / the near side's: %.3f; its largest texel %.2f\n", far, map.largest());
  EXPECT_NEAR(far, 1.36, 0.05);
  // The Sun at 90° from the line of sight (a quarter Moon): half the disc lit, a mean near 1, not 1 by default.
  EXPECT_NE(moon_disc_mean_albedo(map, axes, {-1, 0, 0}, {0, 1, 0}), 1.0);
  EXPECT_GT(map.largest(), 1.5);
  try {
    (void)MoonAlbedoMap::load("/nonexistent/moon.png");
    ADD_FAILURE() << "a missing map loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/moon.png"), std::string::npos) << e.what();
  }
}

TEST(NightSkyPass, SkippedByItsOwnTestWhenNoStarCouldShow) {
  REQUIRE_CATALOGUE();
  const astro::StarCatalogue c = bright_stars();
  const scene::Scene s = greenwich("", sirius_enu(c), 1.0);  // a daylight exposure
  RenderOptions o = options(true, true);
  o.night_sky.moon = false;  // the Moon is seen by day: not part of this test
  TestRenderer stars(o), none(options(false, false));
  const warp::FisheyeProjection dome(48, 48);
  const auto a = stars.renderer.render_image(s, dome);
  EXPECT_FALSE(stars.renderer.last_frame().night_sky.drawn);
  EXPECT_EQ(stars.renderer.last_frame().night_sky.stars, 0u);
  EXPECT_EQ(a, none.renderer.render_image(s, dome));
}

/// The site's sky with the sun `depression_deg` below the horizon in the south (geometric).
scene::Scene at_twilight(double depression_deg, double exposure) {
  scene::Scene s = greenwich("earth-advanced", {0, 0, 1}, exposure);  // the dome's centre at the zenith
  const scene::LocalHorizon h = scene::local_horizon_at(s.camera.position_m, s.bodies[0]);
  s.sun.direction = glm::normalize(-std::cos(depression_deg * kDeg) * h.north - std::sin(depression_deg * kDeg) * h.up);
  return s;
}

/// "sun D° down, exposure E": where a twilight frame was taken.
std::string twilight_label(double depression_deg, double exposure) {
  return "sun " + std::to_string(depression_deg) + "° down, exposure " + std::to_string(exposure);
}

/// A frame a pass was skipped in against the frame that drew it: no value
/// moves by half a code for either tone operator, so each 8-bit code is the
/// same or one step away where the sky sits within that change of a rounding
/// boundary (the bound is on the continuous code value; code_difference.h).
testing::CodeDifference expect_within_half_a_code(const std::vector<float>& skipped, const std::vector<float>& drawn,
                                                  const std::string& at) {
  const testing::CodeDifference d = testing::code_difference(skipped, drawn);
  EXPECT_LT(d.largest_code_change, kInvisibleCodeChange) << at;
  EXPECT_LE(d.largest_byte_change, 1) << at;
  return d;
}

TEST(NightSkyPass, TheSkyIsNoDarkerThanItsFloorFromTheTables) {
  // The star test's B (atmosphere/lut/sky_radiance_lower_bound.h): every pixel of sky
  // the passes draw (direct colour: channel k = exposure · L(λ_k)) is at least
  // exposure · E_sun · S_min, from the sun at the horizon to deep twilight,
  // through the 4D tables and through the sky-view table; and the floor is
  // not empty (within a factor 5 of the darkest pixel).
  const SmallTables& t = SmallTables::get("earth-advanced");
  const atmosphere::lut::SkyRadianceLowerBound floor(t.model, t.tables, true);
  RenderOptions o = twilight_options(false, false);
  o.skip_hidden_sunlight = false;  // the sky the tables give, also where it is too faint to show
  const warp::FisheyeProjection dome(48, 48);
  for (const SkyViewTableUse use : {SkyViewTableUse::always, SkyViewTableUse::off}) {
    o.sky_view_table = use;
    TestRenderer r(o);
    for (double depression : {0.0, 3.0, 6.0, 10.0, 14.0}) {
      const scene::Scene s = at_twilight(depression, 1.0);
      const auto image = r.renderer.render_image(s, dome);
      const glm::dvec3 up = glm::normalize(s.camera.position_m);
      const std::vector<double> k =
          floor.radiance_per_irradiance(glm::dot(up, s.sun.direction), glm::length(s.camera.position_m));
      std::array<double, 3> darkest{1e300, 1e300, 1e300};
      for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
          const auto ray = dome.ray(x + 0.5, y + 0.5);
          if (!ray || glm::dot(s.camera.orientation * glm::normalize(*ray), up) <= 0.0) continue;  // the sky only
          for (std::size_t c = 0; c < 3; ++c)
            darkest[c] = std::min(darkest[c], double(image[(static_cast<std::size_t>(y) * 48 + x) * 3 + c]));
        }
      const auto weights = image::spectral_to_rgb_weights(s.wavelengths_nm, image::ColourMapping::direct);
      for (std::size_t c = 0; c < 3; ++c) {
        double b = 0.0;
        for (std::size_t i = 0; i < weights.size(); ++i) b += weights[i][c] * s.sun.irradiance_W_m2_nm[i] * k[i];
        EXPECT_GT(b, 0.0);
        EXPECT_LE(b, darkest[c]) << "sun " << depression << "° down, channel " << c;
        EXPECT_GT(b, darkest[c] / 5.0) << "sun " << depression << "° down, channel " << c;
        if (use == SkyViewTableUse::off && c == 1)
          std::printf("sun %4.1f° down: the darkest sky %.3g, its floor %.3g (%.2f of it)\n", depression, darkest[c], b,
                      b / darkest[c]);
      }
    }
  }
}

TEST(NightSkyPass, WhereTheSkyHidesEveryStarItsTestSkipsThemAndTheFrameMovesByLessThanHalfACode) {
  // The stars' test against the sky (render/night/star_visibility.h): at
  // twilight exposures under a sky bright enough to hide every star the test
  // skips them; the frame with the stars forced on moves no value by half a
  // code, for both tone operators: each 8-bit code the same, or one step away
  // where the sky sits within that change of a rounding boundary (the test's
  // bound is on the continuous code value; code_difference.h). Under the night
  // sky the test lets them run.
  REQUIRE_CATALOGUE();
  const RenderOptions o = twilight_options(true, true);
  TestRenderer tested(o), always(without_sky_test(o, &NightSkyRenderOptions::skip_hidden_stars));
  const warp::FisheyeProjection dome(48, 48);
  int skipped = 0;
  for (double depression : {0.0, 4.0, 8.0})
    for (double exposure : {30.0, 300.0, 3000.0, 30000.0}) {
      const scene::Scene s = at_twilight(depression, exposure);
      const auto a = tested.renderer.render_image(s, dome);
      const FrameStats stats = tested.renderer.last_frame();
      std::printf("sun %.0f° down, exposure %g: sky floor %.3g, stars' peak %.3g: %s\n", depression, exposure,
                  stats.night_sky.star_test.largest_sky_floor(), stats.night_sky.star_test.largest_sky_peak(),
                  stats.night_sky.star_test.could_show ? "runs" : "skipped");
      if (stats.night_sky.star_test.could_show) continue;
      ++skipped;
      EXPECT_EQ(stats.night_sky.stars, 0u);
      const auto b = always.renderer.render_image(s, dome);
      ASSERT_GT(always.renderer.last_frame().night_sky.stars, 0u) << "the forced frame holds stars";
      const std::string at = twilight_label(depression, exposure);
      EXPECT_LE(expect_within_half_a_code(a, b, at).codes_differing, a.size() / 100) << at;
    }
  EXPECT_GE(skipped, 4) << "the sky hides the stars in several of these frames";
  // Night, the sun 30° down: the stars show and the test says so.
  tested.renderer.render_image(at_twilight(30.0, 1e6), dome);
  EXPECT_TRUE(tested.renderer.last_frame().night_sky.star_test.could_show);
  EXPECT_GT(tested.renderer.last_frame().night_sky.stars, 0u);
}

TEST(NightSkyPass, WhereTheTwilightSkyHidesTheNightFloorItsTestSkipsItAndTheFrameMovesByLessThanHalfACode) {
  // The night floor's test against the sky behind it (render/night/star_pass.h,
  // the star test's B): through twilight, where the floor could move a code
  // on a black sky but not on the darkest sky the passes draw, the pass is
  // skipped, and the frame with the test against black only (which draws the
  // floor) is within half a code of it. At night the floor is drawn.
  const RenderOptions o = twilight_options(false, true);
  int skipped = 0;
  TestRenderer tested(o), against_black(without_sky_test(o, &NightSkyRenderOptions::skip_hidden_floor));
  const warp::FisheyeProjection dome(48, 48);
  for (double depression : {0.0, 4.0, 8.0, 12.0})
    for (double exposure : {1e5, 3e5, 1e6}) {
      const scene::Scene s = at_twilight(depression, exposure);
      const auto a = tested.renderer.render_image(s, dome);
      const bool drawn = tested.renderer.last_frame().night_sky.drawn;
      const auto b = against_black.renderer.render_image(s, dome);
      const bool drawn_on_black = against_black.renderer.last_frame().night_sky.drawn;
      EXPECT_TRUE(drawn_on_black || !drawn) << "the test against the sky is the stricter";
      if (!drawn_on_black) continue;  // invisible on black too
      if (drawn) {
        EXPECT_EQ(a, b);
        continue;
      }
      ++skipped;
      const std::string at = twilight_label(depression, exposure);
      const testing::CodeDifference d = expect_within_half_a_code(a, b, at);
      std::printf("%s: the floor skipped, %.3g code from the frame with it\n", at.c_str(), d.largest_code_change);
    }
  EXPECT_GE(skipped, 3) << "the twilight sky hides the floor in several of these frames";
  tested.renderer.render_image(at_twilight(30.0, 3e5), dome);
  EXPECT_TRUE(tested.renderer.last_frame().night_sky.drawn) << "night: the floor shows";
}

TEST(NightSkyPass, TheSunFarBelowTheHorizonIsNotDrawnAndTheFrameMovesByLessThanHalfACode) {
  // render/frame/sun_light.h: where the sun's light through the atmosphere
  // could not move a display value (the tables' bound for its cosine, times
  // its irradiance and the exposure, under half a code step at black), the
  // atmosphere's sky-and-ground tiles are zeroed instead of drawn by the sun's
  // pass; the frame with the sun's passes forced on is within half a code of
  // it, with the stars, the night floor and the Moon's light (the Moon up,
  // 2026-01-03) added to both. In deep twilight the sun's pass runs.
  REQUIRE_CATALOGUE();
  RenderOptions o = options(true, true);
  o.night_sky.moon = true;
  RenderOptions forced = o;
  forced.skip_hidden_sunlight = false;
  TestRenderer tested(o), always(forced);
  const warp::FisheyeProjection dome(48, 48);
  for (double depression : {45.0, 60.0, 80.0})
    for (double exposure : {3e5, 1e6}) {
      scene::Scene s = at_twilight(depression, exposure);
      s.sky_clock->time = astro::UtcTime{2026, 1, 3, 23, 0, 0.0};  // the full Moon 57° up
      const std::string at = twilight_label(depression, exposure);
      const auto a = tested.renderer.render_image(s, dome);
      const FrameStats stats = tested.renderer.last_frame();
      EXPECT_TRUE(stats.sunlight_skipped) << at;
      EXPECT_LT(stats.sunlight_bound, kInvisibleDisplayStep) << at;
      EXPECT_TRUE(stats.moonlight) << at;
      EXPECT_GT(stats.night_sky.stars, 0u) << at;
      const auto b = always.renderer.render_image(s, dome);
      EXPECT_FALSE(always.renderer.last_frame().sunlight_skipped) << at;
      const testing::CodeDifference d = expect_within_half_a_code(a, b, at);
      std::printf("%s: the sun's bound %.3g, its passes skipped; %.3g code from the frame with them\n", at.c_str(),
                  stats.sunlight_bound, d.largest_code_change);
    }
  for (double depression : {14.0, 18.0}) {
    tested.renderer.render_image(at_twilight(depression, 3e5), dome);
    EXPECT_FALSE(tested.renderer.last_frame().sunlight_skipped) << "sun " << depression << "° down: its twilight shows";
  }
}

TEST(NightSkyPass, TheUnlitTilesZeroedByAPassOrByABufferClearGiveTheSameFrame) {
  // UnlitTileZeroing: a GPU zeroes the tiles the sun's pass leaves black
  // with zero_tiles.comp, a CPU rasterizer by clearing the band's output;
  // the Moon's light, the night floor and the stars then add to either,
  // bit for bit the same, read back or read on the GPU, band by band.
  REQUIRE_CATALOGUE();
  RenderOptions o = options(true, true);
  o.night_sky.moon = true;
  o.max_band_pixels = 48 * 16;  // three bands
  o.time_passes = true;         // the pass_ms labels say which way ran
  RenderOptions by_pass = o, by_clear = o;
  by_pass.unlit_tile_zeroing = UnlitTileZeroing::compute_pass;
  by_clear.unlit_tile_zeroing = UnlitTileZeroing::buffer_clear;
  TestRenderer pass(by_pass), clear(by_clear);
  const warp::FisheyeProjection dome(48, 48);
  scene::Scene s = at_twilight(60.0, 1e6);
  s.sky_clock->time = astro::UtcTime{2026, 1, 3, 23, 0, 0.0};  // the full Moon 57° up
  const auto a = pass.renderer.render_image(s, dome);
  const FrameStats with_pass = pass.renderer.last_frame();
  const auto b = clear.renderer.render_image(s, dome);
  const FrameStats with_clear = clear.renderer.last_frame();
  ASSERT_TRUE(with_pass.sunlight_skipped && with_clear.sunlight_skipped);
  EXPECT_TRUE(with_pass.pass_ms.contains("zero (sun below)") && !with_pass.pass_ms.contains("clear (sun below)"));
  EXPECT_TRUE(with_clear.pass_ms.contains("clear (sun below)") && !with_clear.pass_ms.contains("zero (sun below)"));
  EXPECT_TRUE(with_pass.moonlight);
  EXPECT_GT(with_pass.night_sky.stars, 0u);
  double largest = 0.0;
  for (float v : a) largest = std::max(largest, double(v));
  EXPECT_GT(largest, 0.0) << "a night frame with the Moon's light";
  EXPECT_EQ(a, b) << "the frame zeroed by a pass is the one zeroed by a buffer clear";
  gl::Texture target = gl::Texture::create_2d(gl::TextureFormat::rgba32f, 48, 48);
  pass.renderer.render_to_texture(s, dome, target);
  const std::vector<float> rgba = target.read();
  std::size_t differing = 0;
  for (std::size_t i = 0; i < 48 * 48; ++i)
    for (std::size_t k = 0; k < 3; ++k) differing += rgba[i * 4 + k] != a[i * 3 + k];
  EXPECT_EQ(differing, 0u) << "values of the texture not the read-back frame's";
}

TEST(NightSkyPass, TheGpuPathCarriesTheStarsAsTheReadBackFrameDoes) {
  // From space (airless Earth below, black tiles around): stars land in tiles
  // no other pass drew; render_to_texture (the live path's bands) equals render_image.
  REQUIRE_CATALOGUE();
  const astro::StarCatalogue c = bright_stars();
  const scene::Scene s = greenwich("", glm::normalize(sirius_enu(c) + glm::dvec3(0.17, 0, 0)), 1e6);
  RenderOptions o = options(true, false);
  o.max_band_pixels = 48 * 16;  // three bands
  TestRenderer t(o);
  const warp::FisheyeProjection dome(48, 48);
  const auto image = t.renderer.render_image(s, dome);
  ASSERT_GT(t.renderer.last_frame().night_sky.stars, 0u);
  gl::Texture target = gl::Texture::create_2d(gl::TextureFormat::rgba32f, 48, 48);
  t.renderer.render_to_texture(s, dome, target);
  const std::vector<float> rgba = target.read();
  // Then the read-back frame again, and the texture again: a difference says
  // whether a path or a frame's place in the sequence loses a pixel.
  const auto image_again = t.renderer.render_image(s, dome);
  t.renderer.render_to_texture(s, dome, target);
  const std::vector<float> rgba_again = target.read();
  double largest = 0.0;
  std::size_t differing = 0, image_changed = 0, texture_changed = 0;
  for (std::size_t i = 0; i < 48 * 48; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const float texture = rgba[i * 4 + k], read_back = image[i * 3 + k];
      if (texture != read_back && ++differing <= 6) {
        // Where a wrong value may come from: the same place in the other
        // bands (16 rows each) of the read-back frame.
        const std::size_t x = i % 48, y = i / 48;
        std::string others;
        for (std::size_t band = 0; band < 3; ++band)
          others += fmt::format(" band {} {}", band, image[((band * 16 + y % 16) * 48 + x) * 3 + k]);
        ADD_FAILURE() << "pixel " << i << " (x " << x << ", y " << y << ": band " << y / 16 << ", its row " << y % 16
                      << ") channel " << k << ": the texture " << texture << ", the read-back frame " << read_back
                      << "; rendered again: the read-back frame " << image_again[i * 3 + k] << ", the texture "
                      << rgba_again[i * 4 + k] << "; the read-back frame at this place of each band:" << others;
      }
      image_changed += image_again[i * 3 + k] != read_back;
      texture_changed += rgba_again[i * 4 + k] != texture;
      largest = std::max(largest, double(read_back));
    }
  EXPECT_EQ(differing, 0u) << "values of the read-back frame not the texture's";
  EXPECT_EQ(image_changed, 0u) << "values of the read-back frame rendered again not the first's";
  EXPECT_EQ(texture_changed, 0u) << "values of the texture rendered again not the first's";
  EXPECT_GT(largest, 0.0);
}

TEST(NightSkyPass, ALiveRendererSwitchesVariantsWithTheNightSkysProgramsBuiltAhead) {
  // A live renderer draws with the frame variant in use while a leaner one
  // builds on a second thread, then switches (render/frame/live_variants.h).
  // The night sky's programs are compiled for each variant too: they are
  // built ahead with the others, so no frame builds a program — the switch
  // in a live show used to compile them on the frame's thread — and the
  // frames after it are the offline renderer's. The sky from space with its
  // stars; a moon on the sun–Earth line (its shadow can fall: the eclipse
  // code), then a quarter turn away from it (none can: the leaner variant).
  REQUIRE_CATALOGUE();
  const astro::StarCatalogue c = bright_stars();
  scene::Scene apart = greenwich("", glm::normalize(sirius_enu(c) + glm::dvec3(0.17, 0, 0)), 1e6);
  scene::Body moon = apart.bodies[0];
  moon.name = "moon";
  moon.atmosphere.reset();
  moon.radius_m = 1.7374e6;
  const glm::dvec3 sun = glm::normalize(apart.sun.direction);
  scene::Scene eclipsed = apart;
  moon.position_m = sun * 3.844e8;
  eclipsed.bodies.push_back(moon);
  moon.position_m = glm::normalize(glm::cross(sun, glm::dvec3(0.0, 0.0, 1.0))) * 3.844e8;
  apart.bodies.push_back(moon);
  ASSERT_TRUE(eclipses_possible(eclipsed));
  ASSERT_FALSE(eclipses_possible(apart));
  const warp::FisheyeProjection dome(48, 48);
  RenderOptions live = options(true, false);
  live.background_variant_builds = true;
  TestRenderer t(live), offline(options(true, false));
  const std::vector<float> expected = offline.renderer.render_image(apart, dome);
  ASSERT_GT(offline.renderer.last_frame().night_sky.stars, 0u);

  t.renderer.render_image(eclipsed, dome);
  ASSERT_GT(t.renderer.last_frame().night_sky.stars, 0u);
  EXPECT_FALSE(t.renderer.last_frame().variant_held) << "the first frame builds what it needs";
  std::vector<float> image = t.renderer.render_image(apart, dome);
  EXPECT_TRUE(t.renderer.last_frame().variant_held) << "drawn with the eclipse code";
  EXPECT_EQ(t.renderer.last_frame().programs_built, 0) << "no program built for the frame";
  const int frames =
      testing::frames_until_the_wanted_variant(t.renderer, [&] { image = t.renderer.render_image(apart, dome); });
  ASSERT_FALSE(t.renderer.last_frame().variant_held) << "still the eclipse code after 400 frames";
  std::printf("the leaner programs, the night sky's too, drawn from frame %d on\n", frames);
  EXPECT_GT(t.renderer.last_frame().night_sky.stars, 0u);
  EXPECT_EQ(image, expected) << "the offline renderer's programs, the same pixels";
}

}  // namespace
}  // namespace zenith::render
