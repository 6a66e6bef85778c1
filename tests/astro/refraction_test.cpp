// Refraction through the model's own air (astro/refraction.h) against Bennett
// (1982) and Sæmundsson (1986), both for 1010 hPa and 10 °C.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "astro/refraction.h"
#include "atmosphere/constants.h"
#include "atmosphere/rayleigh.h"
#include "atmosphere/reference_data.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

constexpr double kArcmin = core::kDeg / 60.0;

TEST(Refraction, GroundDensityFromTheModelsOwnRayleighCoefficient) {
  // earth-advanced was built from N = 2.547e25 m⁻³: the inversion must give it back.
  const auto earth = atmosphere::load_preset("earth-advanced");
  EXPECT_NEAR(ground_number_density_m3(earth) / 2.547e25, 1.0, 1e-12);
  EXPECT_NEAR(ground_refractivity(earth, 550.0), atmosphere::standard_air_refractive_index(550.0) - 1.0, 1e-15);
  EXPECT_NEAR(ground_refractivity(earth, 550.0), 2.7783e-4, 1e-8);  // Edlén's standard air at 550 nm
  // earth-standard gives β_R directly (Bucholtz 1995, paper Table 1): 6.8 % more than
  // Edlén's standard air scatters, read as 6.8 % more air.
  const auto standard = atmosphere::load_preset("earth-standard");
  EXPECT_NEAR(ground_number_density_m3(standard) / 2.547e25, 1.068, 0.005);
  // Mars: 636 Pa at 210 K (NASA fact sheet, as the preset): N = p/(k T).
  const auto mars = atmosphere::load_preset("mars");
  EXPECT_NEAR(ground_number_density_m3(mars) / (636.0 / (atmosphere::kBoltzmann_J_per_K * 210.0)), 1.0, 1e-9);
  // CO2's refractivity 4.5019e-4 at 2.6868e25 m⁻³ (paper Table 1), scaled to Mars' density.
  EXPECT_NEAR(ground_refractivity(mars, 550.0),
              4.5019e-4 * 636.0 / (atmosphere::kBoltzmann_J_per_K * 210.0) / 2.6868e25, 3e-9);
}

TEST(Refraction, EarthAgainstBennettAndSaemundsson) {
  const auto loaded = atmosphere::load_preset("earth-advanced");
  // The model's own air (isothermal: exponential with H = 8.0 km) and the same ground
  // refractivity through the U.S. Standard Atmosphere 1976's density, whose temperature
  // lapse makes the density fall more slowly near the ground (H ≈ 10 km).
  const Refraction model = Refraction::for_atmosphere(loaded);
  const Refraction us1976(loaded.model.ground_radius_m, loaded.model.top_radius_m,
                          atmosphere::us_standard_1976_profile("air", nullptr), ground_refractivity(loaded));
  // The model's ground is standard air (15 °C, 1013.25 hPa): its refractivity is 1.4 %
  // below the formulas' 10 °C, 1010 hPa; above 10° R scales with it.
  const double conditions = (1013.25 / 1010.0) * (283.15 / 288.15);
  struct Case {
    double altitude_deg, tolerance_arcmin;
  };
  // Above 5° both profiles agree with the formulas within the formulas' own accuracy
  // (Bennett: 0.07′ over 0–90°); their difference is the density gradient near the ground.
  for (const Refraction* r : {&model, &us1976})
    for (const Case c : {Case{5.0, 0.5}, Case{10.0, 0.15}, Case{45.0, 0.07}}) {
      SCOPED_TRACE(c.altitude_deg);
      const double value = r->integral_rad(c.altitude_deg * core::kDeg);
      const double bennett = bennett_refraction_deg(c.altitude_deg) * core::kDeg * conditions;
      EXPECT_NEAR(value / kArcmin, bennett / kArcmin, c.tolerance_arcmin);
      // Sæmundsson takes the true altitude: h_true = h_app − R.
      const double true_deg = c.altitude_deg - value / core::kDeg;
      const double saemundsson = saemundsson_refraction_deg(true_deg) * core::kDeg * conditions;
      EXPECT_NEAR(value / kArcmin, saemundsson / kArcmin, c.tolerance_arcmin + 0.05);
    }
  // The horizon (Bennett: 34.5′ = 0.575°, 34.0′ at the model's conditions): the lapse-rate
  // atmosphere within 1.5′; the model's isothermal air lifts 10 % more (0.62°).
  EXPECT_NEAR(us1976.integral_rad(0.0) / kArcmin, bennett_refraction_deg(0.0) * 60.0 * conditions, 1.5);
  EXPECT_NEAR(model.integral_rad(0.0) / core::kDeg, 0.575, 0.1 * 0.575);
  EXPECT_GT(model.integral_rad(0.0), us1976.integral_rad(0.0));
  // The table follows the integral, and lifting an object inverts it.
  for (double h : {0.0, 0.3, 2.0, 7.0, 30.0, 89.0}) {
    EXPECT_NEAR(model.at_apparent_rad(h * core::kDeg), model.integral_rad(h * core::kDeg), 0.005 * kArcmin) << h;
    const double true_alt = h * core::kDeg - model.integral_rad(h * core::kDeg);
    EXPECT_NEAR(model.apparent_from_true_rad(true_alt), h * core::kDeg, 0.01 * kArcmin) << h;
  }
  EXPECT_NEAR(model.integral_rad(0.5 * core::kPi), 0.0, 1e-9);
  // The solver inverts the table itself to rounding, near the horizon too
  // (where R, linear in √h between table points, is steepest).
  for (double h : {0.0, 1e-9, 1e-6, 1e-4, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 45.0, 89.9}) {
    const double apparent = h * core::kDeg;
    const double true_alt = apparent - model.at_apparent_rad(apparent);
    EXPECT_NEAR(model.apparent_from_true_rad(true_alt), apparent, 1e-14) << h;
  }
  // Below the apparent horizon the lift stays R(0): continuous, never NaN.
  EXPECT_NEAR(model.apparent_from_true_rad(-2.0 * core::kDeg), -2.0 * core::kDeg + model.at_apparent_rad(0.0), 1e-12);
}

