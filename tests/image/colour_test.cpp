// Spectral radiance → linear sRGB weights, and sRGB reflectance → spectral weights.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "image/colour.h"

namespace zenith::image {
namespace {

using Weights = std::vector<std::array<double, 3>>;

std::array<double, 3> sum(const Weights& w) {
  std::array<double, 3> s{};
  for (const auto& row : w)
    for (int c = 0; c < 3; ++c) s[c] += row[c];
  return s;
}

/// Relative luminance of linear sRGB (IEC 61966-2-1 / BT.709).
double luminance(const std::array<double, 3>& rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

std::vector<double> even_wavelengths(int n, double from_nm = 380.0, double to_nm = 780.0) {
  std::vector<double> w;
  for (int i = 0; i < n; ++i) w.push_back(from_nm + (to_nm - from_nm) * i / (n - 1));
  return w;
}

void expect_unit_rows(const Weights& w, const std::vector<int>& channel) {
  ASSERT_EQ(w.size(), channel.size());
  for (std::size_t i = 0; i < w.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(w[i][c], c == channel[i] ? 1.0 : 0.0) << "row " << i << " channel " << c;
}

TEST(Colour, DirectWeightsForThePapersWavelengthsAreTheIdentity) {
  const std::vector<double> paper{680.0, 550.0, 440.0};
  expect_unit_rows(spectral_to_rgb_weights(paper, ColourMapping::direct), {0, 1, 2});
  expect_unit_rows(spectral_to_rgb_weights(paper, ColourMapping::automatic), {0, 1, 2});
  // Any order: each wavelength selects its own band.
  expect_unit_rows(spectral_to_rgb_weights(std::vector<double>{440.0, 550.0, 680.0}, ColourMapping::direct), {2, 1, 0});
  expect_unit_rows(spectral_to_rgb_weights(std::vector<double>{550.0, 680.0, 440.0}, ColourMapping::automatic),
                   {1, 0, 2});
  // Band edges: B [380, 500), G [500, 600), R [600, 750].
  expect_unit_rows(spectral_to_rgb_weights(std::vector<double>{600.0, 500.0, 380.0}, ColourMapping::direct), {0, 1, 2});
  expect_unit_rows(spectral_to_rgb_weights(std::vector<double>{750.0, 599.9, 499.9}, ColourMapping::direct), {0, 1, 2});
}

TEST(Colour, DirectRejectsWavelengthsThatDoNotFitItsBands) {
  const std::vector<std::vector<double>> bad{{450.0, 460.0, 700.0},
                                             {680.0, 550.0},
                                             {680.0, 550.0, 440.0, 500.0},
                                             {800.0, 550.0, 440.0},
                                             {680.0, 550.0, 370.0}};
  for (const auto& w : bad) {
    try {
      spectral_to_rgb_weights(w, ColourMapping::direct);
      FAIL() << "no exception for " << w.size() << " wavelengths starting at " << w[0];
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::to_string(int(w[1]))), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("600, 750"), std::string::npos) << e.what();
    }
    EXPECT_THROW(rgb_to_spectral_weights(w, ColourMapping::direct), std::invalid_argument);
  }
}

TEST(Colour, AutomaticFallsBackToCie1931) {
  const std::vector<double> five{450.0, 500.0, 550.0, 600.0, 650.0};
  EXPECT_EQ(spectral_to_rgb_weights(five, ColourMapping::automatic),
            spectral_to_rgb_weights(five, ColourMapping::cie1931));
  const std::vector<double> two_blue{440.0, 460.0, 680.0};
  EXPECT_EQ(spectral_to_rgb_weights(two_blue, ColourMapping::automatic),
            spectral_to_rgb_weights(two_blue, ColourMapping::cie1931));
}

TEST(Colour, Cie1931MapsAFlatSpectrumToLuminanceOneAndNearWhite) {
  const Weights w = spectral_to_rgb_weights(even_wavelengths(64), ColourMapping::cie1931);
  const std::array<double, 3> rgb = sum(w);
  EXPECT_NEAR(luminance(rgb), 1.0, 1e-6);  // exact with the derived matrix's Y row (0.212639, 0.715169, 0.072192)
  // Measured: (0.99575, 1.00137, 0.99900) — within 0.5 % of white (bound 0.6 %).
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 1.0, 0.006) << "channel " << c;
  // Denser sampling converges to the same colour; 16 wavelengths are within 3 %.
  const std::array<double, 3> dense = sum(spectral_to_rgb_weights(even_wavelengths(401), ColourMapping::cie1931));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(dense[c], rgb[c], 1e-3) << "channel " << c;
  const std::array<double, 3> coarse = sum(spectral_to_rgb_weights(even_wavelengths(16), ColourMapping::cie1931));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(coarse[c], 1.0, 0.03) << "channel " << c;
}

TEST(Colour, Cie1931IsIndependentOfTheOrderOfTheWavelengths) {
  std::vector<double> w = even_wavelengths(20);
  const Weights forward = spectral_to_rgb_weights(w, ColourMapping::cie1931);
  std::reverse(w.begin(), w.end());
  const Weights backward = spectral_to_rgb_weights(w, ColourMapping::cie1931);
  for (std::size_t i = 0; i < w.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(forward[i][c], backward[w.size() - 1 - i][c]);
}

TEST(Colour, Cie1931SpectralLinesHaveTheirHues) {
  const std::vector<double> w = even_wavelengths(41);  // every 10 nm
  const Weights weights = spectral_to_rgb_weights(w, ColourMapping::cie1931);
  auto at = [&](double nm) {
    for (std::size_t i = 0; i < w.size(); ++i)
      if (std::fabs(w[i] - nm) < 1e-9) return weights[i];
    ADD_FAILURE() << nm;
    return std::array<double, 3>{};
  };
  const auto red = at(650.0), green = at(530.0), blue = at(450.0);
  // Spectral lines lie outside the sRGB gamut (some channel negative), but their
  // own channel dominates: at 530 nm linear sRGB is about (−0.81, 1.46, −0.02) · Y/0.86.
  EXPECT_GT(red[0], 5 * std::fabs(red[1]));
  EXPECT_GT(red[0], 5 * std::fabs(red[2]));
  EXPECT_GT(green[1], 1.5 * std::fabs(green[0]));
  EXPECT_GT(green[1], 1.5 * std::fabs(green[2]));
  EXPECT_LT(green[0], 0.0);
  EXPECT_GT(blue[2], 2 * std::fabs(blue[0]));
  EXPECT_GT(blue[2], 2 * std::fabs(blue[1]));
  // Luminance peaks near 555 nm (photopic maximum).
  std::size_t brightest = 0;
  for (std::size_t i = 0; i < w.size(); ++i)
    if (luminance(weights[i]) > luminance(weights[brightest])) brightest = i;
  EXPECT_NEAR(w[brightest], 555.0, 10.0);
}

TEST(Colour, InvalidWavelengthsAreRejected) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const std::vector<double>& w : std::vector<std::vector<double>>{{}, {550.0, nan}, {-5.0, 550.0}}) {
    EXPECT_THROW(spectral_to_rgb_weights(w, ColourMapping::cie1931), std::invalid_argument);
    EXPECT_THROW(rgb_to_spectral_weights(w, ColourMapping::cie1931), std::invalid_argument);
  }
  EXPECT_THROW(spectral_to_rgb_weights(std::vector<double>{550.0, 550.0, 600.0}, ColourMapping::cie1931),
               std::invalid_argument);
  // Nothing a CIE observer sees.
  EXPECT_THROW(spectral_to_rgb_weights(std::vector<double>{1500.0, 2000.0}, ColourMapping::cie1931),
               std::invalid_argument);
}

