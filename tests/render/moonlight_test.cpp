// The Moon as the atmosphere passes' second light (render/night/moon_light.h,
// docs/night-sky.md, "Moonlight"): the moonlit sky is the sunlit sky with the
// sun at the Moon's place, scaled by the Moon's irradiance (the tables are
// linear in their source); the passes skipped by their own test by day; the
// zenith under a full Moon against Krisciunas & Schaefer (1991).
//
// Small images (≤ 64²), the shared small tables (earth-advanced at 680, 550,
// 440 nm, the direct colour mapping: channel c is the radiance at λ_c × exposure).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "astro/moon_photometry.h"
#include "astro/sky_positions.h"
#include "astro/v_band.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/sky_radiance_bound.h"
#include "core/units.h"
#include "render/night/star_pass.h"
#include "tests/render/greenwich_night.h"
#include "validate/moonlit_sky.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::render {
namespace {

using core::kDeg;
using testing::TestRenderer;

const astro::Site kSite{testing::kGreenwichLatitudeDeg, testing::kGreenwichLongitudeDeg, 46.0};
const astro::UtcTime kFullMoon{2026, 1, 3, 23, 0, 0.0};  // 99 % lit, high in the south-east at Greenwich

/// A dome master's camera: looking south, the dome's centre at the zenith.
const glm::dvec3 kDomeLook{0.0, -1.0, 0.0};

RenderOptions options(bool moonlight, SkyViewTableUse sky_view = SkyViewTableUse::always) {
  RenderOptions o;
  o.colour = image::ColourMapping::direct;
  o.sun_disc = false;
  o.sky_view_table = sky_view;
  o.night_sky.stars = false;
  o.night_sky.night_floor = false;
  o.night_sky.moon = false;  // the disc is night_sky.comp's: not part of these tests
  o.night_sky.moonlight = moonlight;
  return o;
}

astro::MoonPlace moon_at(const astro::UtcTime& t) {
  return astro::SkyPositions(astro::AstroTime::from_utc(t), kSite).moon();
}

/// The Moon's direction in the world as the renderer places its light (geometric, the camera's local horizon).
glm::dvec3 moon_direction(const scene::Scene& s, const astro::MoonPlace& moon) {
  const scene::LocalHorizon h = scene::local_horizon_at(s.camera.position_m, s.bodies[0]);
  return glm::normalize(h.direction(moon.horizontal.azimuth_rad, moon.horizontal.altitude_rad));
}

/// Looking at the horizon below the Moon (the ground and the sky under it).
glm::dvec3 toward_moon_azimuth(const astro::MoonPlace& moon) {
  return {std::sin(moon.horizontal.azimuth_rad), std::cos(moon.horizontal.azimuth_rad), 0.05};
}

TEST(Moonlight, TheMoonlitSkyIsTheSunlitSkyWithTheSunAtTheMoonTimesItsIrradiance) {
  const astro::MoonPlace moon = moon_at(kFullMoon);
  ASSERT_GT(moon.horizontal.altitude_rad, 20 * kDeg);
  ASSERT_LT(moon.phase_angle_rad, 10 * kDeg);
  const warp::FisheyeProjection dome(64, 64);
  const warp::PlanarProjection horizon = warp::PlanarProjection::symmetric(64, 48, 90.0);
  for (const SkyViewTableUse use : {SkyViewTableUse::always, SkyViewTableUse::off})
    for (const bool dome_view : {true, false}) {
      const warp::Projection& p = dome_view ? static_cast<const warp::Projection&>(dome) : horizon;
      const scene::Scene s =
          testing::greenwich("earth-advanced", dome_view ? kDomeLook : toward_moon_azimuth(moon), 1e6, kFullMoon);
      // The reference: no sky clock (no Moon), the sun at the Moon's place with its irradiance and size.
      scene::Scene reference = s;
      reference.sky_clock.reset();
      reference.sun.direction = moon_direction(s, moon);
      reference.sun.irradiance_W_m2_nm = astro::moon_irradiance_W_m2_nm(moon, s.wavelengths_nm);
      reference.sun.angular_radius_rad = moon.angular_radius_rad;
      TestRenderer lit(options(true, use)), dark(options(false, use));
      const std::vector<float> a = lit.renderer.render_image(s, p);
      ASSERT_TRUE(lit.renderer.last_frame().moonlight);
      const std::vector<float> b = dark.renderer.render_image(s, p);
      EXPECT_FALSE(dark.renderer.last_frame().moonlight);
      const std::vector<float> c = dark.renderer.render_image(reference, p);
      // The moonlight pass adds the reference's own numbers (the same programs,
      // uniforms and tables) to the sun's: one float addition, |error| ≤ ε|a|.
      double worst = 0.0, brightest = 0.0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        const double bound = 0x1p-23 * std::abs(double(a[i])) + 1e-30;
        worst = std::max(worst, std::abs(double(a[i]) - b[i] - c[i]) / bound);
        brightest = std::max(brightest, double(c[i]));
        ASSERT_LE(std::abs(double(a[i]) - b[i] - c[i]), bound)
            << p.describe() << (use == SkyViewTableUse::off ? ", 4D tables" : ", sky view") << ", value " << i;
      }
      EXPECT_GT(brightest, 1e-2) << "the moonlit sky at a night exposure is visible";
      std::printf("%s%s: moonlit − sunlit = reference within %.2f of the bound; brightest %.3g\n", p.describe().c_str(),
                  use == SkyViewTableUse::off ? " (4D tables)" : " (sky view)", worst, brightest);
    }
}

