// Star, Moon and night-sky photometry (astro/v_band.h, star_photometry.h,
// moon_photometry.h, night_sky_floor.h, light_pollution.h)
// against published figures.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "astro/light_pollution.h"
#include "astro/moon_photometry.h"
#include "astro/night_sky_floor.h"
#include "astro/star_photometry.h"
#include "astro/v_band.h"
#include "atmosphere/parameters.h"
#include "atmosphere/photometry.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

TEST(VBand, TheSunsMagnitudeFromTheKuruczSpectrum) {
  // Willmer 2018 (ApJS 236, 47, Table 3): the Sun's apparent V = −26.76.
  const double sun = v_band_mean([](double l) { return atmosphere::solar_irradiance_W_m2_nm(l); });
  EXPECT_NEAR(v_magnitude(sun), -26.76, 0.05);
  EXPECT_NEAR(v_irradiance_W_m2_nm(v_magnitude(1.23e-9)), 1.23e-9, 1e-20);
  // 22 mag/arcsec² is 1.7e-4 cd/m² for a sky of solar colour (the conversion
  // 10.8e4 · 10^(−0.4 μ) cd/m² of Garstang 1986 and the SQM literature gives 1.71e-4).
  const double radiance = v_radiance_W_m2_sr_nm(22.0);
  const double luminance =
      luminance_cd_m2([&](double l) { return radiance * atmosphere::solar_irradiance_W_m2_nm(l) / sun; });
  EXPECT_NEAR(luminance / 1.71e-4, 1.0, 0.1);
}

TEST(StarPhotometry, BallesterosTemperaturesAndFlux) {
  EXPECT_NEAR(ballesteros_temperature_K(0.65), 5778.0, 10.0);  // the Sun's colour → its temperature
  EXPECT_NEAR(ballesteros_temperature_K(0.0), 10125.0, 1.0);   // A0: 4600 (1/1.7 + 1/0.62)
  EXPECT_GT(ballesteros_temperature_K(-0.3), ballesteros_temperature_K(0.0));
  EXPECT_LT(ballesteros_temperature_K(1.5), 4000.0);
  // A star's spectrum reproduces its V, and a red star is redder.
  const std::vector<double> wavelengths = {680.0, 550.0, 440.0};
  const auto vega = star_irradiance_W_m2_nm(0.03, 0.0, wavelengths);
  EXPECT_NEAR(v_magnitude(v_band_mean([&](double l) {
                const double t = ballesteros_temperature_K(0.0);
                return vega[1] * planck_W_m2_sr_nm(l, t) / planck_W_m2_sr_nm(550.0, t);
              })),
              0.03, 1e-3);
  // Vega's measured f_λ at 550 nm is 3.44e-11 W m⁻² nm⁻¹ (Hayes 1985, as used by Bessell 1998): within 10 %.
  EXPECT_NEAR(vega[1] / 3.44e-11, 1.0, 0.1);
  const auto betelgeuse = star_irradiance_W_m2_nm(0.45, 1.5, wavelengths);
  EXPECT_GT(betelgeuse[0] / betelgeuse[2], 3.0 * vega[0] / vega[2]);
  // Five magnitudes are a factor of 100.
  const auto faint = star_irradiance_W_m2_nm(5.03, 0.0, wavelengths);
  EXPECT_NEAR(vega[1] / faint[1], 100.0, 1e-9);
}

TEST(MoonPhotometry, FullAndQuarterMoonAndTheDisc) {
  // Allen / Krisciunas & Schaefer 1991: full Moon V = −12.73 at 384 400 km; quarter (α = 90°) −10.39.
  EXPECT_NEAR(moon_v_magnitude(0.0, 384400.0), -12.73, 0.01);
  EXPECT_NEAR(moon_v_magnitude(0.5 * core::kPi, 384400.0), -12.73 + 0.026 * 90 + 4e-9 * std::pow(90.0, 4), 0.01);
  // The geometric albedo this implies: 0.12 (Allen's Astrophysical Quantities: 0.12).
  EXPECT_NEAR(lunar_geometric_albedo(550.0), 0.12, 0.01);
  EXPECT_GT(lunar_geometric_albedo(680.0), lunar_geometric_albedo(440.0));  // redder than the Sun
  // Sums f(μ₀, μ) over the disc seen along +z (a 400² grid of its projection, each cell's
  // area 4/n² of the unit disc), the sun at phase angle α in the x–z plane.
  auto over_disc = [](double alpha, const std::function<double(double, double)>& f) {
    const int n = 400;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = -1.0 + (i + 0.5) * 2.0 / n, y = -1.0 + (j + 0.5) * 2.0 / n;
        if (x * x + y * y >= 1.0) continue;
        const double mu = std::sqrt(1.0 - x * x - y * y);
        sum += f(x * std::sin(alpha) + mu * std::cos(alpha), mu) * (4.0 / (n * n));
      }
    return sum;
  };
  // Lommel–Seeliger's disc integral: its closed form against a quadrature of μ₀/(μ₀+μ)
  // (the projection's area element already carries the μ of dA·μ).
  for (double alpha_deg : {0.0, 30.0, 60.0, 90.0, 120.0, 150.0}) {
    SCOPED_TRACE(alpha_deg);
    const double a = alpha_deg * core::kDeg;
    const double sum = over_disc(a, [](double mu0, double mu) { return mu0 > 0.0 ? mu0 / (mu0 + mu) : 0.0; });
    EXPECT_NEAR(sum / (core::kPi / 2.0), lommel_seeliger_phase(a), 0.005);
  }
  // The disc's radiance, integrated over the disc, is the Moon's irradiance.
  MoonPlace moon;
  moon.distance_km = 384400.0;
  moon.phase_angle_rad = 60.0 * core::kDeg;
  moon.sun_distance_au = 1.0;
  const std::vector<double> wl = {550.0};
  const double e = moon_irradiance_W_m2_nm(moon, wl)[0];
  const double omega_per_unit_area = std::pow(kMoonRadius_km / moon.distance_km, 2.0);  // solid angle of the disc / π
  const double sum = over_disc(moon.phase_angle_rad, [&](double mu0, double mu) {
    return moon_disc_radiance(mu0, mu, moon.phase_angle_rad, 550.0) * omega_per_unit_area;
  });
  EXPECT_NEAR(sum / e, 1.0, 0.01);
}

