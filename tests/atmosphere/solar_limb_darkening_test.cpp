// The Sun's limb darkening (atmosphere/solar_limb_darkening.h): Neckel &
// Labs's table read back whole, the law between and beyond its wavelengths,
// and the shape of the measured limb.
#include "atmosphere/solar_limb_darkening.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "atmosphere/reference_data.h"

namespace zenith::atmosphere {
namespace {

TEST(SolarLimbDarkening, EveryRowGivesItsOwnTabulatedMean) {
  // Neckel & Labs print beside each row's coefficients the disc's mean intensity over its centre's,
  // 2 Σ a_k/(k + 2): a check of every coefficient as transcribed, to their 4-5 digits.
  const std::vector<LimbDarkeningRow>& rows = neckel_labs_1994_limb_darkening();
  ASSERT_EQ(rows.size(), 30u);
  EXPECT_DOUBLE_EQ(rows.front().wavelength_nm, 303.327);
  EXPECT_DOUBLE_EQ(rows.back().wavelength_nm, 1098.95);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const LimbDarkening law{rows[r].coefficients};
    double sum = 0.0;
    for (double a : law.coefficients) sum += a;
    EXPECT_NEAR(sum, 1.0, 3e-5) << rows[r].wavelength_nm << " nm";
    EXPECT_NEAR(law.mean_over_centre(), rows[r].mean_over_centre, 6e-5) << rows[r].wavelength_nm << " nm";
    if (r > 0) {
      EXPECT_GT(rows[r].wavelength_nm, rows[r - 1].wavelength_nm);
    }
  }
}

TEST(SolarLimbDarkening, TheLawIsTheTablesRowsInterpolatedInWavelength) {
  const std::vector<LimbDarkeningRow>& rows = neckel_labs_1994_limb_darkening();
  const auto sum_of = [](const std::array<double, 6>& a) { return a[0] + a[1] + a[2] + a[3] + a[4] + a[5]; };
  // At a row's wavelength: the row, scaled so that I(1) = 1 exactly.
  const LimbDarkeningRow& row = rows[16];  // 519.930 nm
  const LimbDarkening at_row = solar_limb_darkening(row.wavelength_nm);
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_NEAR(at_row.coefficients[k], row.coefficients[k] / sum_of(row.coefficients), 1e-15);
  EXPECT_NEAR(at_row.intensity(1.0), 1.0, 1e-15);
  // Halfway between two rows: their mean, renormalised.
  const LimbDarkening between = solar_limb_darkening(0.5 * (rows[16].wavelength_nm + rows[17].wavelength_nm));
  std::array<double, 6> mean{};
  for (std::size_t k = 0; k < 6; ++k) mean[k] = 0.5 * (rows[16].coefficients[k] + rows[17].coefficients[k]);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(between.coefficients[k], mean[k] / sum_of(mean), 1e-12);
  // Beyond the table: the nearest row's.
  EXPECT_EQ(solar_limb_darkening(200.0), solar_limb_darkening(rows.front().wavelength_nm));
  EXPECT_EQ(solar_limb_darkening(2000.0), solar_limb_darkening(rows.back().wavelength_nm));
  EXPECT_THROW(solar_limb_darkening(50.0), std::invalid_argument);
  EXPECT_THROW(solar_limb_darkening(20000.0), std::invalid_argument);
  EXPECT_THROW(solar_limb_darkening(std::nan("")), std::invalid_argument);
}

TEST(SolarLimbDarkening, TheMeasuredLimbIsDarkerInTheBlueAndNeverBlack) {
  for (double nm : {440.0, 550.0, 680.0}) {
    const LimbDarkening law = solar_limb_darkening(nm);
    EXPECT_DOUBLE_EQ(law.intensity(1.0), 1.0);
    EXPECT_DOUBLE_EQ(law.intensity(2.0), 1.0);                   // μ clamped
    EXPECT_DOUBLE_EQ(law.intensity(-1.0), law.coefficients[0]);  // the limb: a_0
    double previous = 1.0;
    for (double mu = 0.95; mu > -0.01; mu -= 0.05) {
      const double I = law.intensity(mu);
      EXPECT_LT(I, previous) << nm << " nm, μ " << mu;
      previous = I;
    }
    // The limb keeps 16-36 % of the centre's intensity at these wavelengths (a power law keeps none).
    EXPECT_GT(law.intensity(0.0), 0.15) << nm;
    EXPECT_LT(law.intensity(0.0), 0.36) << nm;
    // m = 2 ∫_0^1 I(μ) μ dμ, by the midpoint rule.
    double integral = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double mu = (i + 0.5) / n;
      integral += 2.0 * law.intensity(mu) * mu / n;
    }
    EXPECT_NEAR(law.mean_over_centre(), integral, 1e-8) << nm;
  }
  for (double mu : {0.0, 0.1, 0.5, 0.9}) {
    EXPECT_LT(solar_limb_darkening(440.0).intensity(mu), solar_limb_darkening(550.0).intensity(mu)) << mu;
    EXPECT_LT(solar_limb_darkening(550.0).intensity(mu), solar_limb_darkening(680.0).intensity(mu)) << mu;
  }
  EXPECT_DOUBLE_EQ(LimbDarkening{}.intensity(0.3), 1.0);
  EXPECT_DOUBLE_EQ(LimbDarkening{}.mean_over_centre(), 1.0);
}

TEST(SolarLimbDarkening, ALawThatIsNotOneIsRefusedNamingWho) {
  EXPECT_NO_THROW(check_limb_darkening(solar_limb_darkening(500.0), "test"));
  EXPECT_NO_THROW(check_limb_darkening(LimbDarkening{}, "test"));
  try {
    check_limb_darkening(LimbDarkening{{0.5, 0.0, 0.0, 0.0, 0.0, 0.0}}, "SunDisc");
    FAIL() << "a law summing to 0.5 was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("SunDisc"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_limb_darkening(LimbDarkening{{-0.5, 1.5, 0.0, 0.0, 0.0, 0.0}}, "test"), std::invalid_argument);
  EXPECT_THROW(check_limb_darkening(LimbDarkening{{std::nan(""), 1.0, 0.0, 0.0, 0.0, 0.0}}, "test"),
               std::invalid_argument);
}

}  // namespace
}  // namespace zenith::atmosphere
