// The measured skies (validate/measured_skies.h) as compiled in, their
// readers' errors, and the score of validate/measured_sky_validation.h
// against values worked by hand.
#include "validate/measured_skies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "validate/measured_sky_validation.h"

namespace zenith::validate {
namespace {

/// Runs `f`, which must throw std::invalid_argument with every one of `parts` in its message.
template <class F>
void expect_refused(F f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "not refused";
  } catch (const std::invalid_argument& e) {
    for (const char* p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

constexpr const char* kSuns =
    "# a comment\ncapture_time_EDT,sun_zenith_deg,sun_azimuth_used_deg\n09:30,48.9,91.1\n11:45,26.7,122.3\n";

TEST(MeasuredSkies, TheCompiledInCapturesAreKidersFifteenWithTheirSuns) {
  const MeasuredSkies skies = kider2014_cornell_skies();
  ASSERT_EQ(skies.wavelengths_nm.size(), 31u);
  EXPECT_DOUBLE_EQ(skies.wavelengths_nm.front(), 360.0);
  EXPECT_DOUBLE_EQ(skies.wavelengths_nm.back(), 360.0 + 11.75 * 30);
  ASSERT_EQ(skies.captures.size(), 15u);  // 09:30 … 13:30, without 13:00 and 13:15
  EXPECT_EQ(skies.captures.front().time, "09:30");
  EXPECT_EQ(skies.captures.back().time, "13:30");
  for (const MeasuredCapture& c : skies.captures) {
    ASSERT_EQ(c.directions.size(), 81u) << c.time;
    EXPECT_GT(c.sun_zenith_deg, 20.0);
    EXPECT_LT(c.sun_zenith_deg, 50.0);
  }
  // The first line of the file and the first capture's sun (validate/data/).
  const MeasuredDirection& first = skies.captures.front().directions.front();
  EXPECT_EQ(first.sample_index, 0);
  EXPECT_DOUBLE_EQ(first.azimuth_deg, 0.0);
  EXPECT_DOUBLE_EQ(first.elevation_deg, 12.115117);
  EXPECT_DOUBLE_EQ(first.radiance_W_m2_sr_nm[0], 0.0574660692);
  EXPECT_DOUBLE_EQ(skies.captures.front().sun_zenith_deg, 48.93794688);
  EXPECT_DOUBLE_EQ(skies.captures.front().sun_azimuth_deg, 91.14246196);
}

TEST(MeasuredSkies, EachCaptureHasTheSunsDistanceOfThatDay) {
  // The Astronomical Almanac's low-precision Sun: R = 1.00014 − 0.01671 cos g − 0.00014 cos 2g au with the mean
  // anomaly g = 357.528° + 0.9856003° n, n days from J2000.0 (JD 2451545.0); EPV00 from the site within 1e-4 au.
  const MeasuredSkies skies = kider2014_cornell_skies();
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  const auto almanac_au = [&](double julian_date_utc) {
    const double g = (357.528 + 0.9856003 * (julian_date_utc - 2451545.0)) * kDeg;
    return 1.00014 - 0.01671 * std::cos(g) - 0.00014 * std::cos(2.0 * g);
  };
  // 2013-05-27 09:30 EDT is 13:30 UTC, JD 2456440.0625; 13:30 EDT four hours later.
  EXPECT_NEAR(skies.captures.front().sun_distance_au, almanac_au(2456440.0625), 1e-4);
  EXPECT_NEAR(skies.captures.back().sun_distance_au, almanac_au(2456440.0625 + 4.0 / 24.0), 1e-4);
  // Late May the Earth recedes towards aphelion: dR/dt = 0.01671 sin g dg/dt, 1.76e-4 au a day; and as the Sun
  // climbs from 48.94° to 21.78° from the zenith the site turns towards it by R_earth (cos 21.78° − cos 48.94°).
  const double g = (357.528 + 0.9856003 * (2456440.0625 - 2451545.0)) * kDeg;
  const double receding_au = 0.01671 * std::sin(g) * 0.9856003 * kDeg * 4.0 / 24.0;
  const double turning_au = 6378.137 / 1.495978707e8 * (std::cos(21.78 * kDeg) - std::cos(48.94 * kDeg));
  EXPECT_NEAR(skies.captures.back().sun_distance_au - skies.captures.front().sun_distance_au, receding_au - turning_au,
              1e-6);

  // A capture time that is no local time is refused, naming it.
  MeasuredSkies odd = skies;
  odd.captures[1].time = "9h45";
  expect_refused(
      [&] {
        set_sun_distances(odd, astro::UtcTime{2013, 5, 27}, -4.0, astro::Site{42.4, -76.5, 0.0});
      },
      {"9h45", "hh:mm"});
}

TEST(MeasuredSkies, TheSunIsAstmG173AveragedOverTheEvaluationsBins) {
  const SolarSpectrum sun = astm_g173_extraterrestrial_sun();
  ASSERT_EQ(sun.wavelengths_nm.size(), 40u);
  // Bruneton 2017's values of the same bins (his atmosphere.cc, rounded to 6 digits).
  EXPECT_NEAR(sun.at(360.0), 1.13419, 1e-5);
  EXPECT_NEAR(sun.at(548.0), 1.85083, 1e-5);
  EXPECT_NEAR(sun.at(712.5), 1.35526, 1e-5);
  expect_refused([&] { sun.at(550.0); }, {"550 nm", "40 samples from 360 to 818.25 nm"});
}

TEST(MeasuredSkies, TheInstrumentsSunIsAstmG173ThroughA3NmSlitAtEachMeasuredWavelength) {
  const SolarSpectrum slit = astm_g173_extraterrestrial_sun_through_3nm_slit();
  const SolarSpectrum bins = astm_g173_extraterrestrial_sun();
  ASSERT_EQ(slit.wavelengths_nm.size(), 31u);
  // Between the Ca II K and H lines (393.4, 396.8 nm) the slit sees far less than the bin above 395.25 nm holds;
  // in the smooth red they agree within a few per cent.
  EXPECT_LT(slit.at(395.25), 0.85 * bins.at(395.25));
  EXPECT_NEAR(slit.at(618.5) / bins.at(618.5), 1.0, 0.03);
  // Over the whole range the two carry about the same energy (ASTM G173: ~1.8 W m^-2 nm^-1 at 500 nm).
  double slit_sum = 0.0, bins_sum = 0.0;
  for (double nm : slit.wavelengths_nm) slit_sum += slit.at(nm), bins_sum += bins.at(nm);
  EXPECT_NEAR(slit_sum / bins_sum, 1.0, 0.03);
}

TEST(MeasuredSkies, ReadersNameTheFileLineAndColumnOfWhatIsWrong) {
  const std::string header = "capture_time_EDT,sample_index,azimuth_deg,elevation_deg,L400,L500\n";
  const MeasuredSkies ok = parse_measured_skies(header + "09:30,0,0,12.1,0.05,0.04\n", "r.csv", kSuns, "s.csv");
  ASSERT_EQ(ok.captures.size(), 1u);
  EXPECT_DOUBLE_EQ(ok.captures[0].sun_azimuth_deg, 91.1);
  expect_refused([&] { parse_measured_skies(header + "09:30,0,0,12.1,0.05\n", "r.csv", kSuns, "s.csv"); },
                 {"r.csv, line 2", "5 cells where the header has 6"});
  expect_refused([&] { parse_measured_skies(header + "09:30,0,0,12.1,-0.05,0.04\n", "r.csv", kSuns, "s.csv"); },
                 {"r.csv, line 2, column L400", "-0.05 is outside [0, 100]"});
  expect_refused([&] { parse_measured_skies(header + "09:30,0,0,95,0.05,0.04\n", "r.csv", kSuns, "s.csv"); },
                 {"column elevation_deg", "outside [0, 90]"});
  expect_refused([&] { parse_measured_skies(header + "10:00,0,0,12.1,0.05,0.04\n", "r.csv", kSuns, "s.csv"); },
                 {"r.csv, line 2, column capture_time_EDT", "capture 10:00 has no line in s.csv"});
  expect_refused(
      [&] {
        parse_measured_skies("capture_time_EDT,sample_index,azimuth_deg,L400\n09:30,0,0,0.05\n", "r.csv", kSuns,
                             "s.csv");
      },
      {"r.csv: no column 'elevation_deg'"});
  expect_refused([&] { parse_measured_skies(header + "09:30,0,0,12.1,abc,0.04\n", "r.csv", kSuns, "s.csv"); },
                 {"column L400", "'abc' is not a number"});
  expect_refused([&] { parse_measured_skies(header + "09:30,0,0,12.1,0.05,0.04\n", "r.csv", "x\n", "s.csv"); },
                 {"s.csv: no header or no rows"});
  expect_refused(
      [&] {
        parse_measured_skies(header + "09:30,0,0,12.1,0.05,0.04\n", "r.csv",
                             "capture_time_EDT,sun_zenith_deg,sun_azimuth_used_deg\n09:30,40,90\n09:30,41,90\n",
                             "s.csv");
      },
      {"s.csv, line 3", "capture 09:30 has a sun line already"});
}

/// Two captures of two directions at 400 and 500 nm, and one wavelength the score leaves out (750 nm).
MeasuredSkies two_captures() {
  const std::string header = "capture_time_EDT,sample_index,azimuth_deg,elevation_deg,L400,L500,L750\n";
  return parse_measured_skies(header +
                                  "09:30,0,0,12,0.10,0.20,0.5\n09:30,1,90,40,0.10,0.20,0.5\n"
                                  "11:45,0,0,12,0.30,0.20,0.5\n11:45,1,90,40,0.30,0.20,0.5\n",
                              "r.csv", kSuns, "s.csv");
}

TEST(MeasuredSkyScore, IsTheRmsOverCapturesOfEachCapturesRmseOverDirectionsAndScoredWavelengths) {
  const MeasuredSkies skies = two_captures();
  // Capture 09:30 off by +0.01 at 400 nm in both directions: RMSE sqrt((2 · 0.01²) / 4) = 0.01 / √2.
  // Capture 11:45 off by −0.03 at 500 nm and nothing else: 0.03 / √2. Every error at 750 nm is out of the score.
  const CaptureSky model = [](const MeasuredCapture& c) {
    std::vector<std::vector<double>> L;
    for (const MeasuredDirection& d : c.directions) {
      std::vector<double> l = d.radiance_W_m2_sr_nm;
      if (c.time == "09:30") l[0] += 0.01;
      if (c.time == "11:45") l[1] -= 0.03;
      l[2] *= 3.0;
      L.push_back(l);
    }
    return L;
  };
  const MeasuredSkyScore s = score_measured_skies(skies, model);
  ASSERT_EQ(s.captures.size(), 2u);
  ASSERT_EQ(s.wavelengths_nm, (std::vector<double>{400.0, 500.0}));
  EXPECT_NEAR(s.captures[0].spectral_rmse_W_m2_sr_nm, 0.01 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(s.captures[1].spectral_rmse_W_m2_sr_nm, 0.03 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(s.spectral_rmse_W_m2_sr_nm, std::sqrt((0.01 * 0.01 + 0.03 * 0.03) / 4.0), 1e-15);
  // Σ model / Σ measured per wavelength over both captures: 400 nm (0.22 + 0.6) / (0.2 + 0.6); 500 nm (0.4 + 0.34) /
  // 0.8.
  EXPECT_NEAR(s.spectral_ratio[0], 0.82 / 0.8, 1e-12);
  EXPECT_NEAR(s.spectral_ratio[1], 0.74 / 0.8, 1e-12);
  EXPECT_NEAR(s.captures[0].model_over_measured, 0.62 / 0.6, 1e-12);
  EXPECT_GT(s.captures[0].luminance_rmse_cd_m2, 0.0);
  EXPECT_GT(s.captures[0].chromaticity_rmse, 0.0);
  ASSERT_EQ(s.directions.size(), 4u);

  const MeasuredSkyScore exact = score_measured_skies(skies, [](const MeasuredCapture& c) {
    std::vector<std::vector<double>> L;
    for (const MeasuredDirection& d : c.directions) L.push_back(d.radiance_W_m2_sr_nm);
    return L;
  });
  EXPECT_EQ(exact.spectral_rmse_W_m2_sr_nm, 0.0);
  EXPECT_EQ(exact.luminance_rmse_cd_m2, 0.0);
  EXPECT_EQ(exact.chromaticity_rmse, 0.0);
}

TEST(MeasuredSkyScore, SumsModelAndMeasurementInBandsOfTheAngleFromTheSun) {
  // cos γ = cos z☉ sin e + sin z☉ cos e cos(a − a☉). 09:30 (sun at zenith 48.9°,
  // azimuth 91.1°): the direction at azimuth 90°, elevation 40° is 1.38° from the
  // sun, the one at azimuth 0°, elevation 12° 83.0°; 11:45 (26.7°, 122.3°): 30.1°
  // and 92.8°. A model twice the measurement at 09:30's near-sun direction and
  // half of it at 11:45's far one, exact elsewhere.
  const MeasuredSkies skies = two_captures();
  const MeasuredSkyScore s = score_measured_skies(skies, [](const MeasuredCapture& c) {
    std::vector<std::vector<double>> L;
    for (const MeasuredDirection& d : c.directions) {
      std::vector<double> l = d.radiance_W_m2_sr_nm;
      const bool near = c.time == "09:30" && d.azimuth_deg == 90.0, far = c.time == "11:45" && d.azimuth_deg == 0.0;
      for (double& x : l) x *= near ? 2.0 : far ? 0.5 : 1.0;
      L.push_back(l);
    }
    return L;
  });
  ASSERT_EQ(s.sun_angle_bands.size(), std::size(kSunAngleBandEdges_deg) - 1);
  const auto band = [&](double from) {
    for (const SunAngleBand& b : s.sun_angle_bands)
      if (b.from_deg == from) return b;
    return SunAngleBand{};
  };
  EXPECT_EQ(band(0).directions, 1u);
  EXPECT_DOUBLE_EQ(band(0).model_over_measured, 2.0);
  EXPECT_EQ(band(30).directions, 1u);
  EXPECT_DOUBLE_EQ(band(30).model_over_measured, 1.0);
  // 83.0° and 92.8°, the scored wavelengths' sums 0.1 + 0.2 and 0.3 + 0.2: (0.3 + 0.5 / 2) / 0.8.
  EXPECT_EQ(band(70).directions, 2u);
  EXPECT_NEAR(band(70).model_over_measured, 0.55 / 0.8, 1e-12);
  EXPECT_EQ(band(10).directions + band(20).directions + band(45).directions + band(100).directions, 0u);
}

TEST(MeasuredSkyScore, AModelOfTheWrongShapeIsRefused) {
  const MeasuredSkies skies = two_captures();
  expect_refused(
      [&] { score_measured_skies(skies, [](const MeasuredCapture&) { return std::vector<std::vector<double>>(1); }); },
      {"1 directions for capture 09:30 of 2"});
  expect_refused(
      [&] {
        score_measured_skies(skies, [](const MeasuredCapture& c) {
          return std::vector<std::vector<double>>(c.directions.size(), std::vector<double>(2));
        });
      },
      {"2 wavelengths of 3"});
}

}  // namespace
}  // namespace zenith::validate