TEST(Colour, WhiteReflectanceIsOneAtEveryWavelength) {
  const std::vector<std::pair<std::vector<double>, ColourMapping>> cases{
      {{680.0, 550.0, 440.0}, ColourMapping::direct},
      {{680.0, 550.0, 440.0}, ColourMapping::automatic},
      {{680.0, 550.0, 440.0}, ColourMapping::cie1931},
      {even_wavelengths(64), ColourMapping::cie1931},
      {even_wavelengths(7, 300.0, 900.0), ColourMapping::automatic}};
  for (const auto& [w, mapping] : cases) {
    const Weights weights = rgb_to_spectral_weights(w, mapping);
    ASSERT_EQ(weights.size(), w.size());
    for (std::size_t i = 0; i < w.size(); ++i) {
      EXPECT_DOUBLE_EQ(weights[i][0] + weights[i][1] + weights[i][2], 1.0) << w[i] << " nm, " << to_string(mapping);
      for (int c = 0; c < 3; ++c) EXPECT_GE(weights[i][c], 0.0);
    }
  }
}

TEST(Colour, ReflectanceIsPiecewiseLinearThroughBlueGreenRed) {
  const std::vector<double> w{400.0, 450.0, 500.0, 550.0, 600.0, 625.0, 650.0, 700.0};
  const Weights r = rgb_to_spectral_weights(w, ColourMapping::cie1931);
  const Weights expected{{0, 0, 1},     {0, 0, 1},       {0, 0.5, 0.5}, {0, 1, 0},
                         {0.5, 0.5, 0}, {0.75, 0.25, 0}, {1, 0, 0},     {1, 0, 0}};
  for (std::size_t i = 0; i < w.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(r[i][c], expected[i][c]) << w[i] << " nm channel " << c;
  // Direct: each wavelength takes its band's channel, and direct round-trips an albedo colour.
  const std::vector<double> paper{680.0, 550.0, 440.0};
  expect_unit_rows(rgb_to_spectral_weights(paper, ColourMapping::direct), {0, 1, 2});
  const std::vector<double> shifted{620.0, 520.0, 470.0};  // not the piecewise-linear values
  expect_unit_rows(rgb_to_spectral_weights(shifted, ColourMapping::automatic), {0, 1, 2});
}

TEST(Colour, NamesRoundTripAndUnknownNamesAreListed) {
  for (ColourMapping m : {ColourMapping::automatic, ColourMapping::direct, ColourMapping::cie1931})
    EXPECT_EQ(parse_colour_mapping(to_string(m)), m);
  EXPECT_STREQ(to_string(ColourMapping::automatic), "auto");
  try {
    parse_colour_mapping("cie2006");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("auto, direct, cie1931"), std::string::npos) << e.what();
  }
}

