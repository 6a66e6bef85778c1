#include "bench/star_twilight.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "astro/sky_positions.h"
#include "bench/star_frames.h"
#include "core/units.h"
#include "render/night/star_pass.h"
#include "scene/frame_scene.h"
#include "show/show.h"
#include "warp/fisheye_projection.h"

namespace zenith::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Row {
  double fixed_exposure = 0.0;  // 0: the show's own exposure track
  double t_s = 0.0, sun_altitude_deg = 0.0, exposure = 0.0;
  bool black_sky = false, global = false, sky = false;  // each test: the stars run
  double floor = 0.0, peak = 0.0, black_peak = 0.0, code_change = 0.0;
  std::size_t stars = 0, tested = 0;
};

/// The show's exposures: its exposure track's values at every whole second, distinct.
std::vector<double> key_exposures(const show::Show& show) {
  std::vector<double> out;
  for (double t = 0.0; t <= show.duration_s() + 1e-9; t += 15.0) {
    scene::Scene s = show.scene();
    scene::apply_frame(show.state_at(t, 0, 0), s);
    if (std::find(out.begin(), out.end(), s.camera.exposure) == out.end()) out.push_back(s.camera.exposure);
  }
  return out;
}

}  // namespace

void sweep_star_twilight(const StarTwilight& w, const std::string& device, const render::TableSource& tables) {
  const show::Show show = show::load_show(w.show);
  render::RenderOptions tested, forced;
  tested.night_sky.star_magnitude_limit = forced.night_sky.star_magnitude_limit = w.magnitude_limit;
  forced.night_sky.skip_hidden_stars = false;
  render::Renderer renderer(tested, tables), always(forced, tables);
  const warp::FisheyeProjection dome(w.dome_px, w.dome_px);
  const render::RowSink discard = [](int, int, std::span<const float>) {};
  const auto scene_at = [&](double t) {
    scene::Scene s = show.scene();
    scene::apply_frame(show.state_at(t, 0, 0), s);
    return s;
  };
  fmt::print("render_bench --stars-show: '{}', a {}² dome master, stars to V {}, on {}\n", w.show.string(), w.dome_px,
             w.magnitude_limit, device);
  std::vector<Row> rows;
  std::vector<double> exposures = {0.0};  // the show's track, then each of its exposures held through the twilight
  for (double e : key_exposures(show)) exposures.push_back(e);
  for (double fixed : exposures) {
    fmt::print("{}\n", fixed > 0.0 ? fmt::format("exposure held at {:g}:", fixed) : "the show's exposure track:");
    for (double t = 0.0; t <= show.duration_s() + 1e-9; t += w.step_s) {
      scene::Scene s = scene_at(t);
      if (fixed > 0.0) s.camera.exposure = fixed;
      renderer.render(s, dome, discard);
      const render::FrameStats& f = renderer.last_frame();
      Row r;
      r.fixed_exposure = fixed;
      r.t_s = t;
      r.exposure = s.camera.exposure;
      if (s.sky_clock) {
        const astro::SkyPositions sky(astro::AstroTime::from_utc(s.sky_clock->time), s.sky_clock->site);
        r.sun_altitude_deg = sky.sun().horizontal.altitude_rad / core::kDeg;
      }
      r.black_peak = f.night_sky.star_test.black_sky_peak;
      r.black_sky = f.night_sky.star_test.black_sky_peak >= render::kInvisibleDisplayStep;
      r.sky = f.night_sky.star_test.could_show;
      r.global = f.night_sky.star_test.could_show ||
                 f.night_sky.star_test.stars_tested > 0;  // the second stage runs where the first could not skip
      r.tested = f.night_sky.star_test.stars_tested;
      r.code_change = f.night_sky.star_test.code_change;
      r.floor = f.night_sky.star_test.largest_sky_floor();
      r.peak = f.night_sky.star_test.largest_sky_peak();
      r.stars = f.night_sky.stars;
      fmt::print(
          "  t {:4.1f} s: sun {:6.2f}°, exposure {:9.4g}: black-sky test {}, global sky test {}, star by star {} "
          "(floor {:.3g}, peak {:.3g}; {} tested one by one, ≤ {:.3g} code; {} stars placed)\n",
          t, r.sun_altitude_deg, r.exposure, r.black_sky ? "runs " : "skips", r.global ? "runs " : "skips",
          r.sky ? "runs " : "skips", r.floor, r.peak, r.tested, r.code_change, r.stars);
      rows.push_back(r);
    }
  }
  std::filesystem::path csv = w.csv;
  std::ofstream out(csv);
  if (!out) throw std::runtime_error("cannot write " + csv.string());
  out << "device,dome_px,exposure_held,show_time_s,sun_altitude_deg,exposure,black_sky_test_runs,"
         "global_test_runs,star_by_star_runs,sky_floor,star_peak,black_sky_peak,stars_tested,code_change,"
         "stars_placed\n";
  for (const Row& r : rows)
    out << '"' << device << "\"," << w.dome_px << ','
        << fmt::format("{},{:.2f},{:.3f},{:.6g},{},{},{},{:.6g},{:.6g},{:.6g},{},{:.4g},{}",
                       r.fixed_exposure > 0.0 ? fmt::format("{:g}", r.fixed_exposure) : "show", r.t_s,
                       r.sun_altitude_deg, r.exposure, int(r.black_sky), int(r.global), int(r.sky), r.floor, r.peak,
                       r.black_peak, r.tested, r.code_change, r.stars)
        << '\n';
  // Per exposure: from which frame on the stars run in every later frame
  // (the tables' floor steps between μs columns, so a test may skip a frame
  // or two after it first ran).
  for (double fixed : exposures) {
    const auto from = [&](bool Row::*test) {
      const Row* start = nullptr;
      for (const Row& r : rows)
        if (r.fixed_exposure == fixed) start = r.*test ? (start ? start : &r) : nullptr;
      return start ? fmt::format("sun {:.2f}° (t {:.0f} s, exposure {:.4g})", start->sun_altitude_deg, start->t_s,
                                 start->exposure)
                   : std::string("never");
    };
    fmt::print(
        "{}: the stars run from the black-sky test's {} on, the global sky test's {} on, the star-by-star test's {} "
        "on\n",
        fixed > 0.0 ? fmt::format("exposure {:g}", fixed) : std::string("the show's exposures"), from(&Row::black_sky),
        from(&Row::global), from(&Row::sky));
  }

  // The saving: at the last frame the global test ran and the star-by-star
  // one skips (else the black-sky test and the sky's).
  std::vector<const Row*> saved;
  for (const Row& r : rows)
    if (r.global && !r.sky) saved.push_back(&r);
  if (saved.empty())
    for (const Row& r : rows)
      if (r.black_sky && !r.sky) saved.push_back(&r);
  std::filesystem::path times = csv;
  times.replace_filename(csv.stem().string() + "_times.csv");
  std::ofstream timing(times);
  if (!timing) throw std::runtime_error("cannot write " + times.string());
  timing << "device,dome_px,show_time_s,sun_altitude_deg,exposure,frame_ms_skipped,frame_ms_forced,saved_ms,"
            "saved_percent,stars_forced,star_test_ms,frames\n";
  if (saved.empty()) {
    fmt::print("no frame where the sky test skips what the black-sky test ran\ncsv: {}\n", csv.string());
    return;
  }
  const Row& at = *saved.back();  // the deepest twilight where the sky hid what the old test drew
  scene::Scene s = scene_at(at.t_s);
  s.camera.exposure = at.exposure;
  std::vector<double> skipped, ran;
  renderer.render(s, dome, discard);  // untimed: programs, the catalogue's epoch
  always.render(s, dome, discard);
  for (int round = 0; round < w.rounds; ++round)
    for (int i = 0; i < w.iterations; ++i) {
      auto start = Clock::now();
      renderer.render(s, dome, discard);
      skipped.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
      start = Clock::now();
      always.render(s, dome, discard);
      ran.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    }
  // The test's own CPU time, from a frame with the passes timed (after one untimed).
  render::RenderOptions timed_options = tested;
  timed_options.time_passes = true;
  render::Renderer timed(timed_options, tables);
  timed.render(s, dome, discard);
  timed.render(s, dome, discard);
  const auto& ms = timed.last_frame().pass_ms;
  const double test_ms = ms.contains("star test") ? ms.at("star test") : 0.0;
  fmt::print("the test itself: {:.2f} ms CPU\n", test_ms);
  const double a = median(skipped), b = median(ran);
  fmt::print(
      "at t {:.1f} s (sun {:.2f}°, exposure {:.4g}): {:.1f} ms with the sky test (skipped), {:.1f} ms with "
      "the stars forced ({} placed): {:.1f} ms saved ({:.1f} %), medians of {}\n",
      at.t_s, at.sun_altitude_deg, at.exposure, a, b, always.last_frame().night_sky.stars, b - a, 100.0 * (b - a) / b,
      skipped.size());
  timing << '"' << device << "\"," << w.dome_px << ','
         << fmt::format("{:.2f},{:.3f},{:.6g},{:.3f},{:.3f},{:.3f},{:.2f},{},{:.3f},{}", at.t_s, at.sun_altitude_deg,
                        at.exposure, a, b, b - a, 100.0 * (b - a) / b, always.last_frame().night_sky.stars, test_ms,
                        skipped.size())
         << '\n';
  fmt::print("csv: {}, {}\n", csv.string(), times.string());
}

}  // namespace zenith::bench
