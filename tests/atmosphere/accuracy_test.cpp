// Table-based radiance against the reference solver, energy conservation and
// horizon continuity. The reference values are fixtures made by
// scripts/make-reference-fixtures (each CSV's first line is its command).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <fstream>
#include <sstream>

#include "atmosphere/constants.h"
#include "atmosphere/sky_sampling.h"
#include "tests/atmosphere/lut_fixture.h"

namespace zenith::atmosphere::lut {
namespace {

struct FixtureRow {
  ViewDirection direction;
  std::vector<double> radiance, standard_error;
};

struct Fixture {
  double altitude_m = 0.0, sun_zenith_deg = 0.0;
  std::vector<FixtureRow> rows;
};

/// Reads tests/data/reference_NAME.csv and the geometry from its command line.
Fixture read_fixture(const std::string& name, std::size_t channels) {
  const std::string path = std::string(ZENITH_SOURCE_DIR) + "/tests/data/reference_" + name + ".csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("missing fixture " + path + " (run scripts/make-reference-fixtures)");
  Fixture f;
  std::string line;
  std::getline(in, line);  // the command
  auto arg = [&](const std::string& flag) {
    const auto p = line.find(flag + " ");
    return std::stod(line.substr(p + flag.size() + 1));
  };
  f.altitude_m = arg("--altitude-m");
  f.sun_zenith_deg = arg("--sun-zenith-deg");
  std::getline(in, line);  // CSV header
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    FixtureRow r;
    s >> r.direction.zenith_deg >> r.direction.azimuth_deg;
    std::vector<double> values;
    double v;
    while (s >> v) values.push_back(v);
    // Columns: L_rel (n), L_spectral (n), Y, se_rel (n).
    r.radiance.assign(values.begin(), values.begin() + long(channels));
    r.standard_error.assign(values.end() - long(channels), values.end());
    f.rows.push_back(r);
  }
  return f;
}

struct Agreement {
  double rms_relative = 0.0, max_relative = 0.0;
  std::string worst;
};

/// Relative error of the tables against the reference at every direction and
/// wavelength, discounting the reference's own Monte Carlo noise (2σ).
Agreement compare(const std::string& preset, const std::string& fixture_name) {
  const SmallTables& t = SmallTables::get(preset);
  const Fixture f = read_fixture(fixture_name, t.model.wavelength_count());
  SkyGeometry g;
  g.altitude_m = f.altitude_m;
  g.sun_zenith_deg = f.sun_zenith_deg;
  std::vector<ViewDirection> dirs;
  for (const auto& r : f.rows) dirs.push_back(r.direction);
  const auto lut = sample_radiance(*t.queries, g, dirs);
  Agreement a;
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < f.rows.size(); ++i)
    for (std::size_t c = 0; c < t.model.wavelength_count(); ++c) {
      const double ref = f.rows[i].radiance[c], se = f.rows[i].standard_error[c];
      const double err = std::max(0.0, std::abs(lut[i].radiance[c] - ref) - 2.0 * se) / ref;
      sum += err * err;
      ++n;
      if (err > a.max_relative)
        a.worst = "view (" + std::to_string(f.rows[i].direction.zenith_deg) + ", " +
                  std::to_string(f.rows[i].direction.azimuth_deg) + ") at " +
                  std::to_string(t.model.wavelengths_nm[c]) + " nm: tables " + std::to_string(lut[i].radiance[c]) +
                  ", reference " + std::to_string(ref) + " +- " + std::to_string(se);
      a.max_relative = std::max(a.max_relative, err);
    }
  a.rms_relative = std::sqrt(sum / n);
  std::cout << fixture_name << ": RMS relative error " << a.rms_relative << ", max " << a.max_relative << " ("
            << a.worst << ")\n";
  return a;
}

// Bounds for the small test tables (TableSizes::small(): 8 radii, 32 view and
// 32 sun angles, 8 scattering angles; 4 orders; 8 Gauss-Legendre nodes), set at
// about 1.3x the errors measured when they were introduced (printed by each
// test). Relative error per direction and wavelength, after discounting twice
// the reference's standard error. The twilight and limb cases are the hardest
// for tables this small (the Earth's shadow and the limb are a few texels
// wide); bench/lut_accuracy_bench reports the same comparison for larger tables.
struct AccuracyCase {
  const char* name;     ///< test name
  const char* preset;
  const char* fixture;  ///< tests/data/reference_<fixture>.csv
  double max_rms, max_max;
};

void PrintTo(const AccuracyCase& c, std::ostream* os) { *os << c.name; }

class AccuracyVsReference : public ::testing::TestWithParam<AccuracyCase> {};

