// The CIE standard general sky (validate/cie_sky.h) against values computed
// by hand from ISO 15469:2004 / CIE S 011/E:2003 and the embedded table.
#include "validate/cie_sky.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/units.h"

using namespace zenith::validate;
using zenith::core::kPi;

using zenith::core::kDeg;

TEST(CieSky, TableHasTheFifteenTypesOfTheStandard) {
  const auto types = cie_general_sky_types();
  ASSERT_EQ(types.size(), 15u);
  for (std::size_t i = 0; i < types.size(); ++i) EXPECT_EQ(types[i].number, int(i) + 1);
  const CieSkyType t12 = cie_general_sky_type(kCieStandardClearSkyType);
  EXPECT_DOUBLE_EQ(t12.a, -1.0);
  EXPECT_DOUBLE_EQ(t12.b, -0.32);
  EXPECT_DOUBLE_EQ(t12.c, 10.0);
  EXPECT_DOUBLE_EQ(t12.d, -3.0);
  EXPECT_DOUBLE_EQ(t12.e, 0.45);
  EXPECT_NE(t12.description.find("clear sky low luminance turbidity"), std::string::npos);
  const CieSkyType t1 = cie_general_sky_type(1);  // overcast, steep gradation
  EXPECT_DOUBLE_EQ(t1.a, 4.0);
  EXPECT_DOUBLE_EQ(t1.b, -0.7);
  EXPECT_THROW(cie_general_sky_type(16), std::out_of_range);
  EXPECT_THROW(cie_general_sky_type(0), std::out_of_range);
}

TEST(CieSky, ParserRefusesMalformedTables) {
  EXPECT_THROW(parse_cie_sky_types("# only a comment\n"), std::invalid_argument);
  EXPECT_THROW(parse_cie_sky_types("type,a,b,c,d,e\n1,4,-0.7,0,-1,0\n"), std::invalid_argument);  // header
  EXPECT_THROW(parse_cie_sky_types("type,a,b,c,d,e,description\n1,4,x,0,-1,0,bad\n"), std::invalid_argument);
  EXPECT_THROW(parse_cie_sky_types("type,a,b,c,d,e,description\n1,4,-0.7\n"), std::invalid_argument);
  const auto two = parse_cie_sky_types("# c\ntype,a,b,c,d,e,description\n7,0,-1,5,-2.5,0.30,x\n3,1.1,-0.8,0,-1,0,y\n");
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].number, 3);  // sorted by number
  EXPECT_DOUBLE_EQ(two[1].e, 0.30);
  EXPECT_EQ(two[1].description, "x");
}

TEST(CieSky, GradationAtZenithAndHorizon) {
  const CieSkyType t12 = cie_general_sky_type(12);
  // φ(0) = 1 + a·e^b = 1 − e^−0.32 = 0.273850962926...
  EXPECT_NEAR(cie_gradation(t12, 0.0), 1.0 - std::exp(-0.32), 1e-15);
  EXPECT_NEAR(cie_gradation(t12, 0.0), 0.27385096292631, 1e-13);
  // φ(π/2) = 1, and continuous toward it.
  EXPECT_DOUBLE_EQ(cie_gradation(t12, kPi / 2.0), 1.0);
  EXPECT_NEAR(cie_gradation(t12, 89.9 * kDeg), 1.0, 1e-10);
  EXPECT_DOUBLE_EQ(cie_gradation(t12, 100.0 * kDeg), 1.0);
  // φ(45°) = 1 − exp(−0.32·√2) = 0.363994673...
  EXPECT_NEAR(cie_gradation(t12, 45.0 * kDeg), 0.3639946730435, 1e-12);
}

TEST(CieSky, IndicatrixAtTheSunAndAtRightAngles) {
  const CieSkyType t12 = cie_general_sky_type(12);
  // f(0) = 1 + c·(1 − e^{dπ/2}) + e = 1 + 10·(1 − e^{−3π/2}) + 0.45 = 11.36016708979
  EXPECT_NEAR(cie_indicatrix(t12, 0.0), 11.360167089789, 1e-11);
  EXPECT_NEAR(cie_indicatrix(t12, 0.0), 1.0 + 10.0 * (1.0 - std::exp(-3.0 * kPi / 2.0)) + 0.45, 1e-14);
  // f(π/2) = 1 for every type (both bracketed terms vanish).
  for (const CieSkyType& t : cie_general_sky_types()) EXPECT_NEAR(cie_indicatrix(t, kPi / 2.0), 1.0, 1e-14) << t.number;
  // f(30°) = 1 + 10·(e^{−π/2} − e^{−3π/2}) + 0.45·0.75 = 3.3264628533
  EXPECT_NEAR(cie_indicatrix(t12, 30.0 * kDeg), 3.326462853296, 1e-11);
}

