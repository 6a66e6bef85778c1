#pragma once
// The Moon's orientation by date (docs/night-sky.md, "The Moon's face"): its
// body-fixed (selenographic) axes, the observer's selenographic point (the
// optical libration l, b), the position angle P of its axis, the sub-solar point.
//
// Model: Cassini's laws with the mean lunar equator of Meeus, "Astronomical
// Algorithms" (2nd ed., 1998), ch. 53. On the mean ecliptic and equinox of
// date (ERFA's eraEcm06, IAU 2006):
//   * the Moon's north pole lies at ecliptic latitude 90° − I, longitude Ω + 90°
//     (I = 1.54242°, the mean lunar equator's inclination; Ω the mean longitude
//     of the ascending node of the orbit, ERFA's eraFaom03): the lunar equator's
//     descending node is the orbit's ascending node;
//   * the prime meridian (longitude 0, the mean sub-Earth point) faces away
//     from the Moon's mean place, at angle F + 180° from the node direction in
//     the lunar equator (F = L − Ω, the mean argument of latitude, eraFaf03):
//     uniform rotation, one turn per draconic month against the node.
// With u the observer → Moon direction and W = λ − Ω its longitude from the
// node, this is Meeus's eq. 53.1:
//   tan A = (sin W cos β cos I − sin β sin I) / (cos W cos β),  l = A − F,
//   sin b = −sin W cos β sin I − sin β cos I,
// written as dot products with the axes. P from the true celestial pole of
// date (the CIP, eraPnm06a): the axis's angle on the sky from north through east.
// Left out: the physical libration (the Moon's forced wobble about Cassini's
// state, ≤ 0.04° in l and b, Meeus's example 53.a: −0.025°, +0.006°); the
// light time of the Moon (1.3 s, < 0.001°). Conventions: IAU (east longitude
// positive, toward Mare Crisium; north toward Mare Frigoris); l > 0 shows more
// of the eastern limb.
#include <glm/vec3.hpp>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"

namespace zenith::astro {

/// The mean lunar equator's inclination to the ecliptic (Meeus ch. 53; IAU 1.54242°).
inline constexpr double kLunarEquatorInclination_deg = 1.54242;

/// The Moon's body-fixed axes as unit vectors on GCRS axes: x toward
/// selenographic (0°, 0°), y toward (90° E, 0°), z toward the north pole.
struct MoonAxes {
  glm::dvec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
};

/// The mean axes at a time (TT), as above.
MoonAxes moon_axes_gcrs(const JulianDate& tt);

/// Selenographic longitude (east positive, (−π, π]) and latitude of a
/// direction `v` from the Moon's centre (GCRS axes, any length).
struct Selenographic {
  double longitude_rad = 0.0, latitude_rad = 0.0;
};
Selenographic selenographic(const MoonAxes& axes, const glm::dvec3& v);

struct MoonOrientation {
  MoonAxes axes;                   ///< on GCRS axes
  Selenographic observer;          ///< the optical libration: l (longitude), b (latitude)
  Selenographic sun;               ///< the sub-solar point
  double axis_position_angle_rad;  ///< P: the north pole's position angle, from north through east, [0, 2π)
};

/// The Moon seen from the site of `sky` (topocentric: the parallax shifts l
/// and b by up to ~1°) or, `geocentric`, from the Earth's centre (almanacs' values).
MoonOrientation moon_orientation(const SkyPositions& sky, bool geocentric = false);

}  // namespace zenith::astro