/// Planck's law at `kelvin` sampled at `wavelengths_nm` (arbitrary scale).
std::vector<double> planck(const std::vector<double>& wavelengths_nm, double kelvin) {
  std::vector<double> b;
  for (double nm : wavelengths_nm) {
    const double m = nm * 1e-9;
    b.push_back(1e-30 / (std::pow(m, 5) * std::expm1(1.438777e-2 / (m * kelvin))));
  }
  return b;
}

TEST(Chromaticity, AFlatSpectrumIsTheEqualEnergyWhite) {
  const std::vector<double> nm = even_wavelengths(64);
  const Chromaticity c = spectrum_chromaticity(nm, std::vector<double>(nm.size(), 2.5));
  EXPECT_NEAR(c.x, 1.0 / 3.0, 0.001);  // 0.3331, 0.3336
  EXPECT_NEAR(c.y, 1.0 / 3.0, 0.001);
}

TEST(Chromaticity, ThePublishedWhitesHaveTheirColourTemperatures) {
  // CIE 15: D65 (0.3127, 0.3290) has a CCT of 6504 K, illuminant A (0.44757, 0.40745) 2856 K, both on or
  // near the Planckian locus (D65 0.0032 above it). The colour matching functions are Wyman et al.'s fit,
  // not the tables: measured 6499 K (Duv 0.0031) and 2829 K (−0.0005).
  const ColourTemperature d65 = correlated_colour_temperature({0.3127, 0.3290});
  EXPECT_NEAR(d65.kelvin, 6504.0, 20.0);
  EXPECT_NEAR(d65.duv, 0.0032, 0.0005);
  const ColourTemperature a = correlated_colour_temperature({0.44757, 0.40745});
  EXPECT_NEAR(a.kelvin, 2856.0, 35.0);
  EXPECT_NEAR(a.duv, 0.0, 0.001);
}

TEST(Chromaticity, APlanckSpectrumAt31WavelengthsGivesBackItsTemperature) {
  const std::vector<double> nm = even_wavelengths(31);
  // The 31-point midpoint quadrature: +0.1 % at 2 856 K, +0.4 % at 11 000 K, +0.9 % at 20 000 K.
  for (double kelvin : {2000.0, 2856.0, 6500.0, 9000.0, 11000.0, 20000.0}) {
    const ColourTemperature t = correlated_colour_temperature(spectrum_chromaticity(nm, planck(nm, kelvin)));
    EXPECT_NEAR(t.kelvin, kelvin, (kelvin > 12000.0 ? 0.015 : 0.006) * kelvin) << kelvin << " K";
    EXPECT_LT(std::abs(t.duv), 0.002) << kelvin << " K";
  }
  // Bluer is hotter: more light at 440 nm than a 9 000 K radiator's, relative to 680 nm.
  std::vector<double> bluer = planck(nm, 9000.0);
  for (std::size_t i = 0; i < nm.size(); ++i) bluer[i] *= std::pow(550.0 / nm[i], 1.0);
  EXPECT_GT(correlated_colour_temperature(spectrum_chromaticity(nm, bluer)).kelvin, 11000.0);
}

