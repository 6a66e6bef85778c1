#include "bench/star_placement.h"

#include <fmt/format.h>

#include <chrono>
#include <deque>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "astro/sky_positions.h"
#include "astro/star_catalogue.h"
#include "bench/star_frames.h"
#include "core/units.h"
#include "render/frame/frame_constants.h"
#include "render/frame/refraction_cache.h"
#include "render/night/star_pass.h"
#include "scene/frame_scene.h"
#include "show/show.h"
#include "warp/fisheye_projection.h"

namespace zenith::bench {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// One step of the placement timed over the stars that reach it.
struct Part {
  std::string name;
  std::size_t stars = 0;
  std::vector<double> ms;
};

}  // namespace

void time_star_placement(const StarTwilight& b, const std::string& device, const render::TableSource& tables) {
  const show::Show show = show::load_show(b.show);
  const auto scene_at = [&](double t) {
    scene::Scene s = show.scene();
    scene::apply_frame(show.state_at(t, 0, 0), s);
    return s;
  };
  const warp::FisheyeProjection dome(b.dome_px, b.dome_px);
  const render::RowSink discard = [](int, int, std::span<const float>) {};
  fmt::print("render_bench --stars-placement: '{}', a {}² dome master, stars to V {}, on {}\n", b.show.string(),
             b.dome_px, b.magnitude_limit, device);

  // ---- 1. The renderer's own figures through the show.
  render::RenderOptions options;
  options.night_sky.star_magnitude_limit = b.magnitude_limit;
  options.time_passes = true;
  render::Renderer renderer(options, tables);
  std::filesystem::path frames_csv = b.csv;
  frames_csv.replace_filename(b.csv.stem().string() + "_frames.csv");
  std::ofstream frames(frames_csv);
  if (!frames) throw std::runtime_error("cannot write " + frames_csv.string());
  frames << "device,dome_px,show_time_s,sun_altitude_deg,exposure,stars_run,stars_tested,stars_placed,star_test_ms,"
            "star_placement_ms\n";
  for (double t = 0.0; t <= show.duration_s() + 1e-9; t += b.step_s) {
    const scene::Scene s = scene_at(t);
    renderer.render(s, dome, discard);  // the first of each: the catalogue's epoch, neighbourhood tables
    renderer.render(s, dome, discard);
    const render::FrameStats& f = renderer.last_frame();
    const auto part = [&](const char* name) { return f.pass_ms.contains(name) ? f.pass_ms.at(name) : 0.0; };
    double sun_deg = 0.0;
    if (s.sky_clock) {
      const astro::SkyPositions sky(astro::AstroTime::from_utc(s.sky_clock->time), s.sky_clock->site);
      sun_deg = sky.sun().horizontal.altitude_rad / core::kDeg;
    }
    fmt::print(
        "  t {:4.1f} s: sun {:6.2f}°, exposure {:8.3g}: stars {} ({} tested one by one), star test {:6.2f} ms, "
        "placement {:6.2f} ms CPU, {} placed\n",
        t, sun_deg, s.camera.exposure, f.night_sky.star_test.could_show ? "run  " : "skipped",
        f.night_sky.star_test.stars_tested, part("star test"), part("star placement"), f.night_sky.stars);
    frames << '"' << device << "\"," << b.dome_px << ','
           << fmt::format("{:.2f},{:.3f},{:.6g},{},{},{},{:.3f},{:.3f}", t, sun_deg, s.camera.exposure,
                          int(f.night_sky.star_test.could_show), f.night_sky.star_test.stars_tested, f.night_sky.stars,
                          part("star test"), part("star placement"))
           << '\n';
  }

  // ---- 2. star_splats on its own at the show's last frame.
  const scene::Scene s = scene_at(show.duration_s());
  const render::FrameConstants constants =
      render::compute_frame_constants(s, render::FrameSky(s), dome, options.colour, options.limb_darkening,
                                      options.night_sky.moon, options.atmosphere.eclipses);
  std::deque<atmosphere::lut::LookupTables> luts;
  std::vector<render::StarAtmosphere> atmospheres;
  for (const scene::Body& body : s.bodies)
    if (body.atmosphere) {
      luts.push_back(tables(body.atmosphere->loaded.model));
      const atmosphere::AtmosphereModel& model = body.atmosphere->loaded.model;
      atmospheres.push_back({body.position_m, model.ground_radius_m, model.top_radius_m, &luts.back()});
    }
  render::RefractionCache refractions;
  render::StarFrame frame =
      render::star_frame(s, dome, constants.camera_to_world, atmospheres, constants.rgb_weights, refractions);
  astro::StarCatalogueOptions catalogue_options;
  catalogue_options.directory = options.night_sky.star_directory;
  catalogue_options.magnitude_limit = b.magnitude_limit;
  render::StarField field(astro::load_star_catalogue(catalogue_options), s.wavelengths_nm);
  const astro::AstroTime time = astro::AstroTime::from_utc(s.sky_clock->time);
  const astro::Site site = s.sky_clock->site;
  std::vector<glm::dvec3> enu;
  auto start = Clock::now();
  field.directions_enu(time, site, enu);
  const double epoch_ms = ms_since(start);
  const std::size_t n = field.wavelengths_nm().size();

  std::vector<Part> parts;
  for (const char* name :
       {"deviates of the interval (star test)", "turn (directions_enu)", "rejections (ground, view cone)", "refraction",
        "occluders", "projection (pixel, splat grid)", "transmittance", "pixel solid angle", "colour weights",
        "twinkle", "place_star, one thread", "star_splats, worker threads", "transmittance, star_transmittance",
        "pixel solid angle, rays", "twinkle, formula", "place_star, one thread, exact reads",
        "star_splats, worker threads, exact reads"})
    parts.push_back(Part{name, 0, {}});
  std::size_t placed = 0;
  for (int round = 0; round < b.rounds * b.iterations; ++round) {
    std::size_t p = 0;
    const auto timed = [&](std::size_t count, auto&& body) {
      const auto t0 = Clock::now();
      body();
      parts[p].ms.push_back(ms_since(t0));
      parts[p++].stars = count;
    };
    // The star test draws every star's deviate once per interval (the show's frames at 120× each a new one).
    if (frame.scintillation) field.largest_scintillation_normal(frame.scintillation_interval + round + 1);
    timed(field.size(), [&] {
      if (frame.scintillation) field.largest_scintillation_normal(frame.scintillation_interval);
    });
    frame.scintillation_normals =
        frame.scintillation ? field.scintillation_normals(frame.scintillation_interval) : nullptr;
    timed(field.size(), [&] { field.directions_enu(time, site, enu); });
    std::vector<std::size_t> kept;
    timed(enu.size(), [&] {
      for (std::size_t i = 0; i < enu.size(); ++i)
        if (!render::star_rejected(enu[i], frame)) kept.push_back(i);
    });
    std::vector<glm::dvec3> d(enu.size());
    timed(kept.size(), [&] {
      for (std::size_t i : kept) d[i] = render::star_apparent_direction(enu[i], frame);
    });
    std::vector<std::size_t> seen;
    timed(kept.size(), [&] {
      for (std::size_t i : kept)
        if (!render::star_hidden(d[i], frame)) seen.push_back(i);
    });
    std::vector<std::size_t> landed;
    std::vector<glm::dvec2> pixel(enu.size());
    timed(seen.size(), [&] {
      for (std::size_t i : seen)
        if (const auto at = render::star_pixel(d[i], frame)) {
          pixel[i] = *at;
          landed.push_back(i);
        }
    });
    std::vector<double> transmittance(enu.size() * n), scratch(n);
    timed(landed.size(), [&] {
      for (std::size_t i : landed)
        render::star_line_of_sight_transmittance(d[i], frame, &transmittance[i * n], scratch.data());
    });
    std::vector<double> omega(enu.size());
    timed(landed.size(), [&] {
      for (std::size_t i : landed)
        omega[i] = frame.closed_form_solid_angle ? dome.pixel_solid_angle_sr(pixel[i].x, pixel[i].y)
                                                 : dome.pixel_solid_angle_by_rays_sr(pixel[i].x, pixel[i].y);
    });
    std::vector<std::array<double, 3>> rgb(enu.size());
    timed(landed.size(), [&] {
      for (std::size_t i : landed) rgb[i] = render::star_colour(field, i, &transmittance[i * n], frame);
    });
    std::vector<double> twinkle(enu.size());
    timed(landed.size(), [&] {
      for (std::size_t i : landed) twinkle[i] = render::star_twinkle(i, d[i], frame);
    });
    std::vector<double> a(n), c(n);
    std::size_t count = 0;
    timed(enu.size(), [&] {
      for (std::size_t i = 0; i < enu.size(); ++i) count += render::place_star(field, i, enu[i], frame, a, c) ? 1 : 0;
    });
    std::vector<render::StarSplat> splats;
    timed(enu.size(), [&] { splats = render::star_splats(field, enu, frame); });
    placed = splats.size();
    if (count != placed) throw std::logic_error("place_star and star_splats placed different stars");
    // The same three steps and the whole placement with the exact reads (the frame without its tables).
    render::StarFrame exact = frame;
    exact.transmittances.clear();
    exact.closed_form_solid_angle = false;
    exact.twinkle_sigma.reset();
    exact.scintillation_normals = nullptr;
    timed(landed.size(), [&] {
      for (std::size_t i : landed)
        render::star_line_of_sight_transmittance(d[i], exact, &transmittance[i * n], scratch.data());
    });
    timed(landed.size(), [&] {
      for (std::size_t i : landed) omega[i] = dome.pixel_solid_angle_by_rays_sr(pixel[i].x, pixel[i].y);
    });
    timed(landed.size(), [&] {
      for (std::size_t i : landed) twinkle[i] = render::star_twinkle(i, d[i], exact);
    });
    timed(enu.size(), [&] {
      for (std::size_t i = 0; i < enu.size(); ++i) render::place_star(field, i, enu[i], exact, a, c);
    });
    timed(enu.size(), [&] { splats = render::star_splats(field, enu, exact); });
  }
  fmt::print(
      "the show's last frame (t {:.0f} s), {} stars, {} placed; the catalogue's ERFA epoch {:.1f} ms (once per "
      "6 h of sky time)\n",
      show.duration_s(), field.size(), placed, epoch_ms);
  std::ofstream csv(b.csv);
  if (!csv) throw std::runtime_error("cannot write " + b.csv.string());
  csv << "device,dome_px,stars,placed,part,stars_in,median_ms,ns_per_star,timings\n";
  double steps = 0.0;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const Part& part = parts[p];
    const double ms = median(part.ms);
    if (p >= 1 && p < 10) steps += ms;
    fmt::print("  {:32s} {:7d} stars {:8.2f} ms {:8.1f} ns/star\n", part.name, part.stars, ms,
               part.stars ? 1e6 * ms / static_cast<double>(part.stars) : 0.0);
    csv << '"' << device << "\"," << b.dome_px << ',' << field.size() << ',' << placed << ",\"" << part.name << "\","
        << part.stars << ',' << fmt::format("{:.3f},{:.1f}", ms, part.stars ? 1e6 * ms / double(part.stars) : 0.0)
        << ',' << part.ms.size() << '\n';
  }
  fmt::print(
      "  the steps together: {:.2f} ms on one thread (the last five rows: with the exact reads instead of the "
      "frame's tables)\ncsv: {}, {}\n",
      steps, b.csv.string(), frames_csv.string());
}

}  // namespace zenith::bench
