// The Earth's shadow at the Moon's distance (astro/lunar_eclipse.h): the
// grazing rays' bending against the refraction at the horizon, the light
// the planet and its air take from the plane behind them (energy kept by
// the refraction), the umbra's red light, its edge and the geometry by date.
// Its light curve against photometry of real eclipses is `zenith validate
// eclipse`'s (docs/validation.md, "Lunar eclipses").
#include "astro/lunar_eclipse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include "astro/refraction.h"
#include "astro/v_band.h"
#include "atmosphere/parameters.h"
#include "atmosphere/photometry.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

using atmosphere::LoadedAtmosphere;

constexpr double kMoonDistance_m = 384.4e6;
constexpr double kSunRadius_rad = 4.65e-3;

class LunarEclipse : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    loaded_ = new LoadedAtmosphere(atmosphere::load_preset("earth-advanced"));
    shadow_ = new EarthShadow(*loaded_, kMoonDistance_m, kSunRadius_rad,
                              std::vector<atmosphere::LimbDarkening>(loaded_->model.wavelengths_nm.size()));
  }
  static void TearDownTestSuite() {
    delete shadow_;
    delete loaded_;
  }
  static LoadedAtmosphere* loaded_;
  static EarthShadow* shadow_;
};
LoadedAtmosphere* LunarEclipse::loaded_ = nullptr;
EarthShadow* LunarEclipse::shadow_ = nullptr;

TEST_F(LunarEclipse, AGrazingRayBendsByTwiceTheRefractionAtTheHorizon) {
  // At the ground: twice Bennett's 34.5′ (1010 hPa, 10 °C) within the model's own air's difference
  // (its density at 15 °C: a few percent less); 10 km up, the density's e-fold of 8 km: ~0.29×.
  const double ground = shadow_->deflection_rad(0.0, 1) / core::kDeg * 60.0;
  EXPECT_NEAR(ground, 2.0 * bennett_refraction_deg(0.0) * 60.0, 0.08 * ground) << "arcmin, 550 nm";
  EXPECT_NEAR(shadow_->deflection_rad(10e3, 1) / shadow_->deflection_rad(0.0, 1), std::exp(-10.0 / 8.0), 0.05);
  // Dispersion: the blue bends more than the red.
  EXPECT_GT(shadow_->deflection_rad(0.0, 2), shadow_->deflection_rad(0.0, 0));
}

TEST_F(LunarEclipse, RefractionMovesTheLightTheAirLetsThroughButKeepsIt) {
  // ∫ (1 − E) 2πY dY over the plane behind the planet is the light the planet and its air take away:
  // π R² of the ground plus ∫ (1 − T(b)) 2πb db over the air. The Sun's disc and the bending only move
  // the rest (to the bins' and heights' resolution).
  const double ground = loaded_->model.ground_radius_m, top = loaded_->model.top_radius_m;
  for (std::size_t i = 0; i < 3; ++i) {
    double taken = 0.0;
    const double step = 1e3;
    for (double y = 0.5 * step; y < top + 2.5e6; y += step)
      taken += (1.0 - shadow_->illumination(y, i)) * 2.0 * core::kPi * y * step;
    double expected = core::kPi * ground * ground;
    for (double b = ground + 5.0; b < top; b += 10.0)
      expected += (1.0 - shadow_->grazing_transmittance(b - ground, i)) * 2.0 * core::kPi * b * 10.0;
    EXPECT_NEAR(taken / expected, 1.0, 0.01) << loaded_->model.wavelengths_nm[i] << " nm";
  }
}

TEST_F(LunarEclipse, TheUmbraIsLitRedAndItsEdgeLiesBeyondTheGeometricOne) {
  // No light reaches the geometric umbra in straight lines; the refracted light is red (the blue is
  // scattered out of the grazing rays) and ~1e-4 of the Sun's at the centre (Vollmer & Gedzelman 2008:
  // 1/2400 for pure molecular air; aerosols and ozone take more).
  const double centre_red = shadow_->illumination(0.0, 0), centre_blue = shadow_->illumination(0.0, 2);
  EXPECT_GT(centre_red, 5.0 * centre_blue);
  EXPECT_GT(centre_red, 1e-5);
  EXPECT_LT(centre_red, 1e-2);
  EXPECT_NEAR(shadow_->illumination(loaded_->model.top_radius_m + 2.0 * kMoonDistance_m * kSunRadius_rad, 1), 1.0,
              1e-9);
  // The umbra as observers time it (crater contacts): ~2 % larger than the solid planet's (Chauvenet's
  // 1/50; single eclipses 1.7–2.1 %: docs/validation.md).
  const double enlargement = shadow_->apparent_umbra_radius_m(1) / shadow_->geometric_umbra_radius_m() - 1.0;
  EXPECT_GT(enlargement, 0.0);
  EXPECT_LT(enlargement, 0.05);
}

