#include "bench/star_frames.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "astro/civil_time.h"
#include "core/units.h"
#include "scene/sky_clock.h"
#include "warp/planar_projection.h"

namespace zenith::bench {
namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

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
  render::RenderOptions timed = with;
  timed.time_passes = true;
  render::Renderer stars(with, tables), no_stars(without, tables), passes(timed, tables);
  const scene::Scene night = at_night(scene, t);
  fmt::print("render_bench --stars: scene '{}' at {} (site {:.4f}°, {:.4f}°), exposure {:g}, stars to V {}\n",
             scene.name, t.time_utc, night.sky_clock->site.latitude_deg, night.sky_clock->site.longitude_deg,
             t.exposure, t.magnitude_limit);
  std::vector<std::pair<int, int>> sizes = t.sizes.empty() ? std::vector<std::pair<int, int>>{{1280, 720}} : t.sizes;
  std::ofstream csv(t.csv);
  if (!csv) throw std::runtime_error("cannot write " + t.csv.string());
  csv << "device,resolution,projection,case,stars_drawn,frame_ms_without_stars,frame_ms_with_stars,overhead_percent,"
         "star_placement_ms,star_splat_ms,night_sky_ms,frames\n";
  for (const auto& [w, h] : sizes) {
    const warp::PlanarProjection projection = warp::PlanarProjection::symmetric(w, h, t.fov_deg);
    for (const bool day : {false, true}) {
      const scene::Scene& s = day ? scene : night;
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
      const std::string label = day ? "day (scene's sun and exposure)" : "night";
      fmt::print(
          "  {}x{} planar {:g}°, {}: {} stars drawn; {:.1f} ms without stars, {:.1f} ms with: {:+.1f} %"
          " (placement {:.1f} ms CPU, splat {:.2f} ms, night sky {:.2f} ms GPU; {} frames each)\n",
          w, h, t.fov_deg, label, b.stats.stars, ma, mb, overhead, part("star placement"), part("stars"),
          part("night sky"), a.ms.size());
      csv << '"' << device << "\"," << w << 'x' << h << ",planar " << t.fov_deg << "deg," << (day ? "day" : "night")
          << ',' << b.stats.stars << ','
          << fmt::format("{:.3f},{:.3f},{:.2f},{:.3f},{:.3f},{:.3f}", ma, mb, overhead, part("star placement"),
                         part("stars"), part("night sky"))
          << ',' << a.ms.size() << '\n';
    }
  }
  fmt::print("csv: {}\n", t.csv.string());
}

}  // namespace zenith::bench
