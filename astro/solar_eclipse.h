#pragma once
// A solar eclipse as a site sees it at one instant: how far apart the Sun's
// and the Moon's discs are, how much of the Sun the Moon covers and what kind
// of eclipse that is — from the topocentric places of astro/sky_positions.h
// (ERFA's Sun and Moon98, ~10″: about 0.5 % of the Sun's diameter).
//
// With r_s, r_m the two angular radii and d the separation of the centres
// (all small angles, so the discs are treated as plane circles):
//   magnitude  M = (r_s + r_m − d) / (2 r_s) in a partial phase (the share of
//              the Sun's diameter covered) and r_m / r_s in an annular or total
//              one (the ratio of the diameters), as NASA's eclipse tables
//              define it,
//   obscuration = covered area / π r_s²  (the lens of two circles, below).
// Kinds: none (d ≥ r_s + r_m), partial, annular (the Moon wholly inside the
// Sun, r_m < r_s, d ≤ r_s − r_m) and total (d ≤ r_m − r_s).
#include <glm/vec3.hpp>

#include "astro/sky_positions.h"
#include "atmosphere/solar_limb_darkening.h"

namespace zenith::astro {

enum class EclipseKind { none, partial, annular, total };
const char* to_string(EclipseKind kind);

struct SolarEclipseView {
  double separation_rad = 0.0;  ///< between the discs' centres
  double sun_radius_rad = 0.0, moon_radius_rad = 0.0;
  double magnitude = 0.0;    ///< share of the Sun's diameter covered, r_m / r_s when central (≤ 0: none)
  double obscuration = 0.0;  ///< share of the Sun's disc area covered, in [0, 1]
  EclipseKind kind = EclipseKind::none;
};

/// The eclipse seen from `sky`'s site at its time.
SolarEclipseView solar_eclipse_view(const SkyPositions& sky);

/// The covered share of a circle of radius r_s by a circle of radius r_m whose
/// centre is d away (plane geometry): 0 apart, min(1, r_m²/r_s²) when one
/// holds the other, else the lens area / π r_s². Throws std::invalid_argument
/// for a negative or non-finite argument or a zero r_s.
double disc_obscuration(double separation, double sun_radius, double moon_radius);

/// The Sun and the Moon of `sky` in the frame of atmosphere/sky_sampling.h
/// (the observer on the +z axis, `observer_radius_m` from the planet's
/// centre), turned so that +x is north and +y east: azimuths count from north
/// through east as an almanac's. For the reference solver's eclipsed sun.
struct SunAndMoon {
  double sun_zenith_deg = 0.0, sun_azimuth_deg = 0.0;
  double sun_angular_radius_rad = 0.0;
  glm::dvec3 moon_centre_m{0.0};  ///< from the planet's centre
  double moon_radius_m = 0.0;
};
SunAndMoon sun_and_moon(const SkyPositions& sky, double observer_radius_m);

/// The covered share of the light of a limb-darkened disc (I(μ)/I(1) =
/// Σ a_k μ^k, μ = sqrt(1 − ρ²/r_s²), atmosphere/solar_limb_darkening.h) by a
/// circle of radius r_m whose centre is d away:
///   ∫ I(ρ) c(ρ) ρ dρ / ∫ I(ρ) 2π ρ dρ = 1/(π m) ∫_0^1 I(μ)/I(1) μ c(ρ(μ)) dμ,
/// c(ρ) the covered angle of the ring of radius ρ (2 acos((ρ² + d² − r_m²) /
/// 2ρd), clamped) and m the law's mean over its centre, integrated in μ by
/// 64-point Gauss–Legendre panels. A uniform law is disc_obscuration(). Throws
/// as disc_obscuration, and as atmosphere::check_limb_darkening.
double limb_darkened_obscuration(double separation, double sun_radius, double moon_radius,
                                 const atmosphere::LimbDarkening& limb);

}  // namespace zenith::astro
