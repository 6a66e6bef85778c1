// Schaefer's naked-eye limiting magnitude (validate/visibility.h), the
// yardstick `zenith validate night` counts visible stars with.
#include <gtest/gtest.h>

#include "validate/visibility.h"

namespace zenith::validate {
namespace {

TEST(Visibility, SchaefersLimitingMagnitude) {
  // Schaefer 1990: a dark sky (22 mag/arcsec² ≈ 54 nL) gives the naked eye ~6.5.
  EXPECT_NEAR(nanolamberts_from_v_mag_arcsec2(22.0), 54.0, 0.5);
  EXPECT_NEAR(naked_eye_limiting_magnitude(22.0), 6.6, 0.1);
  // A city sky (18 mag/arcsec²) ~4.4, a civil-twilight sky (12) below 3.
  EXPECT_NEAR(naked_eye_limiting_magnitude(18.0), 4.4, 0.3);
  EXPECT_LT(naked_eye_limiting_magnitude(12.0), 3.5);
  double last = 100.0;
  for (double mu = 23.0; mu >= 4.0; mu -= 0.25) {
    const double m = naked_eye_limiting_magnitude(mu);
    EXPECT_LE(m, last + 0.3) << mu;  // brighter sky, fewer stars (a small jump at the rod–cone switch)
    last = m;
  }
}

}  // namespace
}  // namespace zenith::validate