TEST(Refraction, MarsIsTiny) {
  const Refraction mars = Refraction::for_atmosphere(atmosphere::load_preset("mars"));
  // n − 1 = 3.7e-6 and H = 11 km: R(0) ≈ (n−1) √(π R/(2H)) ≈ 3.7e-6 · 22 ≈ 17″.
  const double horizon_arcsec = mars.integral_rad(0.0) / core::kDeg * 3600.0;
  EXPECT_GT(horizon_arcsec, 10.0);
  EXPECT_LT(horizon_arcsec, 30.0);
  EXPECT_LT(mars.integral_rad(45.0 * core::kDeg) / core::kDeg * 3600.0, 1.0);
}

TEST(Refraction, ClosedFormOfAnExponentialAtmosphere) {
  // For n − 1 = ε e^(−h/H) with ε ≪ 1 and H ≪ R, the horizontal refraction tends to
  // ε √(π R / (2 H)) (to first order in ε, tan z ≈ √(R/2h) near the ground:
  // R ≈ ∫ (ε/H) e^(−h/H) √(R/2h) dh): the quadrature must find it.
  const double epsilon = 1e-6, radius = 6.371e6, height = 8000.0;
  const Refraction r(radius, radius + 150000.0, atmosphere::DensityProfile::exponential(height), epsilon);
  EXPECT_NEAR(r.integral_rad(0.0) / (epsilon * std::sqrt(core::kPi * radius / (2.0 * height))), 1.0, 0.002);
  // Far from the horizon, (n₀ − 1) tan z (1 − (H/R) sec² z) (the flat-Earth limit and its first
  // curvature term, Green 1985 §4.3's expansion): at 45°, 1 − 2H/R.
  EXPECT_NEAR(r.integral_rad(45.0 * core::kDeg) / epsilon, 1.0 - 2.0 * height / radius, 2e-4);
}

