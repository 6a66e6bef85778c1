#include "bench/star_frames.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "core/units.h"
#include "scene/sky_clock.h"
#include "warp/planar_projection.h"

namespace zenith::bench {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

using Clock = std::chrono::steady_clock;

/// The body the camera stands nearest to (the site's body).
std::size_t nearest_body(const scene::Scene& s) {
  std::size_t best = 0;
  double altitude = 1e300;
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const double a = glm::length(s.camera.position_m - s.bodies[b].position_m) - s.bodies[b].radius_m;
    if (a < altitude) {
      altitude = a;
      best = b;
    }
  }
  return best;
}

/// `scene` at night: a sky clock at the camera's latitude and longitude on its
/// body at `time`, the sun where the ephemeris puts it, `exposure`.
scene::Scene at_night(const scene::Scene& scene, const StarTiming& t) {
  scene::Scene s = scene;
  const std::size_t b = nearest_body(s);
  const scene::Body& body = s.bodies[b];
  const glm::dvec3 local = glm::conjugate(body.orientation) * (s.camera.position_m - body.position_m);
  const double r = glm::length(local);
  astro::Site site;
  site.latitude_deg = std::asin(local.z / r) / core::kDeg;
  site.longitude_deg = std::atan2(local.y, local.x) / core::kDeg;
  site.altitude_m = std::clamp(r - body.radius_m, 0.0, 10000.0);
  s.sky_clock = scene::SkyClock{astro::parse_utc_time(t.time_utc), site, b};
  const scene::EphemerisSun sun =
      scene::ephemeris_sun(s, *s.sky_clock, astro::AstroTime::from_utc(s.sky_clock->time), s.camera.position_m);
  s.sun.direction = sun.direction;
  s.camera.exposure = t.exposure;
  return s;
}

struct Case {
  std::vector<double> ms;
  render::FrameStats stats;
};

void frame(render::Renderer& r, const scene::Scene& s, const warp::Projection& p, Case& c) {
  const render::RowSink discard = [](int, int, std::span<const float>) {};
  const auto start = Clock::now();
  r.render(s, p, discard);
  c.ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  c.stats = r.last_frame();
}

}  // namespace