TEST_F(LunarEclipse, TheMoonSitsInTheShadowAtAnEclipsesMaximum) {
  // 2019-01-21, greatest eclipse 05:12:16 UT (NASA: umbral magnitude 1.195, gamma 0.368): the Moon's centre
  // 0.368 Earth radii from the axis, ~357 000 km away (a perigee eclipse).
  const LunarEclipseGeometry g = lunar_eclipse_geometry(AstroTime::from_utc({2019, 1, 21, 5, 12, 16.0}));
  EXPECT_NEAR(g.axis_distance_m / 6378.137e3, 0.368, 0.01);
  EXPECT_NEAR(g.moon_distance_m, 357.7e6, 1.5e6);
  EXPECT_NEAR(g.sun_angular_radius_rad / core::kDeg * 60.0, 16.26, 0.05) << "arcmin, in January";
}

TEST(LunarEclipseSearch, FindsTheNextEclipseASiteSeesAsNasasCanonHasIt) {
  // NASA's Five Millennium Canon (Espenak & Meeus): 2025-03-14, total, greatest eclipse 06:58:43, umbral
  // magnitude 1.1784, totality 65 min, the Moon up over Greenwich at its start; 2025-09-07, total,
  // 18:11:48, 1.3619, 82 min, seen from Sydney. Times within 3 min (TD and UT are 69 s apart), magnitudes
  // within 0.01 (Danjon's rule on both sides), totality within 2 min.
  const auto minutes_between = [](const AstroTime& a, const AstroTime& b) {
    return (b.utc().value() - a.utc().value()) * 1440.0;
  };
  const auto march = next_lunar_eclipse(Site{51.4779, -0.0015, 46.0}, AstroTime::from_utc({2025, 1, 1, 0, 0, 0.0}));
  ASSERT_TRUE(march.has_value());
  EXPECT_EQ(march->kind, LunarEclipseKind::total);
  EXPECT_NEAR(minutes_between(AstroTime::from_utc({2025, 3, 14, 6, 58, 43.0}), march->maximum), 0.0, 3.0);
  EXPECT_NEAR(march->umbral_magnitude, 1.1784, 0.01);
  EXPECT_NEAR(minutes_between(*march->totality_begins, *march->totality_ends), 65.0, 2.0);
  const auto september =
      next_lunar_eclipse(Site{-33.8688, 151.2093, 10.0}, AstroTime::from_utc({2025, 3, 20, 0, 0, 0.0}));
  ASSERT_TRUE(september.has_value());
  EXPECT_EQ(september->kind, LunarEclipseKind::total);
  EXPECT_NEAR(minutes_between(AstroTime::from_utc({2025, 9, 7, 18, 11, 48.0}), september->maximum), 0.0, 3.0);
  EXPECT_NEAR(september->umbral_magnitude, 1.3619, 0.01);
  EXPECT_NEAR(minutes_between(*september->totality_begins, *september->totality_ends), 82.0, 2.0);
  EXPECT_GT(september->moon_altitude_deg, 0.0);
  for (const LocalLunarEclipse* e : {&*march, &*september})
    std::printf("%s, maximum %s, umbral magnitude %.4f, totality %.1f min\n", to_string(e->kind),
                format_utc_time(e->maximum.calendar_utc()).c_str(), e->umbral_magnitude,
                minutes_between(*e->totality_begins, *e->totality_ends));
  EXPECT_THROW(next_lunar_eclipse(Site{0, 0, 0}, AstroTime::from_utc({2025, 1, 1, 0, 0, 0.0}), 31.0),
               std::invalid_argument);
}

TEST_F(LunarEclipse, RefusesWhatIsNoShadow) {
  const std::vector<atmosphere::LimbDarkening> uniform(loaded_->model.wavelengths_nm.size());
  EXPECT_THROW(EarthShadow(*loaded_, 1e6, kSunRadius_rad, uniform), std::invalid_argument);
  EXPECT_THROW(EarthShadow(*loaded_, kMoonDistance_m, 0.0, uniform), std::invalid_argument);
  EXPECT_THROW(EarthShadow(*loaded_, kMoonDistance_m, kSunRadius_rad, {atmosphere::LimbDarkening{}}),
               std::invalid_argument);
  std::vector<atmosphere::LimbDarkening> not_a_law = uniform;
  not_a_law[1].coefficients[0] = 0.5;
  EXPECT_THROW(EarthShadow(*loaded_, kMoonDistance_m, kSunRadius_rad, not_a_law), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::astro
