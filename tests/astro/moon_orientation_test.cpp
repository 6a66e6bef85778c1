// The Moon's orientation (astro/moon_orientation.h) against Meeus, Astronomical
// Algorithms (2nd ed. 1998), Example 53.a: 1992 April 12, 0h TD, geocentric —
// the optical libration l = −1.206°, b = +4.194° and (with the physical
// libration, ≤ 0.03° here, which we leave out) P = 15.08°; the sub-solar point
// of Example 53.b (l0 = 67.89°, b0 = +1.46°); and the geometry's consistency:
// the arc from the sub-observer to the sub-solar point is the phase angle the
// disc is drawn with (astro/moon_photometry.h), the axes are orthonormal, the
// site's libration differs from the geocentre's by the Moon's parallax.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "astro/moon_orientation.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

using core::kDeg;

double arc_between(const Selenographic& a, const Selenographic& b) {
  const double c = std::sin(a.latitude_rad) * std::sin(b.latitude_rad) +
                   std::cos(a.latitude_rad) * std::cos(b.latitude_rad) * std::cos(a.longitude_rad - b.longitude_rad);
  return std::acos(std::clamp(c, -1.0, 1.0));
}

TEST(MoonOrientation, MeeusExample53aOpticalLibrationAndPositionAngle) {
  const SkyPositions sky(AstroTime::from_tt(2448724.5), Site{});  // 1992 April 12, 0h TD
  const MoonOrientation o = moon_orientation(sky, /*geocentric=*/true);
  std::printf(
      "Meeus 53.a: l %.4f° (−1.206), b %.4f° (+4.194), P %.3f° (15.08); sun l0 %.3f° (67.89), b0 %.3f° (1.46)\n",
      o.observer.longitude_rad / kDeg, o.observer.latitude_rad / kDeg, o.axis_position_angle_rad / kDeg,
      o.sun.longitude_rad / kDeg, o.sun.latitude_rad / kDeg);
  // Moon98 against Meeus's ch. 47 series: the same truncation of ELP-2000/82 (≲ 10″).
  EXPECT_NEAR(o.observer.longitude_rad / kDeg, -1.206, 0.005);
  EXPECT_NEAR(o.observer.latitude_rad / kDeg, 4.194, 0.005);
  // Meeus's P includes the physical libration (ρ, σ: ≈ 0.01° in the pole).
  EXPECT_NEAR(o.axis_position_angle_rad / kDeg, 15.08, 0.03);
  // 53.b's sub-solar point includes the physical libration too (±0.03°).
  EXPECT_NEAR(o.sun.longitude_rad / kDeg, 67.89, 0.05);
  EXPECT_NEAR(o.sun.latitude_rad / kDeg, 1.46, 0.05);
}

TEST(MoonOrientation, TheSubSolarPointIsThePhaseAngleFromTheObserver) {
  const Site greenwich{51.4769, -0.0005, 46.0};
  for (const UtcTime& t :
       {UtcTime{2026, 1, 3, 23, 0, 0.0}, UtcTime{2026, 12, 21, 17, 0, 0.0}, UtcTime{2027, 3, 10, 4, 0, 0.0}}) {
    const SkyPositions sky(AstroTime::from_utc(t), greenwich);
    const MoonOrientation o = moon_orientation(sky);
    EXPECT_NEAR(arc_between(o.observer, o.sun), sky.moon().phase_angle_rad, 1e-9);
    const MoonAxes& a = o.axes;
    EXPECT_NEAR(glm::dot(a.x, a.x), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(a.z, a.z), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(a.x, a.z), 0.0, 1e-12);
    EXPECT_NEAR(glm::dot(a.y, a.y), 1.0, 1e-12);
    // Optical libration stays within its bounds: |l| ≤ 8.1°, |b| ≤ 6.9° plus the parallax (≤ 1°).
    EXPECT_LT(std::abs(o.observer.longitude_rad), 9.1 * kDeg);
    EXPECT_LT(std::abs(o.observer.latitude_rad), 7.9 * kDeg);
    // The site's libration differs from the geocentre's by about the Moon's
    // horizontal parallax times the sine of its zenith distance (≤ 1.02°).
    const MoonOrientation g = moon_orientation(sky, true);
    const double shift = arc_between(o.observer, g.observer);
    const double parallax = std::asin(6378.137 / sky.moon_geocentric_distance_km());
    const double zenith = 0.5 * core::kPi - sky.moon().horizontal.altitude_rad;
    EXPECT_NEAR(shift, parallax * std::sin(zenith), 0.05 * parallax) << t.month;
  }
}

}  // namespace
}  // namespace zenith::astro
