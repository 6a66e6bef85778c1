// `zenith sample --eclipse-at`: the Sun and the Moon by date and place put
// into the reference solver and the tables (apps/sampling.h). At the point of
// greatest eclipse of 2017-08-21 in totality the zenith keeps ~1e-4 of its
// light and turns bluer (Dandekar & Turtle 1971, Appl. Opt. 10(6): ~1e-4 with
// the sun 40–50° up; ~11 000 K against ~9 000 K), by both methods: the
// reference solver in vector transfer, as the tables' shadow weights the
// light's polarization. And the reference solver's sky split by scattering
// order (--reference-orders).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "apps/sampling.h"
#include "astro/civil_time.h"
#include "astro/solar_eclipse.h"
#include "atmosphere/parameters.h"

namespace zenith::app {
namespace {

/// The CSV's first data row: radiance per unit solar irradiance at each wavelength.
std::vector<double> first_radiance_row(const std::string& csv, std::size_t wavelengths) {
  std::istringstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::vector<double> cells;
  std::istringstream cells_in(row);
  for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(std::stod(cell));
  return {cells.begin() + 2, cells.begin() + 2 + static_cast<std::ptrdiff_t>(wavelengths)};
}

TEST(SampleEclipse, AtTheGreatestEclipseOf2017TheZenithKeepsATenThousandthOfItsLightAndTurnsBluer) {
  const atmosphere::AtmosphereModel m = atmosphere::load_preset("earth-advanced").model;  // 680, 550, 440 nm
  const astro::Site site{36.9667, -87.6667, 150.0};
  const astro::SkyPositions sky(astro::AstroTime::from_utc(astro::UtcTime{2017, 8, 21, 18, 25, 30.0}), site);
  ASSERT_EQ(astro::solar_eclipse_view(sky).kind, astro::EclipseKind::total);
  SamplingRequest eclipsed;
  eclipsed.method = SamplingMethod::Reference;
  eclipsed.reference_samples = 400000;
  eclipsed.polarized = true;
  eclipsed.directions = {{0.0, 0.0}};
  place_sun_and_moon(sky, m, eclipsed);
  EXPECT_NEAR(90.0 - eclipsed.geometry.sun_zenith_deg, 64.0, 1.0);  // NASA: the sun 64° up there
  SamplingRequest uneclipsed = eclipsed;
  uneclipsed.occulter = {};
  uneclipsed.reference_samples = 4000;
  const std::vector<double> dark = first_radiance_row(sample_radiance_csv(m, eclipsed), 3);
  const std::vector<double> day = first_radiance_row(sample_radiance_csv(m, uneclipsed), 3);
  for (std::size_t i = 0; i < 3; ++i) {
    std::printf("%.0f nm: totality / daylight %.3g\n", m.wavelengths_nm[i], dark[i] / day[i]);
    EXPECT_GT(dark[i] / day[i], 1e-5) << m.wavelengths_nm[i];
    EXPECT_LT(dark[i] / day[i], 5e-4) << m.wavelengths_nm[i];
  }
  EXPECT_GT(dark[2] / day[2], 1.5 * dark[0] / day[0]) << "bluer: 440 nm keeps more of its daylight than 680 nm";

  // The tables with the Moon's shadow (--method lut): paper tables, no cache.
  SamplingRequest tables = eclipsed;
  tables.method = SamplingMethod::Tables;
  tables.tables.backend = render::PrecomputeBackend::Gpu;  // llvmpipe here: the paper tables in ~20 s, the CPU ~40 s
  tables.tables.use_cache = false;
  tables.tables.show_progress = false;
  // The paper's sizes: the small tables are too coarse for the light in the umbra (docs/validation.md).
  tables.tables.options.sizes = atmosphere::lut::TableSizes{};
  const std::vector<double> from_tables = first_radiance_row(sample_radiance_csv(m, tables), 3);
  for (std::size_t i = 0; i < 3; ++i) {
    std::printf("%.0f nm: tables / reference in totality %.3f\n", m.wavelengths_nm[i], from_tables[i] / dark[i]);
    // validate eclipse's tolerance (docs/validation.md, "Eclipses"): 25 % plus the reference's noise here (~10 %).
    EXPECT_NEAR(from_tables[i] / dark[i], 1.0, 0.25 + 3.0 * 0.1) << m.wavelengths_nm[i];
  }
}

TEST(SampleOrders, TheReferenceSkySplitByOrderAddsUpToTheWholeSky) {
  // --reference-orders: the light scattered once and twice, and three times or more, make up the whole sky
  // within the three estimates' noise (a daylit zenith, the sun 60° down from it, 200 000 paths each:
  // relative standard errors ≲ 1 %); the single scattering alone is well under the whole.
  const atmosphere::AtmosphereModel m = atmosphere::load_preset("earth-advanced").model;
  SamplingRequest all;
  all.method = SamplingMethod::Reference;
  all.reference_samples = 200000;
  all.directions = {{0.0, 0.0}};
  all.geometry.sun_zenith_deg = 60.0;
  SamplingRequest low = all, high = all, single = all;
  low.reference_orders = {1, 2};
  high.reference_orders = {3, 1000};
  single.reference_orders = {1, 1};
  single.reference_samples = 20000;
  const std::vector<double> whole = first_radiance_row(sample_radiance_csv(m, all), 3);
  const std::vector<double> first_two = first_radiance_row(sample_radiance_csv(m, low), 3);
  const std::vector<double> rest = first_radiance_row(sample_radiance_csv(m, high), 3);
  const std::vector<double> once = first_radiance_row(sample_radiance_csv(m, single), 3);
  for (std::size_t i = 0; i < 3; ++i) {
    std::printf("%.0f nm: orders 1-2 %.3e + 3- %.3e against all %.3e; order 1 %.3e\n", m.wavelengths_nm[i],
                first_two[i], rest[i], whole[i], once[i]);
    EXPECT_NEAR((first_two[i] + rest[i]) / whole[i], 1.0, 0.04) << m.wavelengths_nm[i] << " nm";
    EXPECT_GT(rest[i], 0.02 * whole[i]) << m.wavelengths_nm[i] << " nm";
    EXPECT_LT(once[i], 0.95 * whole[i]) << m.wavelengths_nm[i] << " nm";
  }
}

}  // namespace
}  // namespace zenith::app
