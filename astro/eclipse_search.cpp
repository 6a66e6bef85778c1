#include "astro/eclipse_search.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/strings.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

constexpr double kDay_s = 86400.0;

/// The discs and the Sun's altitude at one instant.
struct Sample {
  SolarEclipseView view;
  double sun_altitude_rad = 0.0;
  /// > 0 where the discs overlap (first to last contact).
  double overlap() const { return view.sun_radius_rad + view.moon_radius_rad - view.separation_rad; }
  /// > 0 where one disc lies wholly over or inside the other (second to third contact).
  double nested() const { return std::abs(view.sun_radius_rad - view.moon_radius_rad) - view.separation_rad; }
};

class Search {
 public:
  Search(const Site& site, const AstroTime& origin) : site_(site), origin_(origin) {}

  Sample at(double t_s) const {
    const SkyPositions sky(origin_.plus_seconds(t_s), site_);
    return {solar_eclipse_view(sky), sky.sun().horizontal.altitude_rad};
  }
  double separation(double t_s) const { return at(t_s).view.separation_rad; }

  /// The least separation in [a, b] [s]: a 20-minute grid, then golden section to a second.
  double least_separation(double a, double b) const {
    constexpr double kStep_s = 1200.0;
    double best = a, best_value = separation(a);
    for (double t = a + kStep_s; t <= b; t += kStep_s)
      if (const double v = separation(t); v < best_value) best = t, best_value = v;
    double lo = std::max(a, best - kStep_s), hi = std::min(b, best + kStep_s);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = separation(x1), f2 = separation(x2);
    while (hi - lo > 1.0) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = separation(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = separation(x2);
      }
    }
    return 0.5 * (lo + hi);
  }

  /// The instant in [a, b] where `measure` (Sample::overlap or Sample::nested)
  /// changes sign, to a second; `positive_at_b`: its sign at b.
  double contact(double a, double b, bool positive_at_b, double (Sample::*measure)() const) const {
    while (b - a > 1.0) {
      const double m = 0.5 * (a + b);
      (((at(m).*measure)() > 0.0) == positive_at_b ? b : a) = m;
    }
    return 0.5 * (a + b);
  }

  AstroTime time(double t_s) const { return origin_.plus_seconds(t_s); }

 private:
  Site site_;
  AstroTime origin_;
};

}  // namespace

std::optional<LocalSolarEclipse> next_solar_eclipse(const Site& site, const AstroTime& from, double years) {
  if (!(years > 0.0 && years <= 30.0))
    throw std::invalid_argument(core::cat("next_solar_eclipse: years ", years, " must be in (0, 30]"));
  // Times in seconds from two days before `from`, so an eclipse in progress is found too.
  const Search search(site, from.plus_seconds(-2.0 * kDay_s));
  const double end_s = (years * 365.25 + 2.0) * kDay_s, from_s = 2.0 * kDay_s;
  std::vector<double> daily;
  for (double t = 0.0; t <= end_s + kDay_s; t += kDay_s) daily.push_back(search.separation(t));
  for (std::size_t k = 1; k + 1 < daily.size(); ++k) {
    // A new moon: the daily samples' least separation. Beyond 15° none of the
    // Moon's path within a day can reach the Sun (12° a day, 5.3° of
    // latitude, 1° of parallax).
    if (!(daily[k] <= daily[k - 1] && daily[k] < daily[k + 1]) || daily[k] > 15.0 * core::kDeg) continue;
    const double t_min = search.least_separation(double(k - 1) * kDay_s, double(k + 1) * kDay_s);
    const Sample nearest = search.at(t_min);
    if (nearest.overlap() <= 0.0) continue;  // the Moon passes by the Sun
    const double hours4 = 4.0 * 3600.0;
    const double c1 = search.contact(t_min - hours4, t_min, true, &Sample::overlap),
                 c4 = search.contact(t_min, t_min + hours4, false, &Sample::overlap);
    if (c4 <= from_s) continue;  // over before `from`
    // Seen where the Sun is up between the contacts: the least separation then.
    std::optional<double> maximum;
    double least = 0.0;
    for (double t = c1; t <= c4; t += 60.0) {
      const Sample s = search.at(t);
      if (s.sun_altitude_rad <= 0.0) continue;
      if (!maximum || s.view.separation_rad < least) maximum = t, least = s.view.separation_rad;
    }
    if (!maximum) continue;  // the Sun is down throughout
    const double t_max = nearest.sun_altitude_rad > 0.0 ? t_min : *maximum;
    const Sample at_max = search.at(t_max);
    LocalSolarEclipse eclipse{search.time(t_max), at_max.view, search.time(c1), search.time(c4),
                              at_max.sun_altitude_rad / core::kDeg};
    // Totality or annularity lasts at most 12.5 minutes: an hour either side brackets it.
    if (nearest.nested() > 0.0) {
      const double hour = 3600.0;
      eclipse.second_contact = search.time(search.contact(t_min - hour, t_min, true, &Sample::nested));
      eclipse.third_contact = search.time(search.contact(t_min, t_min + hour, false, &Sample::nested));
    }
    return eclipse;
  }
  return std::nullopt;
}

}  // namespace zenith::astro