/// The first whole hour of 2026-01-26 (the Moon near first quarter) with both the Sun and the Moon 20° up.
std::optional<astro::UtcTime> daylight_with_the_moon_up() {
  for (int hour = 0; hour < 24; ++hour) {
    const astro::UtcTime t{2026, 1, 26, hour, 0, 0.0};
    const astro::SkyPositions sky(astro::AstroTime::from_utc(t), kSite);
    if (sky.sun().horizontal.altitude_rad > 10 * kDeg && sky.moon().horizontal.altitude_rad > 20 * kDeg) return t;
  }
  return std::nullopt;
}

TEST(Moonlight, SkippedByItsOwnTestByDayAndWithTheMoonFarBelowTheHorizon) {
  const std::optional<astro::UtcTime> day = daylight_with_the_moon_up();
  ASSERT_TRUE(day.has_value());
  scene::Scene s = testing::greenwich("earth-advanced", kDomeLook, 10.0, *day);  // a daylight exposure
  s.sun.direction =
      scene::ephemeris_sun(s, *s.sky_clock, astro::AstroTime::from_utc(*day), s.camera.position_m).direction;
  const warp::FisheyeProjection dome(64, 64);
  TestRenderer lit(options(true)), dark(options(false));
  EXPECT_EQ(lit.renderer.render_image(s, dome), dark.renderer.render_image(s, dome)) << "bit for bit";
  EXPECT_FALSE(lit.renderer.last_frame().moonlight);
  std::printf("daylight, the Moon %.1f deg up: the moonlight could add at most %.3g (half a code step: %.3g)\n",
              moon_at(*day).horizontal.altitude_rad / kDeg, lit.renderer.last_frame().moonlight_bound,
              kInvisibleDisplayStep);

  // Night (exposure 1e6), the full Moon 12 hours later: far below the horizon.
  const astro::UtcTime below{2026, 1, 4, 12, 30, 0.0};
  ASSERT_LT(moon_at(below).horizontal.altitude_rad, -12 * kDeg);
  const scene::Scene night = testing::greenwich("earth-advanced", kDomeLook, 1e6, below);
  EXPECT_EQ(lit.renderer.render_image(night, dome), dark.renderer.render_image(night, dome)) << "bit for bit";
  EXPECT_FALSE(lit.renderer.last_frame().moonlight);
  std::printf("night, the Moon %.1f deg below the horizon: at most %.3g\n",
              -moon_at(below).horizontal.altitude_rad / kDeg, lit.renderer.last_frame().moonlight_bound);
}

TEST(Moonlight, TheBoundHoldsEveryPixel) {
  // The test's bound (atmosphere/lut/sky_radiance_bound.h) is above what the passes draw.
  const astro::MoonPlace moon = moon_at(kFullMoon);
  const scene::Scene s = testing::greenwich("earth-advanced", toward_moon_azimuth(moon), 1e6, kFullMoon);
  TestRenderer lit(options(true)), dark(options(false));
  const warp::PlanarProjection horizon = warp::PlanarProjection::symmetric(64, 48, 90.0);
  const std::vector<float> a = lit.renderer.render_image(s, horizon), b = dark.renderer.render_image(s, horizon);
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, double(a[i]) - b[i]);
  EXPECT_LE(largest, lit.renderer.last_frame().moonlight_bound);
  std::printf("largest moonlit value %.3g, bound %.3g\n", largest, lit.renderer.last_frame().moonlight_bound);
}

