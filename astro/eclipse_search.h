#pragma once
// When a site sees its next solar eclipse (docs/shows.md, "Eclipses"): for a
// show whose date and place have none, `zenith show plan` says when the next
// one is. From the ephemeris of astro/sky_positions.h (ERFA's Sun, Moon98 and
// the site's topocentric places), no eclipse catalogue:
//
//   1. daily samples of the separation σ of the Sun's and the Moon's centres
//      bracket each new moon (σ falls ~12° a day toward it);
//   2. in the bracket σ is minimized on a 20-minute grid, then by golden
//      section to a second (one minimum: the Moon gains 0.5° an hour on the
//      Sun, the diurnal parallax moves it 0.08° an hour);
//   3. where σ < r_sun + r_moon there is an eclipse at the site: its contacts
//      by bisection — first and last at σ = r_sun + r_moon, second and third
//      at σ = |r_sun − r_moon| where the least σ falls below that (totality
//      or annularity); it is seen if the Sun is above the geometric horizon
//      at some time between the first and last (sampled every minute), and
//      its maximum is the least σ while the Sun is up.
//
// Tested against NASA's Five Millennium Canon (Espenak & Meeus) for 2017,
// 2023, 2026 and 2027 (tests/astro/eclipse_search_test.cpp).
#include <optional>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "astro/solar_eclipse.h"

namespace zenith::astro {

/// A solar eclipse as one site sees it, the Sun up.
struct LocalSolarEclipse {
  AstroTime maximum;                      ///< the least separation while the Sun is up
  SolarEclipseView at_maximum;            ///< the discs then
  AstroTime first_contact, last_contact;  ///< σ = r_sun + r_moon (the Sun may be down at either)
  double sun_altitude_deg = 0.0;          ///< geometric, at the maximum
  /// σ = |r_sun − r_moon|: where the Moon's disc comes to lie wholly over the
  /// Sun's (totality) or wholly inside it (annularity), and where that ends;
  /// absent where the site sees only a partial eclipse (the Sun may be down at either).
  std::optional<AstroTime> second_contact = std::nullopt, third_contact = std::nullopt;
};

/// The first solar eclipse `site` sees that has not ended at `from` (one in
/// progress then included), within `years` after it (at most 30), or none.
/// Throws std::invalid_argument for years outside (0, 30] and what
/// SkyPositions throws.
std::optional<LocalSolarEclipse> next_solar_eclipse(const Site& site, const AstroTime& from, double years = 5.0);

}  // namespace zenith::astro