TEST(CieSky, SunDistance) {
  EXPECT_NEAR(cie_sun_distance_rad(30.0 * kDeg, 0.0, 30.0 * kDeg), 0.0, 1e-7);
  EXPECT_NEAR(cie_sun_distance_rad(45.0 * kDeg, kPi, 30.0 * kDeg), 75.0 * kDeg, 1e-12);
  EXPECT_NEAR(cie_sun_distance_rad(0.0, 1.234, 40.0 * kDeg), 40.0 * kDeg, 1e-12);
  EXPECT_NEAR(cie_sun_distance_rad(90.0 * kDeg, kPi / 2.0, 60.0 * kDeg), 90.0 * kDeg, 1e-12);
}

TEST(CieSky, RelativeLuminanceIsOneAtTheZenithForEveryType) {
  for (const CieSkyType& t : cie_general_sky_types())
    for (double zs : {0.0, 20.0, 45.0, 80.0, 89.0})
      for (double az : {0.0, 90.0, 217.0})
        EXPECT_NEAR(cie_relative_luminance(t, 0.0, az * kDeg, zs * kDeg), 1.0, 1e-12)
            << "type " << t.number << " sun zenith " << zs;
}

TEST(CieSky, RelativeLuminanceIsSymmetricAboutTheSolarMeridian) {
  const CieSkyType t12 = cie_general_sky_type(12);
  for (double z : {10.0, 45.0, 85.0})
    for (double az : {30.0, 90.0, 135.0}) {
      const double l = cie_relative_luminance(t12, z * kDeg, az * kDeg, 50.0 * kDeg);
      EXPECT_NEAR(cie_relative_luminance(t12, z * kDeg, -az * kDeg, 50.0 * kDeg), l, 1e-13);
      EXPECT_NEAR(cie_relative_luminance(t12, z * kDeg, (360.0 - az) * kDeg, 50.0 * kDeg), l, 1e-13);
    }
}

TEST(CieSky, HandComputedType12Values) {
  const CieSkyType t12 = cie_general_sky_type(12);
  // Sun at Z_s = 30°, view Z = 45° opposite the sun (α = 180°, χ = 75°):
  // f(75°) = 1.13734010380, φ(45°) = 0.36399467304, f(30°) = 3.32646285330,
  // φ(0) = 0.27385096293  →  L/Lz = 0.45445243069.
  EXPECT_NEAR(cie_relative_luminance(t12, 45.0 * kDeg, kPi, 30.0 * kDeg), 0.45445243069, 1e-10);
  // Sun at Z_s = 60°, horizon at α = 90° (χ = 90°): f = φ = 1, L/Lz = 1/(f(60°)·φ(0)) = 2.51003953959.
  EXPECT_NEAR(cie_relative_luminance(t12, 90.0 * kDeg, kPi / 2.0, 60.0 * kDeg), 2.51003953959, 1e-10);
  // Type 5 (uniform luminance) is 1 everywhere.
  const CieSkyType t5 = cie_general_sky_type(5);
  EXPECT_NEAR(cie_relative_luminance(t5, 70.0 * kDeg, 0.3, 40.0 * kDeg), 1.0, 1e-14);
  // Type 12 brightens toward the sun and toward the horizon away from it (the clear-sky shape).
  EXPECT_NEAR(cie_relative_luminance(t12, 40.0 * kDeg, 0.0, 30.0 * kDeg), 2.72523669660, 1e-10);  // χ = 10°
  EXPECT_GT(cie_relative_luminance(t12, 85.0 * kDeg, kPi, 30.0 * kDeg),
            cie_relative_luminance(t12, 60.0 * kDeg, kPi, 30.0 * kDeg));
}