TEST_P(AccuracyVsReference, WithinStatedBounds) {
  const AccuracyCase& c = GetParam();
  const Agreement a = compare(c.preset, c.fixture);
  EXPECT_LT(a.rms_relative, c.max_rms);
  EXPECT_LT(a.max_relative, c.max_max);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AccuracyVsReference,
    ::testing::Values(AccuracyCase{"EarthNoon", "earth-advanced", "earth-advanced_noon", 0.09, 0.20},
                      AccuracyCase{"EarthLowSun", "earth-advanced", "earth-advanced_low_sun", 0.12, 0.28},
                      AccuracyCase{"EarthTwilight", "earth-advanced", "earth-advanced_twilight", 0.30, 0.95},
                      AccuracyCase{"EarthLimbFromOrbit", "earth-advanced", "earth-advanced_orbit_limb", 0.35, 0.80},
                      AccuracyCase{"MarsNoon", "mars", "mars_noon", 0.10, 0.22},
                      AccuracyCase{"MarsLowSun", "mars", "mars_low_sun", 0.11, 0.30},
                      AccuracyCase{"MarsTwilight", "mars", "mars_twilight", 0.15, 0.30},
                      AccuracyCase{"MarsLimbFromOrbit", "mars", "mars_orbit_limb", 0.16, 0.35}),
    [](const auto& test_info) { return std::string(test_info.param.name); });

TEST(Energy, ConservativeAtmosphereOverAWhiteGroundCreatesNoLight) {
  // No absorption anywhere, albedo 1: the light leaving the top can at most
  // equal the light entering (all of it, as the number of orders grows).
  AtmosphereModel m = load_preset("earth-standard").model;
  m.mie_extinction_m1 = m.mie_scattering_m1;
  m.absorbers.clear();
  m.ground_albedo = Spectrum(m.wavelength_count(), 1.0);
  PrecomputeOptions o = SmallTables::small_options();
  o.max_orders = 6;
  const LookupTables tables = precompute_tables_cpu(m, o);
  const TableQueries q(m, tables);
  const double mu_s = std::cos(40.0 * kPi / 180.0);
  const Vec3 sun = direction_from_angles(40.0 * kPi / 180.0, 0.0);
  const Vec3 top{0.0, 0.0, m.top_radius_m - 1.0};
  // Upward flux through the top: ∫ over downward directions of L |cos θ| dω.
  const int n_theta = 48, n_phi = 48;
  Spectrum flux(m.wavelength_count(), 0.0);
  for (int i = 0; i < n_theta; ++i) {
    const double theta = kPi / 2 + (i + 0.5) * (kPi / 2) / n_theta;
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / n_phi;
      const Spectrum l = q.sky_radiance(top, direction_from_angles(theta, phi), sun);
      const double w = std::abs(std::cos(theta)) * std::sin(theta) * (kPi / 2 / n_theta) * (2 * kPi / n_phi);
      for (std::size_t c = 0; c < flux.size(); ++c) flux[c] += l[c] * w;
    }
  }
  for (std::size_t c = 0; c < flux.size(); ++c) {
    EXPECT_LT(flux[c], mu_s * 1.02) << "light created at " << m.wavelengths_nm[c] << " nm";
    EXPECT_GT(flux[c], mu_s * 0.75) << "light lost at " << m.wavelengths_nm[c] << " nm";
  }
}

TEST(HorizonContinuity, NoArtifactAtTheHorizonForAnyPreset) {
  // Sky radiance approaching the horizon from above, and the view just below it
  // from altitude: the step into the horizon is no larger than the variation
  // next to it (a table seam or interpolation across the horizon would be).
  for (const std::string preset : {"earth-standard", "earth-advanced", "mars", "titan", "halcyon"}) {
    const SmallTables& t = SmallTables::get(preset);
    for (double altitude : {1.0, 10e3}) {
      for (double sun_zenith : {30.0, 85.0}) {
        const double r = t.model.ground_radius_m + altitude;
        const double horizon_deg = 90.0 + std::acos(t.model.ground_radius_m / r) * 180.0 / kPi;
        const Vec3 observer{0.0, 0.0, r};
        const Vec3 sun = direction_from_angles(sun_zenith * kPi / 180.0, 0.0);
        std::vector<Spectrum> values;
        const double step = 0.05;
        for (int k = 40; k >= 1; --k)  // from 2° above the horizon to 0.05° above it
          values.push_back(t.queries->sky_radiance(observer, direction_from_angles((horizon_deg - k * step) * kPi / 180.0, kPi / 2), sun));
        values.push_back(t.queries->sky_radiance(observer, direction_from_angles((horizon_deg - 1e-6 * 180.0 / kPi) * kPi / 180.0, kPi / 2), sun));
        for (std::size_t c = 0; c < t.model.wavelength_count(); ++c) {
          double max_step = 0.0;
          for (std::size_t k = 1; k + 3 < values.size(); ++k)
            max_step = std::max(max_step, std::abs(values[k][c] - values[k - 1][c]));
          const std::size_t last = values.size() - 1;
          const double final_steps = std::max(std::abs(values[last][c] - values[last - 1][c]),
                                              std::abs(values[last - 1][c] - values[last - 2][c]));
          for (const auto& v : values) EXPECT_TRUE(std::isfinite(v[c]) && v[c] >= 0.0);
          EXPECT_LE(final_steps, 3.0 * max_step + 1e-3 * values[last][c])
              << preset << " altitude " << altitude << " sun " << sun_zenith << " channel " << c;
        }
      }
    }
  }
}

}  // namespace
}  // namespace zenith::atmosphere::lut
