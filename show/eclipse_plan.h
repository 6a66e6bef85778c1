#pragma once
// The solar and lunar eclipses a show's sky passes through, or when its site
// sees the next ones (`zenith show plan`, docs/shows.md "Eclipses"). A show whose date
// and place have no eclipse is not an error — the show simply has none — but
// the planner says when the next one is (astro/eclipse_search.h).
#include <optional>
#include <string>

#include "astro/civil_time.h"
#include "astro/eclipse_search.h"
#include "astro/lunar_eclipse.h"
#include "astro/sky_positions.h"
#include "show/show.h"

namespace zenith::show {

/// How far ahead of the show's sky the next eclipse is looked for.
inline constexpr double kEclipseSearchYears = 5.0;

struct EclipsePlan {
  astro::Site site;
  astro::AstroTime first, last;  ///< the show's earliest and latest sky time
  /// The first solar eclipse the site sees that is not over at `first`, within kEclipseSearchYears.
  std::optional<astro::LocalSolarEclipse> eclipse;
  /// The same for lunar eclipses (the Moon up at the site between P1 and P4; astro/lunar_eclipse.h).
  std::optional<astro::LocalLunarEclipse> lunar;
  /// Whether the show's sky time reaches it: its first contact before `last`.
  bool during_show() const;
  bool lunar_during_show() const;
};

/// For a show whose scene gives "time" and "site"; none for one without a sky clock.
std::optional<EclipsePlan> plan_eclipses(const Show& show);

/// A line for each kind: the eclipse in the show (solar: kind, maximum,
/// magnitude, obscuration, the Sun's altitude, contacts; lunar: kind,
/// maximum, umbral magnitude, the Moon's altitude, the umbral phase and
/// totality) or that there is none and when the next one is.
std::string describe(const EclipsePlan& plan);

}  // namespace zenith::show
