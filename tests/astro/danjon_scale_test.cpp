// Danjon's scale (astro/danjon_scale.h): the class a model implies from the
// observers' L and the model's error in brightness, the slope against the
// published pairs it comes from and one it does not, the scale's bounds and
// its descriptions.
#include "astro/danjon_scale.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace zenith::astro {
namespace {

TEST(DanjonScale, AModelTooBrightRatesItsEclipseBrighterBySixTenthsAMagnitude) {
  // 2022-11-08: observers 2.4, measured 10.78 mag below the uneclipsed Moon, a model at 10.59.
  EXPECT_NEAR(implied_danjon_class(2.4, 10.78, 10.59), 2.4 + 0.6 * 0.19, 1e-12);
  // One magnitude too dark: 0.6 darker; the measured drop itself: the observers' class.
  EXPECT_NEAR(implied_danjon_class(2.0, 10.0, 11.0), 1.4, 1e-12);
  EXPECT_DOUBLE_EQ(implied_danjon_class(3.1, 9.5, 9.5), 3.1);
  // The scale ends at 0 and 4.
  EXPECT_DOUBLE_EQ(implied_danjon_class(3.5, 12.0, 10.0), 4.0);
  EXPECT_DOUBLE_EQ(implied_danjon_class(0.5, 10.0, 12.0), 0.0);
}

TEST(DanjonScale, TheSlopeJoinsVitalsPairsAndHoldsForTheObservedOneItWasNotMadeFrom) {
  // Magnitudes at mid-totality instead of drops: the uneclipsed Moon cancels in the difference.
  // From 2022-11-08 (L 2.4 at m −1.6) to the 2008-02-21 prediction (m −2.6): L 3.0 ± 0.4 predicted.
  EXPECT_NEAR(implied_danjon_class(2.4, -1.6, -2.6), 3.0, 1e-12);
  // 2008-02-21 as observed: m −2.8 ± 0.3, L 3.0 ± 0.1 — within the pair's own errors of the line.
  const double l_2008 = implied_danjon_class(2.4, -1.6, -2.8);
  EXPECT_NEAR(l_2008, 3.0, 0.1 + 0.6 * 0.3);
}

TEST(DanjonScale, RefusesAClassOffTheScaleAndADropThatIsNotANumber) {
  EXPECT_THROW(implied_danjon_class(4.5, 10.0, 10.0), std::invalid_argument);
  EXPECT_THROW(implied_danjon_class(-0.1, 10.0, 10.0), std::invalid_argument);
  EXPECT_THROW(implied_danjon_class(std::nan(""), 10.0, 10.0), std::invalid_argument);
  EXPECT_THROW(implied_danjon_class(2.0, std::numeric_limits<double>::infinity(), 10.0), std::invalid_argument);
  EXPECT_THROW(implied_danjon_class(2.0, 10.0, std::nan("")), std::invalid_argument);
  try {
    implied_danjon_class(4.5, 10.0, 10.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("[0, 4]"), std::string::npos) << e.what();
  }
}

TEST(DanjonScale, EachClassHasDanjonsDescription) {
  EXPECT_EQ(nearest_danjon_class(2.49), 2);
  EXPECT_EQ(nearest_danjon_class(2.5), 3);
  EXPECT_EQ(nearest_danjon_class(-0.4), 0);
  EXPECT_EQ(nearest_danjon_class(4.6), 4);
  EXPECT_EQ(nearest_danjon_class(std::nan("")), 0);
  EXPECT_NE(danjon_description(0.2).find("almost invisible"), std::string_view::npos);
  EXPECT_NE(danjon_description(1.0).find("grey or brownish"), std::string_view::npos);
  EXPECT_NE(danjon_description(2.4).find("deep red"), std::string_view::npos);
  EXPECT_NE(danjon_description(2.6).find("brick-red"), std::string_view::npos);
  EXPECT_NE(danjon_description(3.9).find("bluish"), std::string_view::npos);
  // Off the scale: its ends.
  EXPECT_EQ(danjon_description(-3.0), danjon_description(0.0));
  EXPECT_EQ(danjon_description(7.0), danjon_description(4.0));
  EXPECT_EQ(danjon_description(std::nan("")), danjon_description(0.0));
}

}  // namespace
}  // namespace zenith::astro
