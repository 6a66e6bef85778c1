// The star pass's test, star by star (render/night/star_visibility.h): the
// sky bound behind one star below every pixel its splat touches, from the sun
// at the horizon to deep twilight, through the 4D tables and the sky-view
// table; where the test skips, the frame with the stars forced on within half
// a code of it in every value, so the same 8-bit code or one step away where
// the sky sits within that of a rounding boundary (a dome master and a planar
// view, both tone operators, day, twilight and the evening show's first
// frames with its own exposure track); and a bright star on a dark sky that
// moves a code is never skipped.
//
// Small images (≤ 64²), the shared small tables. Needs stellarium-data
// (scripts/bootstrap) for the stars; skipped without it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "../atmosphere/lut_fixture.h"
#include "astro/star_catalogue.h"
#include "atmosphere/lut/sky_radiance_lower_bound.h"
#include "core/units.h"
#include "image/colour.h"
#include "image/tone_mapping.h"
#include "render/night/star_visibility.h"
#include "scene/frame_scene.h"
#include "scene/local_horizon.h"
#include "show/show.h"
#include "tests/render/code_difference.h"
#include "tests/render/greenwich_night.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::render {
namespace {

using atmosphere::lut::SmallTables;
using core::kDeg;
using testing::TestRenderer;

#define REQUIRE_CATALOGUE()                                                                        \
  if (!std::filesystem::exists(astro::kStellariumStarDirectory / "stars_0_0v0_8.cat"))             \
  GTEST_SKIP() << "stellarium-data is not installed (" << astro::kStellariumStarDirectory.string() \
               << "): scripts/bootstrap installs it"

const astro::UtcTime kTime{2026, 1, 15, 23, 0, 0.0};  // Sirius due south, 20° up at Greenwich

RenderOptions options(bool stars, double magnitude_limit = 1.5) {
  RenderOptions o;
  o.colour = image::ColourMapping::direct;  // channel c = radiance at 680, 550, 440 nm × exposure
  o.sun_disc = false;
  o.night_sky.stars = stars;
  o.night_sky.night_floor = false;
  o.night_sky.star_magnitude_limit = magnitude_limit;
  o.night_sky.moon = false;
  o.night_sky.moonlight = false;
  return o;
}

/// Greenwich at kTime (earth-advanced), the camera looking along `look_enu`,
/// the sun `elevation_deg` above the horizon (below where negative) at
/// azimuth `sun_azimuth_deg` from north through east.
scene::Scene greenwich_sky(const glm::dvec3& look_enu, double exposure, double elevation_deg, double sun_azimuth_deg) {
  scene::Scene s = testing::greenwich("earth-advanced", look_enu, exposure, kTime);
  const scene::LocalHorizon h = scene::local_horizon_at(s.camera.position_m, s.bodies[0]);
  const double e = elevation_deg * kDeg, a = sun_azimuth_deg * kDeg;
  s.sun.direction = glm::normalize(std::cos(e) * (std::cos(a) * h.north + std::sin(a) * h.east) + std::sin(e) * h.up);
  return s;
}

/// Sirius (the catalogue's brightest) in the site's east-north-up frame at kTime, geometric.
glm::dvec3 sirius_enu() {
  const astro::SkyPositions sky(astro::AstroTime::from_utc(kTime),
                                astro::Site{testing::kGreenwichLatitudeDeg, testing::kGreenwichLongitudeDeg, 46.0});
  astro::StarCatalogueOptions bright;
  bright.magnitude_limit = 1.5;
  return sky.star(astro::load_star_catalogue(bright).stars.front()).east_north_up();
}

TEST(StarVisibility, TheSkyBehindAStarIsNoDarkerThanItsOwnBound) {
  // Every pixel a star's splat would touch, for a star at every pixel of a 64²
  // dome (offset from the centres), is at least the star's own bound B_s
  // (SkyBehindStarBound::at over the splat's footprint), from the sun at the horizon
  // to 14° down at the evening show's first and last exposures, through the
  // 4D tables and through the sky-view table; and B_s is well above the
  // darkest sky's B where the star is not kept.
  const SmallTables& t = SmallTables::get("earth-advanced");
  const atmosphere::lut::SkyRadianceLowerBound floor(t.model, t.tables, true);
  const warp::FisheyeProjection dome(64, 64);
  for (const SkyViewTableUse use : {SkyViewTableUse::always, SkyViewTableUse::off}) {
    RenderOptions o = options(false);
    o.sky_view_table = use;
    o.skip_hidden_sunlight = false;  // the sky the tables give, also where it is too faint to show
    TestRenderer r(o);
    for (double depression : {0.0, 3.0, 6.0, 10.0, 14.0})
      for (double exposure : {10.0, 2e5}) {
        const scene::Scene s = greenwich_sky({0, 0, 1}, exposure, -depression, 180.0);
        const auto image = r.renderer.render_image(s, dome);
        const glm::dvec3 up = glm::normalize(s.camera.position_m);
        const glm::dmat3 camera_to_world = glm::mat3_cast(s.camera.orientation);
        const auto weights = image::spectral_to_rgb_weights(s.wavelengths_nm, image::ColourMapping::direct);
        const std::vector<double> k =
            floor.radiance_per_irradiance(glm::dot(up, s.sun.direction), glm::length(s.camera.position_m));
        std::array<double, 3> whole{};
        for (std::size_t c = 0; c < 3; ++c)
          for (std::size_t i = 0; i < weights.size(); ++i)
            whole[c] += exposure * weights[i][c] * s.sun.irradiance_W_m2_nm[i] * k[i];
        const SkyBehindStarBound behind(floor, s.camera.position_m, s.bodies[0].position_m, t.model.ground_radius_m,
                                        s.sun.direction, use == SkyViewTableUse::always, weights,
                                        s.sun.irradiance_W_m2_nm, exposure, {}, whole);
        std::size_t checked = 0, stars = 0, kept = 0, above = 0;
        double least_ratio = 1e300;  // B_s over the darkest pixel its splat touches
        for (int y = 0; y < 64; ++y)
          for (int x = 0; x < 64; ++x) {
            const glm::dvec2 p(x + 0.5 + 0.3, y + 0.5 - 0.2);
            const auto ray = dome.ray(p.x, p.y);
            if (!ray) continue;
            const glm::dvec3 d = glm::normalize(camera_to_world * glm::normalize(*ray));
            if (glm::dot(d, up) <= 0.0) continue;  // the ground hides it
            const auto rho = splat_footprint_radius(dome, camera_to_world, p, d);
            if (!rho) continue;
            ++stars;
            if (behind.kept(d, *rho)) {
              ++kept;
              continue;
            }
            const std::array<double, 3> b = behind.at(d, *rho);
            double darkest = 1e300;
            for (int py = static_cast<int>(std::floor(p.y - 0.5)); py <= static_cast<int>(std::floor(p.y - 0.5)) + 1;
                 ++py)
              for (int px = static_cast<int>(std::floor(p.x - 0.5)); px <= static_cast<int>(std::floor(p.x - 0.5)) + 1;
                   ++px) {
                if (px < 0 || py < 0 || px >= 64 || py >= 64) continue;
                const auto pixel_ray = dome.ray(px + 0.5, py + 0.5);
                if (!pixel_ray || glm::dot(camera_to_world * glm::normalize(*pixel_ray), up) <= 0.0) continue;
                for (std::size_t c = 0; c < 3; ++c) {
                  const double v = image[(static_cast<std::size_t>(py) * 64 + px) * 3 + c];
                  EXPECT_LE(b[c], v) << "sun " << depression << "° down, exposure " << exposure << ", star at (" << p.x
                                     << ", " << p.y << "), pixel (" << px << ", " << py << "), channel " << c
                                     << (use == SkyViewTableUse::always ? ", sky-view" : ", 4D");
                  darkest = std::min(darkest, v / b[c]);
                  ++checked;
                }
              }
            if (darkest < 1e300) least_ratio = std::min(least_ratio, darkest);
            above += b[1] > 1.5 * whole[1];
          }
        EXPECT_GT(checked, 2000u);
        EXPECT_LT(kept, stars / 2) << "most stars get their own bound";
        // Where B, the darkest sky's floor, sits well under this part of the sky, B_s rises with it.
        if (depression >= 3.0) {
          EXPECT_GT(above, (stars - kept) / 2) << "sun " << depression << "° down";
        }
        if (exposure == 10.0 && use == SkyViewTableUse::off)
          std::printf(
              "sun %4.1f° down: %zu of %zu stars on their own bound, %zu above 1.5 B; the darkest pixel ≥ %.3f B_s\n",
              depression, stars - kept, stars, above, least_ratio);
      }
  }
}

/// Renders `s` with the test and with the stars forced on; where the test
/// skipped, checks the two frames agree to the code. Returns 1 where the
/// second stage decided to skip, else 0.
int check_skip(TestRenderer& tested, TestRenderer& forced, const scene::Scene& s, const warp::Projection& p,
               const std::string& what) {
  const auto a = tested.renderer.render_image(s, p);
  const FrameStats stats = tested.renderer.last_frame();
  if (stats.night_sky.star_test.could_show) return 0;
  EXPECT_EQ(stats.night_sky.stars, 0u) << what;
  EXPECT_LT(stats.night_sky.star_test.code_change, kInvisibleCodeChange) << what;
  const auto b = forced.renderer.render_image(s, p);
  if (forced.renderer.last_frame().night_sky.stars == 0) return 0;  // nothing to compare with
  // Every value within half a code: each 8-bit code the same, or one step
  // away where the sky sits within that change of a rounding boundary.
  const testing::CodeDifference d = testing::code_difference(a, b);
  EXPECT_LT(d.largest_code_change, kInvisibleCodeChange) << what;
  EXPECT_LE(d.largest_byte_change, 1) << what;
  EXPECT_LE(d.codes_differing, a.size() / 100) << what;
  const bool second = stats.night_sky.star_test.stars_tested > 0;
  std::printf("%s: skipped by the %s stage (bound %.3g code), the forced frame %.3g code away, %zu codes differ\n",
              what.c_str(), second ? "second" : "first", stats.night_sky.star_test.code_change, d.largest_code_change,
              d.codes_differing);
  return second ? 1 : 0;
}

TEST(StarVisibility, WhereItSkipsTheFrameWithTheStarsForcedOnIsTheSameToTheCode) {
  REQUIRE_CATALOGUE();
  RenderOptions o = options(true, 4.0);
  RenderOptions always = o;
  always.night_sky.skip_hidden_stars = false;
  TestRenderer tested(o), forced(always);
  int second = 0;
  // A dome master (zenith up) and a 10° planar view of Sirius, day and twilight.
  const warp::FisheyeProjection dome(48, 48);
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(64, 48, 10.0);
  const glm::dvec3 sirius = sirius_enu();
  for (double elevation : {30.0, 0.0, -3.0, -6.0, -9.0})
    for (double exposure : {30.0, 300.0, 3000.0, 3e4, 3e5}) {
      const std::string at = "sun " + std::to_string(elevation) + "°, exposure " + std::to_string(exposure);
      second += check_skip(tested, forced, greenwich_sky({0, 0, 1}, exposure, elevation, 0.0), dome, "dome, " + at);
      second += check_skip(tested, forced, greenwich_sky(sirius, exposure, elevation, 0.0), planar, "planar, " + at);
    }
  // The evening show's first frames, with its own exposure track, on a dome master.
  const show::Show show =
      show::load_show(std::filesystem::path(ZENITH_SOURCE_DIR) / "configs/shows/earth-evening-hayden.json");
  const warp::FisheyeProjection master(256, 256);
  for (double t_s : {0.0, 4.0, 8.0, 12.0, 16.0}) {
    scene::Scene s = show.scene();
    scene::apply_frame(show.state_at(t_s, 0, 0), s);
    second += check_skip(tested, forced, s, master, "the evening show at " + std::to_string(t_s) + " s");
  }
  EXPECT_GE(second, 3) << "the second stage skips frames the first could not";
}

TEST(StarVisibility, BeforeItsLadderTheBrightestStarInTheViewAnswers) {
  // A 4° view on the first star after the 16 brightest (to V 3) with no
  // brighter star within 5° of it, 25° or more up, the sun 18° down: where
  // the forced star moves a code, the test decides from that star alone,
  // before its ladder (whose rungs test 16, 64 and all of the catalogue's stars
  // one by one: never that star's rank). The 16 brightest out of view used to
  // send every narrow night view through the ladder (3.7 ms of a 79° ground
  // view's frame on this project's VM).
  REQUIRE_CATALOGUE();
  constexpr double kLimit = 3.0;
  astro::StarCatalogueOptions catalogue_options;
  catalogue_options.magnitude_limit = kLimit;
  const astro::StarCatalogue catalogue = astro::load_star_catalogue(catalogue_options);
  const astro::SkyPositions sky(astro::AstroTime::from_utc(kTime),
                                astro::Site{testing::kGreenwichLatitudeDeg, testing::kGreenwichLongitudeDeg, 46.0});
  std::vector<glm::dvec3> enu;
  for (const auto& star : catalogue.stars) {
    enu.push_back(sky.star(star).east_north_up());
  }
  std::size_t k = kFirstStarsTested;
  const auto alone = [&](std::size_t j) {
    for (std::size_t i = 0; i < j; ++i)
      if (glm::dot(enu[i], enu[j]) > std::cos(5.0 * kDeg)) return false;
    return enu[j].z > std::sin(25.0 * kDeg);
  };
  while (k < enu.size() && !alone(k)) ++k;
  ASSERT_LT(k, enu.size());
  ASSERT_NE(k + 1, kNeighbourhoodFirsts[2]);  // a rung's count
  ASSERT_NE(k + 1, enu.size());
  RenderOptions o = options(true, kLimit), always = o;
  always.night_sky.skip_hidden_stars = false;
  TestRenderer tested(o), forced(always), without(options(false));
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(32, 32, 4.0);
  int decided = 0;
  for (double exposure = 1e3; exposure < 2e6; exposure *= std::sqrt(10.0)) {
    const scene::Scene s = greenwich_sky(enu[k], exposure, -18.0, 0.0);
    const auto image = forced.renderer.render_image(s, planar);
    ASSERT_GE(forced.renderer.last_frame().night_sky.stars, 1u) << "exposure " << exposure;
    if (testing::code_difference(image, without.renderer.render_image(s, planar)).largest_code_change < 0.5) continue;
    tested.renderer.render_image(s, planar);
    EXPECT_TRUE(tested.renderer.last_frame().night_sky.star_test.could_show) << "exposure " << exposure;
    EXPECT_EQ(tested.renderer.last_frame().night_sky.star_test.stars_tested, k + 1) << "exposure " << exposure;
    ++decided;
  }
  std::printf("the view on the catalogue's star %zu (V %.2f): decided by it alone at %d exposures\n", k + 1,
              catalogue.stars[k].v_mag, decided);
  EXPECT_GE(decided, 2);
}

TEST(StarVisibility, ABrightStarOnADarkSkyThatMovesACodeIsNeverSkipped) {
  // Sirius 20° up in the south, the sun 9° down in the north (the dark side of
  // the sky), a 4° planar view on the star: raising the exposure, the test
  // must let the stars run in every frame where the forced stars move a code
  // value by half a code, and it does skip the frames below.
  REQUIRE_CATALOGUE();
  RenderOptions o = options(true);
  RenderOptions always = o;
  always.night_sky.skip_hidden_stars = false;
  TestRenderer tested(o), forced(always);
  const warp::PlanarProjection planar = warp::PlanarProjection::symmetric(32, 32, 4.0);
  const glm::dvec3 sirius = sirius_enu();
  double first_visible = 0.0, first_run = 0.0;
  for (double exposure = 0.1; exposure < 2e6; exposure *= std::sqrt(std::sqrt(10.0))) {
    const scene::Scene s = greenwich_sky(sirius, exposure, -9.0, 0.0);
    const auto a = tested.renderer.render_image(s, planar);
    const bool runs = tested.renderer.last_frame().night_sky.star_test.could_show;
    const auto b = forced.renderer.render_image(s, planar);
    ASSERT_GT(forced.renderer.last_frame().night_sky.stars, 0u);
    // The star's change against the same frame without stars.
    const auto none = [&] {
      RenderOptions without = options(false);
      TestRenderer r(without);
      return r.renderer.render_image(s, planar);
    }();
    const double moved = testing::code_difference(b, none).largest_code_change;
    if (moved >= 0.5) {
      EXPECT_TRUE(runs) << "exposure " << exposure << ": the star moves " << moved << " code";
      // Sirius alone moves a code: the second stage says so from the brightest
      // stars alone, before its ladder (which tests at least kFirstStarsTested).
      const std::size_t tested_stars = tested.renderer.last_frame().night_sky.star_test.stars_tested;
      EXPECT_GE(tested_stars, 1u) << "exposure " << exposure;
      EXPECT_LT(tested_stars, kFirstStarsTested) << "exposure " << exposure;
    }
    if (moved >= 0.5 && first_visible == 0.0) first_visible = exposure;
    if (runs && first_run == 0.0) first_run = exposure;
    if (!runs) {
      EXPECT_LT(testing::code_difference(a, b).largest_code_change, kInvisibleCodeChange);
    }
  }
  ASSERT_GT(first_visible, 0.0) << "the star shows at some exposure";
  ASSERT_GT(first_run, 0.1) << "and the test skips it below";
  std::printf("Sirius moves half a code from exposure %.3g; the test lets the stars run from %.3g (%.2f times lower)\n",
              first_visible, first_run, first_visible / first_run);
  EXPECT_LE(first_run, first_visible);
}

}  // namespace
}  // namespace zenith::render
