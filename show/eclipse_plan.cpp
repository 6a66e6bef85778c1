#include "show/eclipse_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace zenith::show {
namespace {

std::string utc(const astro::AstroTime& t) {
  const astro::UtcTime u = t.calendar_utc();
  return fmt::format("{:04d}-{:02d}-{:02d} {:02d}:{:02d}:{:02d} UTC", u.year, u.month, u.day, u.hour, u.minute,
                     static_cast<int>(std::floor(u.second)));
}

}  // namespace

bool EclipsePlan::during_show() const { return eclipse && eclipse->first_contact.utc().value() <= last.utc().value(); }

bool EclipsePlan::lunar_during_show() const {
  return lunar && lunar->penumbra_begins.utc().value() <= last.utc().value();
}

std::optional<EclipsePlan> plan_eclipses(const Show& show) {
  const std::optional<scene::SkyClock>& clock = show.scene().sky_clock;
  if (!clock) return std::nullopt;
  // The show's sky time over its timeline, each second and at its end (a time track may run backwards).
  std::optional<astro::AstroTime> first, last;
  const double duration = show.duration_s();
  for (double t = 0.0;; t = std::min(t + 1.0, duration)) {
    if (const std::optional<astro::AstroTime> sky = show.sky_time_at(t)) {
      if (!first || sky->utc().value() < first->utc().value()) first = sky;
      if (!last || sky->utc().value() > last->utc().value()) last = sky;
    }
    if (t >= duration) break;
  }
  if (!first) return std::nullopt;
  return EclipsePlan{clock->site, *first, *last, astro::next_solar_eclipse(clock->site, *first, kEclipseSearchYears),
                     astro::next_lunar_eclipse(clock->site, *first, kEclipseSearchYears)};
}

std::string describe(const EclipsePlan& p) {
  const std::string where = fmt::format("{:.4f}°, {:.4f}°", p.site.latitude_deg, p.site.longitude_deg);
  const auto about = [](const astro::LocalSolarEclipse& e) {
    std::string text = fmt::format(
        "{} solar eclipse, maximum {} (magnitude {:.3f}, {:.1f} % of the disc covered, the Sun "
        "{:.1f}° up), contacts {} – {}",
        astro::to_string(e.at_maximum.kind), utc(e.maximum), e.at_maximum.magnitude, 100.0 * e.at_maximum.obscuration,
        e.sun_altitude_deg, utc(e.first_contact), utc(e.last_contact));
    if (e.second_contact) {
      const bool covered = e.at_maximum.moon_radius_rad >= e.at_maximum.sun_radius_rad;
      const long seconds = std::lround((e.third_contact->utc().value() - e.second_contact->utc().value()) * 86400.0);
      text += fmt::format(", {} {} – {} ({} min {:02d} s)", covered ? "totality" : "annularity", utc(*e.second_contact),
                          utc(*e.third_contact), seconds / 60, seconds % 60);
    }
    return text;
  };
  std::string out;
  if (p.during_show()) {
    out = fmt::format("eclipse: the show's sky at {} holds a {}\n", where, about(*p.eclipse));
  } else {
    out = fmt::format("eclipse: none at {} during the show's sky time ({} – {}); ", where, utc(p.first), utc(p.last));
    out += p.eclipse ? fmt::format("the next one seen from there: a {}\n", about(*p.eclipse))
                     : fmt::format("none seen from there within {:.0f} years\n", kEclipseSearchYears);
  }
  const auto about_lunar = [](const astro::LocalLunarEclipse& e) {
    std::string text =
        fmt::format("{} lunar eclipse, maximum {} (umbral magnitude {:.3f}, the Moon {})", astro::to_string(e.kind),
                    utc(e.maximum), e.umbral_magnitude,
                    e.moon_altitude_deg >= 0.0
                        ? fmt::format("{:.1f}° up", e.moon_altitude_deg)
                        : fmt::format("{:.1f}° below the horizon then: seen before or after", -e.moon_altitude_deg));
    if (e.umbra_begins) text += fmt::format(", umbra {} – {}", utc(*e.umbra_begins), utc(*e.umbra_ends));
    if (e.totality_begins) text += fmt::format(", totality {} – {}", utc(*e.totality_begins), utc(*e.totality_ends));
    return text;
  };
  if (p.lunar_during_show())
    return out + fmt::format("lunar eclipse: the show's sky holds a {}\n", about_lunar(*p.lunar));
  if (p.lunar) return out + fmt::format("lunar eclipse: the next one seen from there: a {}\n", about_lunar(*p.lunar));
  return out + fmt::format("lunar eclipse: none seen from there within {:.0f} years\n", kEclipseSearchYears);
}

}  // namespace zenith::show
