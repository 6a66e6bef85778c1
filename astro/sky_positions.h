#pragma once
// Where the stars, the Sun and the Moon are, for a time and a place on the
// Earth, by ERFA (the IAU SOFA algorithms; Debian liberfa-dev):
//  * eraApco13: IAU 2006/2000A precession–nutation (CIP X, Y and CIO locator s),
//    the Earth rotation angle from UT1, the observer's barycentric position and
//    velocity (EPV00 Earth + the site's geocentric position and diurnal
//    velocity), light deflection by the Sun and annual + diurnal aberration;
//    polar motion taken as zero (< 0.3″, ~10 m). Refraction is switched off
//    there (phpa = 0): refraction.h applies our own, from the model's air.
//  * stars: eraAtciq (proper motion and parallax to the date, deflection,
//    aberration, bias–precession–nutation: ICRS → CIRS) then eraAtioq (CIRS →
//    azimuth and zenith distance at the site);
//  * the Sun: EPV00 (eraEpv00; ~0.05″ against DE405 over 1900–2100), seen from
//    the observer, through the same aberration and rotation;
//  * the Moon: Moon98 (eraMoon98, Meeus' ELP-2000/82 truncation; ~10″ in
//    position), geometric, topocentric by subtracting the observer's geocentric
//    position, then the same rotation. Phase angle from the Sun–Moon–observer triangle.
// Every angle is geometric (before refraction). Azimuth from north through east.
// Figures against almanacs: docs/night-sky.md, tests/astro/sky_positions_test.cpp.
#include <array>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "astro/civil_time.h"
#include "astro/star_catalogue.h"

namespace zenith::astro {

/// An observer on the Earth: geodetic latitude and longitude (WGS84, east
/// positive) and height above the ellipsoid.
struct Site {
  double latitude_deg = 0.0;   ///< [−90, 90]
  double longitude_deg = 0.0;  ///< [−180, 360)
  double altitude_m = 0.0;     ///< [−500, 10000]
};

/// Throws std::invalid_argument naming the field and its range.
void check_site(const Site& site);

/// A direction in the observer's sky.
struct Horizontal {
  double azimuth_rad = 0.0;   ///< from north through east, [0, 2π)
  double altitude_rad = 0.0;  ///< above the horizon (geometric: no refraction)
  /// Unit vector in the local frame (east, north, up).
  glm::dvec3 east_north_up() const;
};

/// Right ascension and declination on the true equator and equinox of date
/// (an almanac's "apparent place").
struct Equatorial {
  double ra_rad = 0.0, dec_rad = 0.0;
};

struct SunPlace {
  Horizontal horizontal;
  double distance_au = 1.0;         ///< observer–Sun
  double angular_radius_rad = 0.0;  ///< R_sun / distance (R_sun = 695 700 km, IAU 2015 B3)
};

struct MoonPlace {
  Horizontal horizontal;
  double distance_km = 0.0;           ///< observer–Moon centre
  double angular_radius_rad = 0.0;    ///< asin(R_moon / distance), R_moon = 1737.4 km
  double phase_angle_rad = 0.0;       ///< Sun–Moon–observer angle: 0 full, π new
  double illuminated_fraction = 0.0;  ///< (1 + cos phase angle) / 2
  double sun_distance_au = 1.0;       ///< Moon–Sun
};

class SkyPositions {
 public:
  /// Throws std::invalid_argument for a bad site (AstroTime has refused any
  /// date ERFA cannot convert).
  SkyPositions(const AstroTime& time, const Site& site);

  const AstroTime& time() const { return time_; }
  const Site& site() const { return site_; }

  Horizontal star(const CatalogueStar& star) const;
  /// All of them into `out` (resized).
  void stars(const std::vector<CatalogueStar>& stars, std::vector<Horizontal>& out) const;
  SunPlace sun() const;
  MoonPlace moon() const;

  /// Geocentric apparent places (for almanac comparisons): the same chain seen
  /// from the Earth's centre, on the true equator and equinox of date.
  Equatorial apparent_geocentric(const CatalogueStar& star) const;
  Equatorial sun_apparent_geocentric() const;
  Equatorial moon_apparent_geocentric() const;
  /// Geocentric distance of the Moon [km].
  double moon_geocentric_distance_km() const;
  /// The Moon's phase angle seen from the Earth's centre (almanacs'; the site's
  /// differs by up to the Moon's parallax, ~1°).
  double moon_geocentric_phase_angle_rad() const;

  /// The vectors behind moon(), on GCRS axes [au]: observer → Moon and Moon →
  /// Sun; `geocentric`: from the Earth's centre instead of the site
  /// (astro/moon_orientation.h orients the Moon with them).
  struct MoonVectors {
    glm::dvec3 moon_from_observer_au{}, sun_from_moon_au{};
  };
  MoonVectors moon_vectors(bool geocentric = false) const;
  /// A direction given on GCRS axes (a body's axis, not a place) as a unit
  /// vector of the site's (east, north, up): the Earth's orientation only, as
  /// moon() turns the Moon's vector.
  glm::dvec3 gcrs_direction_enu(const glm::dvec3& v) const;

 private:
  AstroTime time_;
  Site site_;
  struct State;  // ERFA's star-independent parameters for the site and the geocentre, the bodies' vectors
  std::shared_ptr<const State> state_;
};

/// The Moon's and the Sun's radii used above [km].
inline constexpr double kMoonRadius_km = 1737.4;
inline constexpr double kSunRadius_km = 695700.0;
inline constexpr double kAstronomicalUnit_km = 149597870.7;

}  // namespace zenith::astro
