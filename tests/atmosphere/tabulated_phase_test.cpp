#include "atmosphere/tabulated_phase.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "atmosphere/aeronet_phase_file.h"
#include "atmosphere/parameters.h"
#include "atmosphere/phase_functions.h"
#include "atmosphere/reference/random.h"
#include "atmosphere/reference_data.h"
#include "core/json_reader.h"
#include "tests/atmosphere/test_util.h"

namespace zenith::atmosphere {
namespace {

using test::integrate_over_sphere_in_sin_half_angle;

constexpr double kDeg = kPi / 180.0;

/// `scale` × HG(θ; g) at every `step_deg` from 0 to 180.
TabulatedPhase::Column henyey_greenstein_column(double wavelength_nm, double g, double scale,
                                                const std::vector<double>& angles_deg) {
  TabulatedPhase::Column c{wavelength_nm, {}};
  for (double a : angles_deg) c.values.push_back(scale * henyey_greenstein(std::cos(a * kDeg), g));
  return c;
}

std::vector<double> angles_every(double step_deg) {
  std::vector<double> a;
  for (double x = 0.0; x < 180.0 - 1e-9; x += step_deg) a.push_back(x);
  a.push_back(180.0);
  return a;
}

TEST(TabulatedPhase, AHenyeyGreensteinTableGivesTheHenyeyGreensteinPhase) {
  // HG(g = 0.7) every degree, 3 times too large: normalised back, within 1 %
  // of the closed form from the forward peak (P(0) = 18.9 sr^-1 · 4π) to the back.
  const std::vector<double> angles = angles_every(1.0);
  const TabulatedPhase table(angles, {henyey_greenstein_column(550.0, 0.7, 3.0, angles)}, {550.0});
  EXPECT_NEAR(table.integral_as_given(0), 3.0, 3e-3);
  for (double theta : {0.0, 0.3, 1.0, 2.5, 5.0, 10.0, 30.0, 60.0, 90.0, 135.0, 180.0}) {
    const double c = std::cos(theta * kDeg);
    EXPECT_NEAR(table(0, c) / henyey_greenstein(c, 0.7), 1.0, 1e-2) << theta;
  }
  // Exactly normalised (the interpolant's integral, not the closed form's), and
  // its mean cosine is HG's g.
  EXPECT_NEAR(integrate_over_sphere_in_sin_half_angle([&](double c) { return table(0, c); }), 1.0, 1e-12);
  EXPECT_NEAR(table.asymmetry(0), 0.7, 2e-3);
  EXPECT_NEAR(integrate_over_sphere_in_sin_half_angle([&](double c) { return c * table(0, c); }), table.asymmetry(0),
              1e-12);
}

TEST(TabulatedPhase, IsLinearInWavelengthBetweenColumnsAndHeldOutside) {
  const std::vector<double> angles = angles_every(2.0);
  const TabulatedPhase table(
      angles, {henyey_greenstein_column(800.0, 0.8, 1.0, angles), henyey_greenstein_column(400.0, 0.5, 1.0, angles)},
      {300.0, 400.0, 600.0, 900.0});
  for (double theta : {0.0, 20.0, 90.0, 170.0}) {
    const double c = std::cos(theta * kDeg);
    const double hg5 = henyey_greenstein(c, 0.5), hg8 = henyey_greenstein(c, 0.8);
    EXPECT_NEAR(table(0, c) / hg5, 1.0, 1e-2) << theta;  // below the columns: the nearest one
    EXPECT_NEAR(table(1, c) / hg5, 1.0, 1e-2) << theta;
    EXPECT_NEAR(table(2, c) / (0.5 * (hg5 + hg8)), 1.0, 1e-2) << theta;
    EXPECT_NEAR(table(3, c) / hg8, 1.0, 1e-2) << theta;
  }
  EXPECT_NEAR(table.asymmetry(2), 0.65, 3e-3);
}

TEST(TabulatedPhase, ItsProposalIsADensityAndWeightsReproduceItsMoments) {
  const std::vector<double> angles = angles_every(1.0);
  const TabulatedPhase table(angles, {henyey_greenstein_column(550.0, 0.85, 1.0, angles)}, {550.0});
  EXPECT_NEAR(integrate_over_sphere_in_sin_half_angle([&](double c) { return table.proposal_pdf(0, c); }), 1.0, 1e-12);
  // E_q[P/q] = 1 and E_q[(P/q) cos θ] = g, within 4 standard errors.
  reference::Pcg32 rng(7, 1);
  const int n = 200000;
  double sum[2] = {}, sum_sq[2] = {};
  for (int k = 0; k < n; ++k) {
    const double c = table.sample_cosine(0, rng.uniform(), rng.uniform());
    const double w = table(0, c) / table.proposal_pdf(0, c);
    for (int f = 0; f < 2; ++f) {
      const double x = f == 0 ? w : w * c;
      sum[f] += x;
      sum_sq[f] += x * x;
    }
    ASSERT_LT(w, 1.5) << c;  // the proposal follows P segment by segment
  }
  const double expected[2] = {1.0, table.asymmetry(0)};
  for (int f = 0; f < 2; ++f) {
    const double mean = sum[f] / n, error = std::sqrt((sum_sq[f] / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, expected[f], 4.0 * error + 1e-12) << f;
  }
}

TEST(TabulatedPhase, RefusesTablesItCannotUse) {
  const std::vector<double> ok = {0.0, 90.0, 180.0};
  const TabulatedPhase::Column column{550.0, {4.0, 1.0, 1.0}};
  EXPECT_THROW(TabulatedPhase({0.0, 90.0}, {{550.0, {4.0, 1.0}}}, {550.0}), std::invalid_argument);
  EXPECT_THROW(TabulatedPhase({0.0, 90.0, 90.0, 180.0}, {{550.0, {4.0, 1.0, 1.0, 1.0}}}, {550.0}),
               std::invalid_argument);
  EXPECT_THROW(TabulatedPhase(ok, {{550.0, {4.0, -1.0, 1.0}}}, {550.0}), std::invalid_argument);
  EXPECT_THROW(TabulatedPhase(ok, {{550.0, {4.0, 1.0}}}, {550.0}), std::invalid_argument);
  EXPECT_THROW(TabulatedPhase(ok, {column, column}, {550.0}), std::invalid_argument);
  EXPECT_THROW(TabulatedPhase(ok, {}, {550.0}), std::invalid_argument);
}

// ------------------------------------------------------------ AERONET's files

const std::filesystem::path kEgbert =
    std::filesystem::path(ZENITH_SOURCE_DIR) / "tests/data/aeronet/egbert_2013-05-27.pfn";

TEST(AeronetPhaseFile, ReadsEgbertsRetrievalsOfTheMeasuredSkysDay) {
  const AeronetPhaseFunctions a = read_aeronet_phase_functions(kEgbert);
  EXPECT_EQ(a.site, "Egbert");
  EXPECT_EQ(a.level, "Level 1.5 Almucantar Retrievals, Version 2");
  ASSERT_EQ(a.wavelengths_nm, (std::vector<double>{442.0, 674.0, 871.0, 1020.0}));
  ASSERT_EQ(a.angles_deg.size(), 83u);
  EXPECT_EQ(a.angles_deg[1], 1.71);
  EXPECT_EQ(a.angles_deg.back(), 180.0);
  ASSERT_EQ(a.retrievals.size(), 5u);
  EXPECT_EQ(a.retrievals.front().time, "11:19:04");
  EXPECT_EQ(a.retrievals.back().time, "14:18:59");
  // Values as written: the first retrieval's forward value at 442 nm, the last one's backward value at 1020 nm.
  EXPECT_EQ(a.retrievals.front().values[0][0], 73.345490);
  EXPECT_EQ(a.retrievals.front().diagnostics.at("tau440(measured)"), "0.113925");
  EXPECT_EQ(a.retrievals.back().diagnostics.at("alpha440-870"), "0.862035");
  const std::vector<TabulatedPhase::Column> mean = a.mean_columns();
  EXPECT_NEAR(mean[0].values[0], (73.345490 + 73.065620 + 72.037720 + 85.011780 + 78.302930) / 5.0, 1e-9);

  // AERONET's scale is ½ ∫ P sin θ dθ = 1, i.e. ∫ P dω = 4π; the asymmetry that
  // day (442 nm) against the trapezoid rule on the file's own angles.
  const TabulatedPhase table(a.angles_deg, mean, {442.0, 674.0});
  double g_trapezoid = 0.0, norm_trapezoid = 0.0;
  for (std::size_t j = 0; j + 1 < a.angles_deg.size(); ++j) {
    const double t0 = a.angles_deg[j] * kDeg, t1 = a.angles_deg[j + 1] * kDeg;
    const double f0 = mean[0].values[j] * std::sin(t0), f1 = mean[0].values[j + 1] * std::sin(t1);
    norm_trapezoid += 0.5 * (f0 + f1) * (t1 - t0);
    g_trapezoid += 0.5 * (f0 * std::cos(t0) + f1 * std::cos(t1)) * (t1 - t0);
  }
  EXPECT_NEAR(table.integral_as_given(0) / (4.0 * kPi), 0.5 * norm_trapezoid, 0.01);
  EXPECT_NEAR(table.asymmetry(0), g_trapezoid / norm_trapezoid, 0.01);
  EXPECT_GT(table.asymmetry(0), 0.6);
  EXPECT_LT(table.asymmetry(0), 0.7);

  // Against the Cornette–Shanks phase (g 0.7) of the day's atmosphere as
  // Bruneton inverted it (docs/physics.md, docs/validation.md): 3.4× at 0°,
  // 0.55× at 10–15°, 1.3–2× at 42–90°.
  const auto ratio = [&](double theta_deg) {
    const double c = std::cos(theta_deg * kDeg);
    return table(0, c) / cornette_shanks(c, 0.7);
  };
  EXPECT_NEAR(ratio(0.0), 3.4, 0.05);
  for (double theta : {10.63, 12.86, 15.10}) EXPECT_NEAR(ratio(theta), 0.555, 0.025) << theta;
  EXPECT_NEAR(ratio(41.93), 1.33, 0.03);
  EXPECT_NEAR(ratio(75.47), 1.97, 0.04);
  EXPECT_NEAR(ratio(90.0), 1.88, 0.04);
}

TEST(AeronetPhaseFile, TheMeasuredDaysAtmospheresHoldWhatItsFileAndTheTablesGive) {
  // validate/data's variants of the Cornell day (docs/validation.md, "Better
  // physics"), from their sources: the aerosol optical depth of the AERONET
  // retrievals (means of tau440 and alpha440-870; extinction beta lambda^-alpha / H_M,
  // beta = tau440 0.44^alpha, H_M 1.2 km, albedo 0.8), their phase function, and
  // ozone sigma(233 K) times the U.S. Standard Atmosphere's peak density.
  const AeronetPhaseFunctions a = read_aeronet_phase_functions(kEgbert);
  double tau440 = 0.0, alpha = 0.0;
  for (const auto& r : a.retrievals) {
    tau440 += std::stod(r.diagnostics.at("tau440(measured)"));
    alpha += std::stod(r.diagnostics.at("alpha440-870"));
  }
  tau440 /= static_cast<double>(a.retrievals.size());
  alpha /= static_cast<double>(a.retrievals.size());
  const double beta = tau440 * std::pow(0.44, alpha);
  EXPECT_NEAR(beta, 0.05295, 1e-5);
  const std::filesystem::path data = std::filesystem::path(ZENITH_SOURCE_DIR) / "validate/data";
  double o3_peak_m3 = 0.0;
  us_standard_1976_profile("o3", &o3_peak_m3);
  for (const char* name : {"aeronet_aod", "aeronet", "aeronet_ozone", "ozone"}) {
    SCOPED_TRACE(name);
    const AtmosphereModel m =
        load_atmosphere_file((data / (std::string("cornell_2013-05-27_") + name + ".json")).string()).model;
    const bool aod = std::string(name) != "ozone", phase = aod && std::string(name) != "aeronet_aod";
    const bool ozone = std::string(name).find("ozone") != std::string::npos;
    const TabulatedPhase measured(a.angles_deg, a.mean_columns(), m.wavelengths_nm);
    for (std::size_t i = 0; i < m.wavelength_count(); ++i) {
      const double lambda_um = m.wavelengths_nm[i] / 1000.0;
      if (aod) {
        EXPECT_NEAR(m.mie_extinction_m1[i] / (beta * std::pow(lambda_um, -alpha) / 1200.0), 1.0, 1e-5);
        EXPECT_NEAR(m.mie_scattering_m1[i] / m.mie_extinction_m1[i], 0.8, 1e-5);
      }
      EXPECT_EQ(m.mie_phase.model, phase ? MiePhase::Model::Tabulated : MiePhase::Model::CornetteShanks);
      if (phase) {
        for (double c : {1.0, 0.9, 0.0, -1.0}) EXPECT_NEAR(m.mie_phase(i, c) / measured(i, c), 1.0, 1e-12);
      }
      ASSERT_EQ(m.absorbers.size(), ozone ? 1u : 0u);
      if (ozone) {
        EXPECT_NEAR(m.absorbers[0].absorption_m1[i] / (ozone_cross_section_m2(m.wavelengths_nm[i], 233.0) * o3_peak_m3),
                    1.0, 1e-4);
      }
    }
  }
}

/// The Egbert file with one line replaced (0-based), written to a temporary file.
std::filesystem::path egbert_with_line(std::size_t index, const std::string& replacement, const std::string& name) {
  std::ifstream in(kEgbert);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  lines.at(index) = replacement;
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream out(path);
  for (const std::string& line : lines) out << line << '\n';
  return path;
}

TEST(AeronetPhaseFile, RefusesMissingValuesAndOtherFilesNamingLineAndColumn) {
  std::ifstream in(kEgbert);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  struct Case {
    std::size_t line;
    std::string text, key, message;
  };
  std::string missing = lines[4];
  missing.replace(missing.find(",73.345490,"), 11, ",-999,");
  const Case cases[] = {
      {4, missing, "line 5, column '0.0000[442nm]'", "'-999' is not a phase-function value"},
      {5, lines[5].substr(0, 200), "line 6", "fields where the column names give 366"},
      {3, "Site,Date,Time", "line 4", "is this an AERONET file?"},
  };
  int k = 0;
  for (const Case& c : cases) {
    const auto path = egbert_with_line(c.line, c.text, "zenith_aeronet_bad_" + std::to_string(k++) + ".pfn");
    try {
      read_aeronet_phase_functions(path);
      ADD_FAILURE() << "accepted: " << c.key;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.file(), path.string());
      EXPECT_EQ(e.key(), c.key) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace zenith::atmosphere