TEST(Moonlight, EveryBandAndEveryOutputDecidesAlike) {
  // A node renders its slice as bands of its own projection: the moonlit frame
  // in four bands equals it in one, and the test's outcome and bound are the
  // same through a dome master and a planar view of the same camera (they
  // depend on the camera, the exposure and the tables, not the projection), so
  // every node of a cluster lights the same atmospheres the same way.
  const astro::MoonPlace moon = moon_at(kFullMoon);
  const scene::Scene s = testing::greenwich("earth-advanced", toward_moon_azimuth(moon), 1e6, kFullMoon);
  RenderOptions banded = options(true);
  banded.max_band_pixels = 64 * 16;
  TestRenderer whole(options(true)), bands(banded);
  const warp::PlanarProjection view = warp::PlanarProjection::symmetric(64, 64, 90.0);
  EXPECT_EQ(whole.renderer.render_image(s, view), bands.renderer.render_image(s, view));
  EXPECT_EQ(bands.renderer.last_frame().bands, 4);
  const FrameStats planar = whole.renderer.last_frame();
  whole.renderer.render_image(s, warp::FisheyeProjection(32, 32));
  EXPECT_TRUE(planar.moonlight);
  EXPECT_EQ(whole.renderer.last_frame().moonlight, planar.moonlight);
  EXPECT_EQ(whole.renderer.last_frame().moonlight_bound, planar.moonlight_bound);
}

TEST(Moonlight, ZenithUnderAFullMoonAgainstKrisciunasSchaefer1991) {
  // The full Moon of kFullMoon at Greenwich; the zenith's moonlit V surface
  // brightness from the tables (the renderer's numbers: its zenith pixel
  // equals them to the sky-view table's interpolation) against K&S 1991's
  // model with the model's own extinction coefficient k(550 nm).
  const astro::MoonPlace moon = moon_at(kFullMoon);
  const atmosphere::lut::SmallTables& t = atmosphere::lut::SmallTables::get("earth-advanced");
  const atmosphere::lut::TableQueries q(t.model, t.tables);
  const double moon_zenith_deg = 90.0 - moon.horizontal.altitude_rad / kDeg;
  const atmosphere::Vec3 camera{0.0, 0.0, t.model.ground_radius_m + 2.0};
  const atmosphere::Vec3 to_moon{std::sin(moon_zenith_deg * kDeg), 0.0, std::cos(moon_zenith_deg * kDeg)};
  const atmosphere::Spectrum per_irradiance = q.sky_radiance(camera, {0.0, 0.0, 1.0}, to_moon);
  const std::vector<double> e = astro::moon_irradiance_W_m2_nm(moon, t.model.wavelengths_nm);
  std::vector<double> radiance(e.size());
  for (std::size_t k = 0; k < e.size(); ++k) radiance[k] = per_irradiance[k] * e[k];
  const double ours = astro::v_surface_brightness(astro::v_band_mean(t.model.wavelengths_nm, radiance));
  const std::size_t green = 1;  // 550 nm
  ASSERT_NEAR(t.model.wavelengths_nm[green], 550.0, 1.0);
  const double k_v = 1.0857 * t.model.zenith_optical_depth().total[green];
  const double published = validate::v_mag_arcsec2_from_nanolamberts(
      validate::krisciunas_schaefer_moon_nL(moon.phase_angle_rad / kDeg, moon_zenith_deg, moon_zenith_deg, 0.0, k_v));
  std::printf("full Moon (phase %.1f deg) %.1f deg up, k = %.3f: zenith %.2f mag/arcsec^2, K&S 1991 %.2f\n",
              moon.phase_angle_rad / kDeg, 90.0 - moon_zenith_deg, k_v, ours, published);
  EXPECT_NEAR(ours, published, 0.5);  // docs/night-sky.md, "Moonlight": their scatter and the aerosol

  // The renderer's zenith pixel (a 65² dome master's centre) is the tables' radiance × exposure.
  const scene::Scene s = testing::greenwich("earth-advanced", kDomeLook, 1e6, kFullMoon);
  TestRenderer lit(options(true)), dark(options(false));
  const warp::FisheyeProjection dome(65, 65);
  const std::vector<float> a = lit.renderer.render_image(s, dome), b = dark.renderer.render_image(s, dome);
  const std::size_t centre = (32 * 65 + 32) * 3;
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(double(a[centre + k]) - b[centre + k], radiance[k] * 1e6, 0.03 * radiance[k] * 1e6) << "channel " << k;
}

}  // namespace
}  // namespace zenith::render