TEST(Chromaticity, BluerThanAnyPlanckianRadiatorIsInfinitelyHot) {
  const std::vector<double> nm = even_wavelengths(31);
  // λ⁻⁴ is Planck's law as T → ∞ (Rayleigh–Jeans): the locus' blue end itself.
  std::vector<double> rayleigh_jeans, bluer;
  for (double l : nm) {
    rayleigh_jeans.push_back(std::pow(l / 550.0, -4.0));
    bluer.push_back(std::pow(l / 550.0, -6.0));
  }
  const ColourTemperature end = correlated_colour_temperature(spectrum_chromaticity(nm, rayleigh_jeans));
  EXPECT_TRUE(std::isinf(end.kelvin)) << end.kelvin;
  EXPECT_LT(std::abs(end.duv), 0.001);
  const ColourTemperature beyond = correlated_colour_temperature(spectrum_chromaticity(nm, bluer));
  EXPECT_TRUE(std::isinf(beyond.kelvin)) << beyond.kelvin;
  EXPECT_GT(std::abs(beyond.duv), 0.005);
  // 200 000 K is still on the locus, and found — within a mired (10⁶ / K): there the locus is so short
  // that the 31-point quadrature's error moves the temperature by 14 % (5.0 against 4.4 mired).
  const double found = correlated_colour_temperature(spectrum_chromaticity(nm, planck(nm, 2e5))).kelvin;
  EXPECT_NEAR(1e6 / found, 1e6 / 2e5, 1.0) << found;
}

TEST(Chromaticity, TheEffectiveBlackbodyTemperatureIsThePlanckCurveOfTheSpectrumsShape) {
  // Eclipse photometry's measure (Dandekar & Turtle 1971, 410–800 nm): the shape alone, any scale.
  const std::vector<double> nm = even_wavelengths(16, 380.0, 755.0);
  for (double kelvin : {5000.0, 9000.0, 11000.0, 30000.0}) {
    std::vector<double> b = planck(nm, kelvin);
    for (double& v : b) v *= 3.7e4;
    EXPECT_NEAR(effective_blackbody_temperature_K(nm, b, 410.0, 800.0), kelvin, 1e-4 * kelvin) << kelvin;
  }
  // Only the band counts: a spectrum 9 000 K's inside 530–660 nm and anything outside.
  std::vector<double> mixed = planck(nm, 9000.0);
  for (std::size_t i = 0; i < nm.size(); ++i)
    if (nm[i] < 530.0 || nm[i] > 660.0) mixed[i] *= 5.0;
  EXPECT_NEAR(effective_blackbody_temperature_K(nm, mixed, 530.0, 660.0), 9000.0, 1.0);
  // Steeper than Rayleigh–Jeans: no Planck curve, infinitely hot.
  std::vector<double> steep;
  for (double l : nm) steep.push_back(std::pow(l / 550.0, -6.0));
  EXPECT_TRUE(std::isinf(effective_blackbody_temperature_K(nm, steep, 410.0, 800.0)));
  EXPECT_THROW(effective_blackbody_temperature_K(nm, steep, 700.0, 720.0), std::invalid_argument);  // one λ
  std::vector<double> zero = steep;
  zero[5] = 0.0;
  EXPECT_THROW(effective_blackbody_temperature_K(nm, zero, 410.0, 800.0), std::invalid_argument);
}

TEST(Chromaticity, SaysWhichWavelengthsCannotCarryAColourAndRefusesBadSpectra) {
  const std::vector<double> three = {680.0, 550.0, 440.0};
  const std::string why = colour_spectrum_problem(three);
  EXPECT_NE(why.find("at least 16 wavelengths"), std::string::npos) << why;
  EXPECT_NE(why.find("440–680 nm"), std::string::npos) << why;
  EXPECT_TRUE(colour_spectrum_problem(even_wavelengths(16, 380.0, 755.0)).empty());
  EXPECT_FALSE(colour_spectrum_problem(even_wavelengths(16, 420.0, 755.0)).empty());
  EXPECT_FALSE(colour_spectrum_problem(even_wavelengths(15, 380.0, 780.0)).empty());

  const std::vector<double> nm = even_wavelengths(16);
  EXPECT_THROW(spectrum_chromaticity(nm, std::vector<double>(15, 1.0)), std::invalid_argument);
  std::vector<double> negative(16, 1.0);
  negative[3] = -0.5;
  EXPECT_THROW(spectrum_chromaticity(nm, negative), std::invalid_argument);
  EXPECT_THROW(spectrum_chromaticity(nm, std::vector<double>(16, 0.0)), std::invalid_argument);
  EXPECT_THROW(correlated_colour_temperature({0.7, 0.5}), std::invalid_argument);
  EXPECT_THROW(correlated_colour_temperature({std::nan(""), 0.3}), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::image