void time_stars(const StarTiming& t, const std::string& device, const scene::Scene& scene,
                const render::TableSource& tables) {
  render::RenderOptions with, without;
  with.night_sky.star_magnitude_limit = t.magnitude_limit;
  without.night_sky.stars = false;
  if (t.moonlight) {  // what differs is the Moon's light; no stars in either
    with.night_sky.stars = false;
    without.night_sky.moonlight = false;
  }
  const char* feature = t.moonlight ? "moonlight" : "stars";
  render::RenderOptions timed = with;
  timed.time_passes = true;
  render::Renderer stars(with, tables), no_stars(without, tables), passes(timed, tables);
  const scene::Scene night = at_night(scene, t);
  // The moonlight's day: the sky clock at a daylight hour with the Moon up, the scene's own exposure.
  StarTiming day_timing = t;
  day_timing.time_utc = t.day_time_utc;
  day_timing.exposure = scene.camera.exposure;
  const scene::Scene moon_day = at_night(scene, day_timing);
  if (t.moonlight)
    for (const scene::Scene* s : {&night, &moon_day}) {
      const astro::SkyPositions sky(astro::AstroTime::from_utc(s->sky_clock->time), s->sky_clock->site);
      fmt::print("  {}: the Moon {:.1f}° up ({:.0f} % lit), the Sun {:.1f}°, exposure {:g}\n",
                 astro::format_utc_time(s->sky_clock->time), sky.moon().horizontal.altitude_rad / core::kDeg,
                 100.0 * sky.moon().illuminated_fraction, sky.sun().horizontal.altitude_rad / core::kDeg,
                 s->camera.exposure);
    }
  fmt::print("render_bench --{}: scene '{}' at {} (site {:.4f}°, {:.4f}°), exposure {:g}{}\n", feature, scene.name,
             t.time_utc, night.sky_clock->site.latitude_deg, night.sky_clock->site.longitude_deg, t.exposure,
             t.moonlight ? "" : fmt::format(", stars to V {}", t.magnitude_limit));
  std::vector<std::pair<int, int>> sizes = t.sizes.empty() ? std::vector<std::pair<int, int>>{{1280, 720}} : t.sizes;
  std::ofstream csv(t.csv);
  if (!csv) throw std::runtime_error("cannot write " + t.csv.string());
  if (t.moonlight)
    csv << "device,resolution,projection,case,moonlight_drawn,moonlight_bound,frame_ms_without_moonlight,"
           "frame_ms_with_moonlight,overhead_percent,paired_overhead_percent,moonlight_passes_ms,moonlight_sky_view_ms,"
           "atmosphere_passes_ms,"
           "frames\n";
  else
    csv << "device,resolution,projection,case,stars_drawn,frame_ms_without_stars,frame_ms_with_stars,overhead_percent,"
           "paired_overhead_percent,"
           "star_placement_ms,star_splat_ms,night_sky_ms,frames\n";
  for (const auto& [w, h] : sizes) {
    const warp::PlanarProjection projection = warp::PlanarProjection::symmetric(w, h, t.fov_deg);
    for (const bool day : {false, true}) {
      const scene::Scene& s = day ? (t.moonlight ? moon_day : scene) : night;
      Case a, b;
      frame(stars, s, projection, b);  // untimed: the catalogue, shader variants
      frame(no_stars, s, projection, a);
      a.ms.clear();
      b.ms.clear();
      for (int round = 0; round < t.rounds; ++round)
        for (int i = 0; i < t.iterations; ++i) {
          frame(no_stars, s, projection, a);
          frame(stars, s, projection, b);
        }
      // The pass's own parts, from one frame with GL timer queries (serialized: not a frame time),
      // after one untimed (the catalogue's epoch, shader variants).
      passes.render(s, projection, [](int, int, std::span<const float>) {});
      passes.render(s, projection, [](int, int, std::span<const float>) {});
      const auto& ms = passes.last_frame().pass_ms;
      const auto part = [&](const char* name) { return ms.contains(name) ? ms.at(name) : 0.0; };
      const double ma = median(a.ms), mb = median(b.ms);
      const double overhead = 100.0 * (mb - ma) / ma;
      // The frames alternate without, with: the median of each pair's
      // difference cancels the machine's slow drifts (a shared VM's frame times
      // wander by more than the stars cost between runs).
      std::vector<double> pairs;
      for (std::size_t i = 0; i < std::min(a.ms.size(), b.ms.size()); ++i) pairs.push_back(b.ms[i] - a.ms[i]);
      const double paired = 100.0 * median(pairs) / ma;
      const std::string label = day ? "day (scene's sun and exposure)" : "night";
      if (t.moonlight) {
        // The GPU time of the Moon's passes and of the sun's atmosphere passes, summed over their names.
        double moon_ms = 0.0, sun_ms = 0.0;
        for (const auto& [name, v] : ms)
          if (name.starts_with("moonlight: "))
            moon_ms += v;
          else if (name.starts_with("atmosphere "))
            sun_ms += v;
        fmt::print(
            "  {}x{} planar {:g}°, {}: moonlight {} (bound {:.3g}); {:.1f} ms without, {:.1f} ms with: {:+.1f} %"
            " (paired {:+.1f} %; its passes {:.1f} ms, its sky-view table {:.2f} ms, the sun's atmosphere passes "
            "{:.1f} ms GPU; {} "
            "frames each)\n",
            w, h, t.fov_deg, label, b.stats.moonlight ? "drawn" : "skipped", b.stats.moonlight_bound, ma, mb, overhead,
            paired, moon_ms, part("sky-view table, moonlight"), sun_ms, a.ms.size());
        csv << '"' << device << "\"," << w << 'x' << h << ",planar " << t.fov_deg << "deg," << (day ? "day" : "night")
            << ',' << b.stats.moonlight << ',' << b.stats.moonlight_bound << ','
            << fmt::format("{:.3f},{:.3f},{:.2f},{:.2f},{:.3f},{:.3f},{:.3f}", ma, mb, overhead, paired, moon_ms,
                           part("sky-view table, moonlight"), sun_ms)
            << ',' << a.ms.size() << '\n';
        continue;
      }
      fmt::print(
          "  {}x{} planar {:g}°, {}: {} stars drawn; {:.1f} ms without stars, {:.1f} ms with: {:+.1f} %"
          " (paired {:+.1f} %; placement {:.1f} ms CPU, splat {:.2f} ms, night sky {:.2f} ms GPU; {} frames each)\n",
          w, h, t.fov_deg, label, b.stats.night_sky.stars, ma, mb, overhead, paired, part("star placement"),
          part("stars"), part("night sky"), a.ms.size());
      csv << '"' << device << "\"," << w << 'x' << h << ",planar " << t.fov_deg << "deg," << (day ? "day" : "night")
          << ',' << b.stats.night_sky.stars << ','
          << fmt::format("{:.3f},{:.3f},{:.2f},{:.2f},{:.3f},{:.3f},{:.3f}", ma, mb, overhead, paired,
                         part("star placement"), part("stars"), part("night sky"))
          << ',' << a.ms.size() << '\n';
    }
  }
  fmt::print("csv: {}\n", t.csv.string());
}

}  // namespace zenith::bench