TEST(Refraction, TheClosedFormInversionIsTheRootOfTheTablesOwnFunction) {
  // apparent_from_true_rad solves h − at_apparent_rad(h) = h_true on the
  // table's segment in closed form: it must be that root, found here by 200
  // bisections of the same function, to a few ulps of π/2 — from below the
  // horizon (where a star still shows from altitude) to the zenith, on Earth
  // from 2 m and from an aircraft's 10 km, on Mars, and through air
  // of 3.6 times Earth's refractivity (just short of ducting: ε R/H = 0.8).
  const auto earth = atmosphere::load_preset("earth-advanced");
  const auto mars = atmosphere::load_preset("mars");
  const Refraction cases[] = {Refraction::for_atmosphere(earth, 550.0, 2.0),
                              Refraction::for_atmosphere(earth, 550.0, 10000.0), Refraction::for_atmosphere(mars),
                              Refraction(6.371e6, 6.471e6, atmosphere::DensityProfile::exponential(8000.0), 1e-3)};
  for (const Refraction& r : cases) {
    const double r0 = r.at_apparent_rad(0.0);
    double worst = 0.0;
    for (int k = 0; k <= 20000; ++k) {
      // Dense near the horizon (the refraction's curvature), every 0.01° above.
      const double h_true = k < 10000 ? -2.0 * r0 + 4.0 * r0 * k / 10000.0 : 2.0 * r0 + (k - 10000) * 0.01 * core::kDeg;
      if (h_true > 0.5 * core::kPi) break;
      const double got = r.apparent_from_true_rad(h_true);
      double want = h_true + r0;  // below −R(0): h + R(0)
      if (h_true > -r0) {
        double lo = std::max(0.0, h_true), hi = std::min(0.5 * core::kPi, h_true + r0);
        for (int i = 0; i < 200; ++i) {
          const double mid = 0.5 * (lo + hi);
          (mid - r.at_apparent_rad(mid) - h_true < 0.0 ? lo : hi) = mid;
        }
        want = 0.5 * (lo + hi);
      }
      worst = std::max(worst, std::abs(got - want));
      ASSERT_GE(got, h_true) << "refraction lifts: " << h_true;
    }
    EXPECT_LT(worst, 1e-14) << "ground refractivity " << r.ground_refractivity();
  }
}

TEST(Refraction, ADuctIsWhereNrStopsGrowingWithHeight) {
  // n r = (1 + ε e^(−h/H)) (R + h) grows with h while ε e^(−h/H) ((R + h)/H − 1) < 1: in an exponential
  // atmosphere a duct reaches from the ground up to the root h* of ε e^(−h/H) ((R + h)/H − 1) = 1.
  const double radius = 6.371e6, height = 8000.0;
  const auto profile = atmosphere::DensityProfile::exponential(height);
  const auto duct = [&](double epsilon, double observer_m) {
    return ducting_altitude_m(radius, radius + 150000.0, profile, epsilon, observer_m);
  };
  EXPECT_FALSE(duct(2.9e-4, 0.0));  // the Earth's air: ε (R/H − 1) = 0.23
  const double epsilon = 2e-3;      // 1.59 at the ground
  ASSERT_TRUE(duct(epsilon, 0.0));
  EXPECT_EQ(*duct(epsilon, 0.0), 0.0);
  double lo = 0.0, hi = 20000.0;  // h* by bisection
  while (hi - lo > 1e-3) {
    const double mid = 0.5 * (lo + hi);
    (epsilon * std::exp(-mid / height) * ((radius + mid) / height - 1.0) > 1.0 ? lo : hi) = mid;
  }
  const double top_m = lo;
  EXPECT_NEAR(top_m, height * std::log(epsilon * (radius / height - 1.0)), 50.0);  // ~3.7 km
  ASSERT_TRUE(duct(epsilon, top_m - 10.0));
  EXPECT_EQ(*duct(epsilon, top_m - 10.0), top_m - 10.0);  // inside it, at the observer
  EXPECT_FALSE(duct(epsilon, top_m + 10.0));              // above it, rays escape
  try {
    Refraction(radius, radius + 150000.0, profile, epsilon);
    ADD_FAILURE() << "a duct at the observer was not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("trapped 0.00 km up"), std::string::npos) << e.what();
  }
}

TEST(Refraction, BadInputIsRefused) {
  const auto profile = atmosphere::DensityProfile::exponential(8000.0);
  EXPECT_THROW(Refraction(6.371e6, 6.471e6, profile, -1e-4), std::invalid_argument);
  EXPECT_THROW(Refraction(6.371e6, 6.471e6, profile, 2.9e-4, 200000.0), std::invalid_argument);
  // A gas dense enough to trap horizontal rays (ducting).
  EXPECT_THROW(Refraction(6.371e6, 6.471e6, atmosphere::DensityProfile::exponential(100.0), 0.05),
               std::invalid_argument);
}

}  // namespace
}  // namespace zenith::astro
