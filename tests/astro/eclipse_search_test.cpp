// The next solar eclipse a site sees (astro/eclipse_search.h) against NASA's
// Five Millennium Canon of Solar Eclipses (Espenak & Meeus 2006) and its
// local circumstances: 2017 at its point of greatest eclipse, 2026 over
// northern Spain near sunset, 2027 at Luxor near noon.
#include "astro/eclipse_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace zenith::astro {
namespace {

double minutes_between(const AstroTime& a, const UtcTime& b) {
  return (a.utc().value() - AstroTime::from_utc(b).utc().value()) * 1440.0;
}

TEST(EclipseSearch, FindsTheTotalEclipseOf2017AtItsGreatestPoint) {
  const Site site{36.9667, -87.6667, 150.0};
  const auto e = next_solar_eclipse(site, AstroTime::from_utc({2017, 8, 1, 0, 0, 0.0}), 0.5);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->at_maximum.kind, EclipseKind::total);
  // Greatest eclipse 18:25:32 UTC, the Sun 64° up (NASA).
  EXPECT_NEAR(minutes_between(e->maximum, {2017, 8, 21, 18, 25, 32.0}), 0.0, 1.0);
  EXPECT_NEAR(e->sun_altitude_deg, 64.0, 1.0);
  // First and last contact 16:56 and 19:51 UTC (validate eclipse's bisection finds the same to a second).
  EXPECT_NEAR(minutes_between(e->first_contact, {2017, 8, 21, 16, 56, 3.0}), 0.0, 0.1);
  EXPECT_NEAR(minutes_between(e->last_contact, {2017, 8, 21, 19, 51, 10.0}), 0.0, 0.1);
  // In progress at 18:00: the same eclipse.
  const auto during = next_solar_eclipse(site, AstroTime::from_utc({2017, 8, 21, 18, 0, 0.0}), 0.5);
  ASSERT_TRUE(during.has_value());
  EXPECT_NEAR(minutes_between(during->maximum, {2017, 8, 21, 18, 25, 32.0}), 0.0, 1.0);
  // After it: none within the next half year at this site.
  EXPECT_FALSE(next_solar_eclipse(site, AstroTime::from_utc({2017, 8, 22, 0, 0, 0.0}), 0.5).has_value());
}

TEST(EclipseSearch, FindsSpainsSunsetTotalityAndLuxorsNoonTotality) {
  // 2026-08-12 at León, in the path over northern Spain: totality ~18:29 UTC with the Sun ~10° up.
  const auto spain =
      next_solar_eclipse(Site{42.5987, -5.5671, 840.0}, AstroTime::from_utc({2026, 6, 1, 0, 0, 0.0}), 0.5);
  ASSERT_TRUE(spain.has_value());
  EXPECT_EQ(spain->at_maximum.kind, EclipseKind::total);
  EXPECT_NEAR(minutes_between(spain->maximum, {2026, 8, 12, 18, 29, 0.0}), 0.0, 6.0);
  EXPECT_GT(spain->sun_altitude_deg, 5.0);
  EXPECT_LT(spain->sun_altitude_deg, 15.0);
  // 2027-08-02 at Luxor, near the point of greatest eclipse (10:07 UTC, the Sun 82° up).
  const auto luxor =
      next_solar_eclipse(Site{25.6872, 32.6396, 80.0}, AstroTime::from_utc({2027, 3, 1, 0, 0, 0.0}), 1.0);
  ASSERT_TRUE(luxor.has_value());
  EXPECT_EQ(luxor->at_maximum.kind, EclipseKind::total);
  EXPECT_NEAR(minutes_between(luxor->maximum, {2027, 8, 2, 10, 7, 0.0}), 0.0, 6.0);
  EXPECT_GT(luxor->sun_altitude_deg, 75.0);
}

TEST(EclipseSearch, RefusesASearchOfNoTimeOrCenturies) {
  const AstroTime t = AstroTime::from_utc({2026, 1, 1, 0, 0, 0.0});
  EXPECT_THROW(next_solar_eclipse(Site{}, t, 0.0), std::invalid_argument);
  EXPECT_THROW(next_solar_eclipse(Site{}, t, 31.0), std::invalid_argument);
  EXPECT_THROW(next_solar_eclipse(Site{95.0, 0.0, 0.0}, t, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::astro