TEST(NightSky, DarkZenithAndVanRhijn) {
  const auto earth = atmosphere::load_preset("earth-advanced");
  const NightSkyFloor floor(earth.model);
  EXPECT_NEAR(floor.zenith_v_mag_arcsec2(), 22.0, 1e-6);
  // About 0.2 mcd/m² at a dark zenith (22 mag/arcsec² ↔ 0.17 mcd/m² for a solar-colour sky; the
  // airglow's green line, near the eye's peak, adds some).
  EXPECT_GT(floor.zenith_luminance_cd_m2(), 0.15e-3);
  EXPECT_LT(floor.zenith_luminance_cd_m2(), 0.30e-3);
  // Van Rhijn: 1 at the zenith, 6.0 at the horizon for a layer at 90 km over 6371 km.
  EXPECT_DOUBLE_EQ(floor.van_rhijn(0.0), 1.0);
  EXPECT_NEAR(floor.van_rhijn(0.5 * core::kPi), 1.0 / std::sqrt(1.0 - std::pow(6371.0 / 6461.0, 2.0)), 1e-9);
  EXPECT_NEAR(floor.van_rhijn(0.5 * core::kPi), 6.0, 0.05);
  const auto zenith = floor.top_of_atmosphere_radiance(0.0);
  const auto horizon = floor.top_of_atmosphere_radiance(0.5 * core::kPi);
  for (std::size_t i = 0; i < zenith.size(); ++i) {
    EXPECT_GT(zenith[i], 0.0);
    EXPECT_GT(horizon[i], 2.0 * zenith[i]);  // the airglow dominates, times 6
  }
  // Green of the [O I] line: at 550 nm above the continuum's neighbours per nm.
  EXPECT_GT(zenith[1], zenith[2]);
  EXPECT_THROW(NightSkyFloor(earth.model, {25.0, 90000.0}), std::invalid_argument);
  // Brighter floors scale.
  EXPECT_NEAR(NightSkyFloor(earth.model, {21.0, 90000.0}).zenith_v_mag_arcsec2(), 21.0, 1e-6);
}

TEST(NightSky, LightPollutionInPhysicalUnits) {
  const auto earth = atmosphere::load_preset("earth-advanced");
  const LightPollution glow(earth.model, {2.0, 3000.0});
  const auto zenith = glow.radiance(0.0);
  // Its luminance is the given 2 mcd/m² (the sampled spectrum's luminance weights are coarse:
  // check through the gradient instead, and the spectrum's order).
  EXPECT_NEAR(glow.gradient(0.0, 1), 1.0, 1e-5);  // Pickering's X(90°) = 1 to 2e-6
  double last = 1.0;
  for (double z = 10.0; z <= 90.0; z += 10.0) {
    const double g = glow.gradient(z * core::kDeg, 1);
    EXPECT_GT(g, last);
    last = g;
  }
  EXPECT_GT(last, 3.0);
  EXPECT_LT(last, 8.0);
  EXPECT_GT(zenith[2], 0.0);  // scattered lamp light reaches the blue
  // Bortle 1 is the natural sky: nothing artificial; Bortle 9 is thousands of times brighter.
  const NightSkyFloor floor(earth.model);
  EXPECT_NEAR(bortle_artificial_mcd_m2(1, earth.model, floor.zenith_luminance_cd_m2()), 0.0, 0.05);
  const double b5 = bortle_artificial_mcd_m2(5, earth.model, floor.zenith_luminance_cd_m2());
  EXPECT_GT(b5, 0.5);
  EXPECT_LT(b5, 3.0);  // 20.0 mag/arcsec² ≈ 1.1 mcd/m²
  EXPECT_THROW(bortle_zenith_v_mag_arcsec2(10), std::invalid_argument);
  EXPECT_THROW(LightPollution(earth.model, {-1.0, 3000.0}), std::invalid_argument);
  EXPECT_THROW(LightPollution(earth.model, {1.0, 500.0}), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::astro
