// Frame time of the renderer against resolution and number of atmospheres, in
// the layout of the paper's Table 2 (Costa et al., section 6, "Average
// performance of our method relative to the number of visible atmospheres").
//
// The scene is configs/scenes/three-worlds.json: Earth, Mars and Titan side by
// side, each with its atmosphere, all in view of a 16:9 planar camera (90°
// horizontal field) and of a 180° dome master. Every case renders the same
// three bodies and the same pixels; only the work differs:
//
//   bodies only    RenderOptions::atmospheres = false: G-buffer, resolve, readback
//   N atmospheres  the first N bodies keep their atmosphere, the others have none
//
// at each resolution: 1280×720 and 1920×1080 planar 90°, 4096² and 8192²
// fisheye 180° (square sizes are dome masters, the others planar views).
//
// Timing. A frame is timed by the wall clock around Renderer::render(); the
// renderer reads every band back (glGetTexImage), which waits for the GPU, so
// the time is the whole frame: passes, readback and conversion to RGB rows.
// Before a case's first timed frame the renderer has rendered the same
// projection once (its tile cones are computed once per projection) and holds
// every table set (loaded from the cache, or precomputed and stored, before
// the first case). A case renders up to --iterations frames, stopping early
// when the next frame would take it past --budget-s. With --rounds R the whole
// list of cases runs R times, so that a burst of load from other processes
// spreads over the cases instead of spoiling one. A case reports the median of
// all its frames and the fastest one (on a shared machine, the frame least
// disturbed by other processes). A frame during which the renderer had to
// fetch tables is not counted.
//
// Google Benchmark drives the cases (filter them with --benchmark_filter=, get
// its reports with --benchmark_out=); each case is one benchmark "iteration"
// running its own frame loop (frames take seconds on a CPU rasterizer), whose
// median is reported as the manual time. At the end the program prints the
// table in the paper's layout and writes CSV, one row per case:
//
//   device, resolution, projection, atmospheres (0: bodies only), frame_ms (median),
//   mpixel_per_s (all width × height pixels, a fisheye's corners included),
//   tiles_covered (16×16 tiles the atmosphere passes ran on, summed over the
//   atmospheres), tiles_total (tiles in the frame), frames (timed), frame_ms_min
//
// and, with gnuplot installed, a PNG chart next to it (same name, .png).
//
//   render_bench [--quick] [--tables paper|small] [--orders N] [--sizes WxH[,WxH...]]
//                [--iterations N] [--rounds R] [--budget-s S] [--csv FILE] [--no-chart] [--chart-only]
//                [--scene FILE] [--fov DEG] [--time-passes] [--moving] [--sky-view-error] [--no-sky-view]
//                [--gbuffer-path] [--general-tiles]
//                [--cache DIR]
//                [--device auto|software|hardware]
//                [--benchmark_filter=REGEX] ...
//   render_bench --present ...   the live frame that stays on the GPU (bench/present_bench.h)
//
// The ground view of docs/rendering-performance.md:
//   render_bench --scene configs/scenes/earth-ground-view.json --sizes 1280x720 --fov 79
// and the ratio against another build from one interleaved run: scripts/bench-compare.
//
// Results for docs/rendering-performance.md: bench/results/render_frame_times.csv.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/lut/table_cache.h"
#include "bench/bench_tables.h"
#include "bench/command_line.h"
#include "bench/moving_camera.h"
#include "bench/present_bench.h"
#include "bench/process_cpu.h"
#include "bench/star_frames.h"
#include "bench/star_placement.h"
#include "bench/star_twilight.h"
#include "render/gl/egl_context.h"
#include "render/gl/software_rasterizer.h"
#include "render/lut/gpu_precompute.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"
#include "warp/viewport_config.h"

namespace {

using namespace zenith;
using Clock = std::chrono::steady_clock;

constexpr double kPlanarFovDeg = 90.0;    // horizontal field of the planar views (default; --fov)
constexpr double kFisheyeFovDeg = 180.0;  // the dome masters
constexpr int kTile = 16;                 // render::kTileSize: tiles of the atmosphere passes

// ---- command line

struct Options {
  bool quick = false, chart = true, chart_only = false, time_passes = false, sky_view_error = false, moving = false;
  bool gbuffer_path = false;
  bool no_sky_view = false;
  bool general_tiles = false;
  double planar_fov_deg = kPlanarFovDeg;
  std::string tables = "paper", device = "auto";
  int orders = atmosphere::lut::kDefaultScatteringOrders, iterations = 3, rounds = 3;
  double budget_s = 120.0;
  std::vector<std::pair<int, int>> sizes;  // empty: the defaults (see default_sizes)
  std::filesystem::path csv = std::filesystem::path(ZENITH_SOURCE_DIR) / "bench/results/render_frame_times.csv";
  std::filesystem::path scene = std::filesystem::path(ZENITH_SOURCE_DIR) / "configs/scenes/three-worlds.json";
  std::optional<std::filesystem::path> cache;
  std::optional<double> stars;  // --stars LIMIT: the night sky's pass (bench/star_frames.h)
  bool moonlight = false;       // --moonlight: the Moon's light of the atmosphere passes (the same)
  bool star_time_given = false;
  bench::StarTiming star_timing;
  bool star_placement = false;        // --stars-placement: with --stars-show, the placement's parts
  bench::StarTwilight star_twilight;  // --stars-show SHOW: the test through a show's twilight (bench/star_twilight.h)
  /// Per-projector mode: render every output of this viewport config (its own
  /// projection, warp and size) and report each one's frame time and peak memory.
  std::optional<std::filesystem::path> viewport;
  std::filesystem::path viewport_csv =
      std::filesystem::path(ZENITH_SOURCE_DIR) / "bench/results/projector_frame_times.csv";
};

constexpr const char* kUsage =
    "usage: render_bench [--quick] [--tables paper|small] [--orders N] [--sizes WxH[,WxH...]]\n"
    "                    [--iterations N] [--rounds R] [--budget-s S] [--csv FILE] [--no-chart] [--chart-only]\n"
    "                    [--scene FILE] [--fov DEG] [--time-passes] [--moving] [--sky-view-error] [--no-sky-view] "
    "[--gbuffer-path] [--general-tiles]\n"
    "                    [--cache DIR]\n"
    "                    [--device auto|software|hardware]\n"
    "                    [Google Benchmark flags, e.g. --benchmark_filter=planar]\n"
    "  --quick        only the planar 1280x720 and 1920x1080 cases (a smoke run)\n"
    "  --tables       lookup-table sizes: paper (default) or small\n"
    "  --orders       scattering orders of the tables (default 8)\n"
    "  --sizes        replace the resolutions; square sizes are 180 deg dome masters,\n"
    "                 the others planar views with a 90 deg horizontal field\n"
    "  --iterations   timed frames per case and round, at most (default 3)\n"
    "  --rounds       run every case this many times, interleaved (default 3); the median and\n"
    "                 the fastest of all their frames are reported\n"
    "  --budget-s     stop a case's frames when the next would exceed this many seconds (default 120)\n"
    "  --stars LIMIT  the night sky's pass instead: frames with and without the catalogue's stars to V LIMIT\n"
    "                 (8.7: ~100 000) at night and in the scene's day (bench/star_frames.h); with\n"
    "                 --stars-time ISO (UTC), --stars-exposure X, --stars-csv FILE\n"
    "                 (default bench/results/star_frame_times.csv); the ground view:\n"
    "                 --scene configs/scenes/earth-ground-view.json --sizes 1280x720 --fov 79 --stars 8.7\n"
    "  --stars-show SHOW  with --stars: where the pass's test lets the stars run through the show's\n"
    "                 twilight and what skipping them saves (bench/star_twilight.h), on a fisheye dome\n"
    "                 master of --stars-dome N pixels (default 1024), every --stars-step S show seconds\n"
    "                 (default 2); --stars-csv (default bench/results/star_twilight_skip.csv)\n"
    "  --stars-placement  with --stars-show: the star test's and the placement's CPU time through the show\n"
    "                 and the placement's parts at its last frame (bench/star_placement.h), every\n"
    "                 --stars-step S show seconds; --stars-csv (default bench/results/star_placement.csv)\n"
    "  --moonlight    the Moon's light of the atmosphere passes instead: frames with and without it at a full\n"
    "                 Moon (--stars-time, default 2026-01-03T20:00:00Z) and by day, --stars-exposure, --stars-csv\n"
    "                 (default bench/results/moonlight_frame_times.csv)\n"
    "  --csv          output CSV (default bench/results/render_frame_times.csv in the source tree)\n"
    "  --no-chart     no gnuplot script and PNG next to the CSV\n"
    "  --chart-only   render nothing: redraw the chart of an existing --csv (same --quick/--sizes)\n"
    "  --scene        scene file (default configs/scenes/three-worlds.json)\n"
    "  --fov          horizontal field of the planar views in degrees (default 90); the ground view:\n"
    "                 --scene configs/scenes/earth-ground-view.json --sizes 1280x720 --fov 79\n"
    "  --time-passes  time every pass of each case's last frame (glFinish-bracketed) and print the split\n"
    "  --moving       the camera and the sun turn by 1 µrad every frame (bench/moving_camera.h): no frame\n"
    "                 reuses the tile classification or sky-view tables of the one before, as in a show\n"
    "                 whose camera and clock run\n"
    "  --sky-view-error  also render each size with all atmospheres without the sky-view table (4D\n"
    "                 lookups per pixel) and print the relative difference of the two images\n"
    "  --no-sky-view  the one-pass tiles read the 4D tables per pixel instead of the sky-view table\n"
    "  --gbuffer-path every tile through the G-buffer, atmosphere and resolve passes, 4D lookups per\n"
    "                 pixel (the frame's structure before the sky-view table; with --time-passes: its split)\n"
    "  --general-tiles  each shell's one-pass tiles with its general program, as a cold start draws\n"
    "                 them until their kinds' own are built (RenderOptions::tile_programs)\n"
    "  --cache        table cache directory (default $ZENITH_CACHE_DIR, $XDG_CACHE_HOME/zenith, ~/.cache/zenith)\n"
    "  --device       GL device: auto (default), software (llvmpipe), hardware\n"
    "  --viewport     also time every output of a viewport config (configs/viewports/), with all\n"
    "                 atmospheres: per-projector frame time and peak memory\n"
    "  --viewport-csv its CSV (default bench/results/projector_frame_times.csv)\n"
    "render_bench --present ...: the live frame that stays on the GPU (render_bench --present --help)\n";

std::pair<int, int> parse_size(const std::string& text) {
  // By hand: GCC 12 warns falsely inside <regex> under the sanitizer build (-Werror).
  const auto x = text.find_first_of("xX");
  auto digits = [](const std::string& d) {
    return !d.empty() && d.size() <= 5 && d.find_first_not_of("0123456789") == std::string::npos;
  };
  if (x == std::string::npos || !digits(text.substr(0, x)) || !digits(text.substr(x + 1)))
    throw std::invalid_argument(fmt::format("--sizes '{}': expected WIDTHxHEIGHT, e.g. 1920x1080", text));
  const int w = std::stoi(text.substr(0, x)), h = std::stoi(text.substr(x + 1));
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw std::invalid_argument(fmt::format("--sizes '{}': width and height must be in [1, 16384]", text));
  return {w, h};
}

Options parse_options(int argc, char** argv) {
  Options o;
  auto value = [&](int& i, const std::string& flag) -> std::string {
    if (i + 1 >= argc) throw std::invalid_argument(flag + ": a value is missing");
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      o.quick = true;
    else if (a == "--no-chart")
      o.chart = false;
    else if (a == "--chart-only")
      o.chart_only = true;
    else if (a == "--tables") {
      o.tables = value(i, a);
      if (o.tables != "paper" && o.tables != "small")
        throw std::invalid_argument("--tables '" + o.tables + "': use paper or small");
    } else if (a == "--orders") {
      o.orders = std::stoi(value(i, a));
      if (o.orders < 1 || o.orders > 50) throw std::invalid_argument("--orders: must be in [1, 50]");
    } else if (a == "--iterations") {
      o.iterations = std::stoi(value(i, a));
      if (o.iterations < 1 || o.iterations > 1000) throw std::invalid_argument("--iterations: must be in [1, 1000]");
    } else if (a == "--rounds") {
      o.rounds = std::stoi(value(i, a));
      if (o.rounds < 1 || o.rounds > 100) throw std::invalid_argument("--rounds: must be in [1, 100]");
    } else if (a == "--budget-s") {
      o.budget_s = std::stod(value(i, a));
      if (!(o.budget_s >= 0.0)) throw std::invalid_argument("--budget-s: must be >= 0");
    } else if (a == "--sizes") {
      std::stringstream list(value(i, a));
      for (std::string item; std::getline(list, item, ',');) o.sizes.push_back(parse_size(item));
      if (o.sizes.empty()) throw std::invalid_argument("--sizes: give at least one WIDTHxHEIGHT");
    } else if (a == "--csv")
      o.csv = value(i, a);
    else if (a == "--scene")
      o.scene = value(i, a);
    else if (a == "--time-passes")
      o.time_passes = true;
    else if (a == "--moving")
      o.moving = true;
    else if (a == "--sky-view-error")
      o.sky_view_error = true;
    else if (a == "--gbuffer-path")
      o.gbuffer_path = true;
    else if (a == "--no-sky-view")
      o.no_sky_view = true;
    else if (a == "--general-tiles")
      o.general_tiles = true;
    else if (a == "--fov") {
      o.planar_fov_deg = std::stod(value(i, a));
      if (!(o.planar_fov_deg > 0.0 && o.planar_fov_deg < 180.0))
        throw std::invalid_argument("--fov: must be in (0, 180)");
    } else if (a == "--cache")
      o.cache = value(i, a);
    else if (a == "--moonlight")
      o.moonlight = true;
    else if (a == "--stars") {
      o.stars = std::stod(value(i, a));
      if (!(*o.stars >= -2.0 && *o.stars <= 10.5))
        throw std::invalid_argument("--stars: V limit must be in [-2, 10.5]");
    } else if (a == "--stars-time") {
      o.star_timing.time_utc = value(i, a);
      o.star_time_given = true;
    } else if (a == "--stars-exposure") {
      o.star_timing.exposure = std::stod(value(i, a));
      if (!(o.star_timing.exposure > 0.0 && o.star_timing.exposure <= 1e6))
        throw std::invalid_argument("--stars-exposure: must be in (0, 1e6]");
    } else if (a == "--stars-csv")
      o.star_timing.csv = value(i, a);
    else if (a == "--stars-show")
      o.star_twilight.show = value(i, a);
    else if (a == "--stars-placement")
      o.star_placement = true;
    else if (a == "--stars-dome") {
      o.star_twilight.dome_px = std::stoi(value(i, a));
      if (!(o.star_twilight.dome_px >= 16 && o.star_twilight.dome_px <= 8192))
        throw std::invalid_argument("--stars-dome: must be in [16, 8192]");
    } else if (a == "--stars-step") {
      o.star_twilight.step_s = std::stod(value(i, a));
      if (!(o.star_twilight.step_s > 0.0)) throw std::invalid_argument("--stars-step: must be > 0");
    } else if (a == "--device")
      o.device = value(i, a);
    else if (a == "--viewport")
      o.viewport = value(i, a);
    else if (a == "--viewport-csv")
      o.viewport_csv = value(i, a);
    else
      bench::help_or_unknown_option(a, kUsage);
  }
  return o;
}

// ---- cases

/// One output format: its size and the projection it implies.
struct Resolution {
  int width = 0, height = 0;
  bool fisheye = false;
  double planar_fov_deg = kPlanarFovDeg;
  std::string label() const { return fmt::format("{}x{}", width, height); }
  std::string projection() const {
    return fisheye ? fmt::format("fisheye {:g}deg", kFisheyeFovDeg) : fmt::format("planar {:g}deg", planar_fov_deg);
  }
  std::unique_ptr<warp::Projection> make() const {
    if (!fisheye)
      return std::make_unique<warp::PlanarProjection>(warp::PlanarProjection::symmetric(width, height, planar_fov_deg));
    warp::FisheyeParameters p;
    p.fov_deg = kFisheyeFovDeg;
    return std::make_unique<warp::FisheyeProjection>(width, height, p);
  }
};

Resolution resolution_of(std::pair<int, int> size, double planar_fov_deg = kPlanarFovDeg) {
  return {size.first, size.second, size.first == size.second, planar_fov_deg};
}

std::vector<Resolution> resolutions(const Options& o) {
  std::vector<std::pair<int, int>> sizes = o.sizes;
  if (sizes.empty()) {
    sizes = {{1280, 720}, {1920, 1080}};
    if (!o.quick) sizes.insert(sizes.end(), {{4096, 4096}, {8192, 8192}});
  }
  std::vector<Resolution> out;
  for (auto s : sizes) out.push_back(resolution_of(s, o.planar_fov_deg));
  return out;
}

/// The measured figures of one case (a CSV row).
struct Result {
  Resolution resolution;
  int atmospheres = 0;       // 0: bodies only
  double frame_s = 0.0;      // median
  double frame_min_s = 0.0;  // fastest frame: the least disturbed by other processes
  int frames = 0;
  std::size_t tiles_covered = 0, tiles_total = 0;
  double peak_memory_mb = 0.0;  // largest over the case's rounds (process peak during its frames)
  double cpu_s = 0.0;           // median CPU time of the process per frame (all threads: llvmpipe's too)
};

/// Resets the process's peak resident set size (Linux: /proc/self/clear_refs "5").
void reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}

/// Peak resident set size since the last reset [MB] (VmHWM of /proc/self/status; 0 if unknown).
/// On a CPU rasterizer the GPU's images live in this process, so it is the frame's whole footprint.
double peak_memory_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  return 0.0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// `scene` with only its first `count` atmospheres (in body order); the bodies
/// beyond keep their place, size and albedo.
scene::Scene with_atmospheres(const scene::Scene& scene, int count) {
  scene::Scene out = scene;
  int kept = 0;
  for (scene::Body& b : out.bodies)
    if (b.atmosphere && kept++ >= count) b.atmosphere.reset();
  return out;
}

int atmosphere_count(const scene::Scene& scene) {
  return static_cast<int>(std::count_if(scene.bodies.begin(), scene.bodies.end(),
                                        [](const scene::Body& b) { return b.atmosphere.has_value(); }));
}

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void write_csv(const std::filesystem::path& path, const std::string& device, const std::vector<Result>& results) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream csv(path);
  if (!csv) throw std::runtime_error("cannot write " + path.string());
  csv << "device,resolution,projection,atmospheres,frame_ms,mpixel_per_s,tiles_covered,tiles_total,frames,"
         "frame_ms_min,peak_memory_mb,cpu_ms\n";
  for (const Result& r : results) {
    const double pixels = double(r.resolution.width) * double(r.resolution.height);
    csv << csv_field(device) << ',' << r.resolution.label() << ',' << r.resolution.projection() << ',' << r.atmospheres
        << ',' << fmt::format("{:.3f}", r.frame_s * 1e3) << ',' << fmt::format("{:.3f}", pixels / r.frame_s / 1e6)
        << ',' << r.tiles_covered << ',' << r.tiles_total << ',' << r.frames << ','
        << fmt::format("{:.3f}", r.frame_min_s * 1e3) << ',' << fmt::format("{:.0f}", r.peak_memory_mb) << ','
        << fmt::format("{:.3f}", r.cpu_s * 1e3) << '\n';
  }
  if (!csv.flush()) throw std::runtime_error("cannot write " + path.string());
}

/// Frame time against the number of atmospheres, one line per resolution.
void write_chart(const std::filesystem::path& csv, const std::vector<Resolution>& res, const std::string& device) {
  std::filesystem::path gp = csv, png = csv;
  gp.replace_extension(".gp");
  png.replace_extension(".png");
  std::ofstream s(gp);
  s << "set terminal pngcairo size 900,600\nset output '" << png.string() << "'\n"
    << "set datafile separator ','\nset logscale y\nset grid\nset key top left\n"
    << "set xlabel 'atmospheres (0: bodies only)'\nset xtics 1\n"
    << "set ylabel 'frame time [ms] (solid: median, dashed: fastest frame)'\n"
    << "set title \"zenith renderer, three-worlds scene: " << device << "\" noenhanced\n"
    << "plot ";
  // Solid: the median frame; dashed: the fastest one.
  for (std::size_t i = 0; i < res.size(); ++i) {
    const std::string select = fmt::format("'{}' using (strcol(2) eq '{}' ? $4 : 1/0):", csv.string(), res[i].label());
    s << (i ? ", \\\n     " : "") << select << "5 with linespoints pt 7 lc " << i + 1 << " title '" << res[i].label()
      << ' ' << res[i].projection() << "', \\\n     " << select << "10 with linespoints dt 2 pt 6 lc " << i + 1
      << " notitle";
  }
  s << '\n';
  s.close();
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0 &&
      std::system(("gnuplot '" + gp.string() + "'").c_str()) == 0)
    fmt::print("chart: {}\n", png.string());
  else
    fmt::print("gnuplot not found or failed: chart script left in {}\n", gp.string());
}

/// The paper's layout: a row per resolution, a column per case, frame time in
/// ms (the median, or with `fastest` the fastest frame).
enum class Figure { median, fastest, cpu };

void print_table(const std::vector<Resolution>& res, int max_atmospheres, const std::vector<Result>& results,
                 Figure figure) {
  std::string head = fmt::format("{:<24}{:>14}", "resolution", "bodies only");
  for (int n = 1; n <= max_atmospheres; ++n) head += fmt::format("{:>14}", fmt::format("{} ATM", n));
  fmt::print("\n{}\n{}\n",
             figure == Figure::median    ? "frame time [ms], median"
             : figure == Figure::fastest ? "frame time [ms], fastest frame"
                                         : "CPU time of the process per frame [ms] (all threads), median",
             head);
  for (const Resolution& r : res) {
    std::string line = fmt::format("{:<24}", r.label() + " " + r.projection());
    for (int n = 0; n <= max_atmospheres; ++n) {
      auto it = std::find_if(results.begin(), results.end(), [&](const Result& x) {
        return x.atmospheres == n && x.resolution.width == r.width && x.resolution.height == r.height;
      });
      line += it == results.end() ? fmt::format("{:>14}", "-")
                                  : fmt::format("{:>14.1f}", (figure == Figure::median    ? it->frame_s
                                                              : figure == Figure::fastest ? it->frame_min_s
                                                                                          : it->cpu_s) *
                                                                 1e3);
    }
    fmt::print("{}\n", line);
  }
}

/// Per-projector frame time and peak memory for every output of a viewport
/// config (all the scene's atmospheres), e.g. the six projectors of a dome.
void time_projectors(const Options& opt, const std::string& device, const scene::Scene& scene,
                     render::Renderer& renderer) {
  const warp::ViewportConfig config = warp::load_viewport_config(*opt.viewport);
  const render::RowSink discard = [](int, int, std::span<const float>) {};
  if (opt.viewport_csv.has_parent_path()) std::filesystem::create_directories(opt.viewport_csv.parent_path());
  std::ofstream csv(opt.viewport_csv);
  if (!csv) throw std::runtime_error("cannot write " + opt.viewport_csv.string());
  csv << "device,viewports,output,size,projection,frame_ms,frame_ms_min,peak_memory_mb,frames\n";
  fmt::print("\nper projector ({}, scene '{}'):\n{:<10} {:>11} {:>10} {:>10} {:>9}  projection\n", config.name,
             scene.name, "output", "size", "median ms", "min ms", "peak MB");
  for (const warp::OutputConfig& out : config.outputs) {
    renderer.render(scene, *out.projection, discard);  // tile cones, ray tables: once per projection
    reset_peak_memory();
    std::vector<double> times;
    for (int i = 0; i < opt.iterations * opt.rounds; ++i) {
      const auto start = Clock::now();
      renderer.render(scene, *out.projection, discard);
      times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    const double peak = peak_memory_mb(), med = median(times), fastest = *std::min_element(times.begin(), times.end());
    const std::string size = fmt::format("{}x{}", out.width_px, out.height_px);
    fmt::print("{:<10} {:>11} {:>10.1f} {:>10.1f} {:>9.0f}  {}\n", out.name, size, med * 1e3, fastest * 1e3, peak,
               out.projection->describe());
    csv << csv_field(device) << ',' << csv_field(config.name) << ',' << csv_field(out.name) << ',' << size << ','
        << csv_field(out.projection->describe()) << ','
        << fmt::format("{:.3f},{:.3f},{:.0f}", med * 1e3, fastest * 1e3, peak) << ',' << times.size() << '\n';
  }
  fmt::print("csv: {}\n", opt.viewport_csv.string());
}

/// The sky-view table's difference from the 4D lookups per pixel (the frame
/// with all atmospheres both ways, no sun disc): per value |a − b| / max(b, 1e-3 · brightest),
/// RMS, 99th percentile and largest, as tests/render/renderer_test.cpp measures it.
void print_sky_view_error(const std::vector<Resolution>& res, const scene::Scene& scene,
                          const render::RenderOptions& options, const render::TableSource& tables) {
  render::RenderOptions off = options;
  off.time_passes = false;
  off.sun_disc = false;  // the sky and the ground alone: the disc would set the floor below
  off.sky_view_table = render::SkyViewTableUse::off;
  render::RenderOptions on = off;
  on.sky_view_table = render::SkyViewTableUse::always;
  render::Renderer with_table(on, tables), direct(off, tables);
  fmt::print("\nsky-view table against the 4D lookups per pixel (scene '{}', all atmospheres, no sun disc):\n",
             scene.name);
  for (const Resolution& r : res) {
    const auto projection = r.make();
    const std::vector<float> a = with_table.render_image(scene, *projection),
                             b = direct.render_image(scene, *projection);
    std::size_t table_tiles = 0;
    for (const auto& at : with_table.last_frame().atmospheres) table_tiles += at.sky_view_tiles;
    const float brightest = *std::max_element(b.begin(), b.end());
    const double floor = 1e-3 * std::max(double(brightest), 1e-30);
    std::vector<double> e(b.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      e[i] = std::abs(double(a[i]) - double(b[i])) / std::max(double(b[i]), floor);
      sum += e[i] * e[i];
    }
    std::sort(e.begin(), e.end());
    fmt::print("  {:<24} {} sky-view tiles; relative difference RMS {:.5f}, 99th percentile {:.5f}, max {:.4f}\n",
               r.label() + " " + r.projection(), table_tiles,
               std::sqrt(sum / double(std::max<std::size_t>(e.size(), 1))), e.empty() ? 0.0 : e[e.size() * 99 / 100],
               e.empty() ? 0.0 : e.back());
  }
}

int run(int argc, char** argv) {
  const Options opt = parse_options(argc, argv);
  const std::vector<Resolution> res = resolutions(opt);
  if (opt.chart_only) {
    // The device is the first field of the first row: "llvmpipe (...)",...
    std::ifstream in(opt.csv);
    std::string header, row;
    if (!std::getline(in, header) || !std::getline(in, row) || row.size() < 2 || row[0] != '"')
      throw std::runtime_error(opt.csv.string() + ": not a render_bench CSV with at least one row");
    write_chart(opt.csv, res, row.substr(1, row.find('"', 1) - 1));
    return 0;
  }

  render::gl::ContextOptions context_options;
  context_options.prefer = render::gl::parse_device_preference(opt.device);
  const render::gl::HeadlessContext context(context_options);
  const std::string device = context.renderer();
  benchmark::AddCustomContext("gl_renderer", device);
  if (context.is_software())  // gl/software_rasterizer.h
    benchmark::AddCustomContext("llvmpipe_threads", render::gl::default_software_rasterizer_threads());
  benchmark::AddCustomContext("tables", fmt::format("{} sizes, {} orders", opt.tables, opt.orders));

  const scene::Scene scene = scene::load_scene(opt.scene);
  const int max_atm = atmosphere_count(scene);
  std::vector<scene::Scene> variants;  // index: number of atmospheres kept
  for (int n = 0; n <= max_atm; ++n) variants.push_back(with_atmospheres(scene, n));
  fmt::print("render_bench: scene '{}' ({} bodies, {} atmospheres) on {}\n", scene.name, scene.bodies.size(), max_atm,
             device);

  // Tables as the `zenith` command obtains them: the cache, else the GPU
  // precompute on a context of its own (stored for the next run).
  atmosphere::lut::PrecomputeOptions table_options;
  table_options.sizes = opt.tables == "small" ? atmosphere::lut::TableSizes::small() : atmosphere::lut::TableSizes{};
  table_options.max_orders = opt.orders;
  const atmosphere::lut::TableCache cache(opt.cache.value_or(atmosphere::lut::default_cache_directory()));
  const render::TableSource tables = bench::cached_or_precomputed_tables(
      cache, table_options, opt.tables, context_options, [&] { context.make_current(); });

  render::RenderOptions atm_options, body_options;
  body_options.atmospheres = false;
  atm_options.time_passes = body_options.time_passes = opt.time_passes;
  if (opt.gbuffer_path) {
    atm_options.one_pass_tiles = body_options.one_pass_tiles = false;
    atm_options.sky_view_table = body_options.sky_view_table = render::SkyViewTableUse::off;
  }
  if (opt.no_sky_view) atm_options.sky_view_table = body_options.sky_view_table = render::SkyViewTableUse::off;
  if (opt.general_tiles) atm_options.tile_programs = render::TilePrograms::general;
  if (opt.star_placement) {
    if (!opt.stars || opt.star_twilight.show.empty())
      throw std::invalid_argument("--stars-placement needs --stars LIMIT and --stars-show SHOW");
    bench::StarTwilight p = opt.star_twilight;
    p.magnitude_limit = *opt.stars;
    p.rounds = opt.rounds;
    p.iterations = opt.iterations;
    p.csv = opt.star_timing.csv.empty() ? std::filesystem::path(ZENITH_SOURCE_DIR) / "bench/results/star_placement.csv"
                                        : opt.star_timing.csv;
    bench::time_star_placement(p, device, tables);
    return 0;
  }
  if (opt.stars && !opt.star_twilight.show.empty()) {
    bench::StarTwilight w = opt.star_twilight;
    w.magnitude_limit = *opt.stars;
    w.rounds = opt.rounds;
    w.iterations = opt.iterations;
    w.csv = opt.star_timing.csv.empty()
                ? std::filesystem::path(ZENITH_SOURCE_DIR) / "bench/results/star_twilight_skip.csv"
                : opt.star_timing.csv;
    bench::sweep_star_twilight(w, device, tables);
    return 0;
  }
  if (opt.stars || opt.moonlight) {
    bench::StarTiming t = opt.star_timing;
    t.moonlight = opt.moonlight;
    if (opt.stars) t.magnitude_limit = *opt.stars;
    if (t.moonlight && !opt.star_time_given) t.time_utc = "2026-01-03T20:00:00Z";
    t.rounds = opt.rounds;
    t.iterations = opt.iterations;
    t.sizes = opt.sizes;
    t.fov_deg = opt.planar_fov_deg;
    if (t.csv.empty())
      t.csv = std::filesystem::path(ZENITH_SOURCE_DIR) /
              (t.moonlight ? "bench/results/moonlight_frame_times.csv" : "bench/results/star_frame_times.csv");
    bench::time_stars(t, device, scene, tables);
    return 0;
  }
  render::Renderer with_atmospheres_renderer(atm_options, tables), bodies_renderer(body_options, tables);
  const render::RowSink discard = [](int, int, std::span<const float>) {};

  // Every table set resident before the first case (a small view of the whole scene).
  {
    const auto start = Clock::now();
    with_atmospheres_renderer.render(scene, *resolution_of({64, 36}).make(), discard);
    fmt::print("{} table sets resident after {:.1f} s\n", with_atmospheres_renderer.last_frame().table_sets_uploaded,
               std::chrono::duration<double>(Clock::now() - start).count());
  }

  // Frames of every case, gathered over the rounds; a case is (resolution, atmospheres).
  struct Gathered {
    std::vector<double> times, cpu_times;
    render::FrameStats stats;
    double peak_memory_mb = 0.0;
  };
  std::map<std::pair<std::size_t, int>, Gathered> gathered;
  bool failed = false;
  std::vector<std::unique_ptr<warp::Projection>> projections;
  for (const Resolution& r : res) projections.push_back(r.make());
  std::set<std::tuple<const render::Renderer*, const warp::Projection*, int>> warmed;  // cases drawn once untimed

  for (int round = 0; round < opt.rounds; ++round)
    for (std::size_t ri = 0; ri < res.size(); ++ri)
      for (int n = 0; n <= max_atm; ++n) {
        std::string name = fmt::format("render/{}_{}/{}", res[ri].fisheye ? "fisheye" : "planar", res[ri].label(),
                                       n == 0 ? std::string("bodies_only") : fmt::format("atmospheres:{}", n));
        if (opt.rounds > 1) name += fmt::format("/round:{}", round + 1);
        auto* b = benchmark::RegisterBenchmark(name.c_str(), [&, ri, n, name](benchmark::State& state) {
          render::Renderer& renderer = n == 0 ? bodies_renderer : with_atmospheres_renderer;
          const warp::Projection& projection = *projections[ri];
          scene::Scene s = variants[static_cast<std::size_t>(n)];
          if (warmed.insert({&renderer, &projection, n}).second) {
            // One untimed frame of the case: tile cones of the new projection, albedo
            // maps, and the shader variants its tiles need (compiled on first use).
            renderer.render(s, projection, discard);
          }
          std::vector<double> times, cpu_times;
          render::FrameStats stats;
          reset_peak_memory();
          for (auto _ : state) {
            double spent = 0.0;
            for (int attempt = 0; static_cast<int>(times.size()) < opt.iterations && attempt < opt.iterations + 3;
                 ++attempt) {
              if (opt.moving) bench::move_camera_and_sun(s, variants[static_cast<std::size_t>(n)], attempt);
              const auto start = Clock::now();
              const double cpu_start = bench::process_cpu_s();
              renderer.render(s, projection, discard);
              const double t = std::chrono::duration<double>(Clock::now() - start).count();
              const double cpu = bench::process_cpu_s() - cpu_start;
              if (renderer.last_frame().table_sets_requested > 0) continue;  // fetched tables: not a steady frame
              times.push_back(t);
              cpu_times.push_back(cpu);
              stats = renderer.last_frame();
              spent += t;
              if (spent + t > opt.budget_s) break;
            }
            if (times.empty()) {
              state.SkipWithError("no steady frame (tables fetched in every frame)");
              failed = true;
              return;
            }
            state.SetIterationTime(median(times));
          }
          std::size_t tiles = 0;
          for (const auto& a : stats.atmospheres) tiles += a.tiles;
          state.counters["frames"] = static_cast<double>(times.size());
          state.counters["min_ms"] = *std::min_element(times.begin(), times.end()) * 1e3;
          state.counters["Mpix/s"] = double(projection.width()) * double(projection.height()) / median(times) / 1e6;
          state.counters["atm_tiles"] = static_cast<double>(tiles);
          state.counters["cpu_ms"] = median(cpu_times) * 1e3;
          if (opt.time_passes) {
            std::string split;
            for (const auto& [pass, ms] : stats.pass_ms) split += fmt::format("  {} {:.1f}", pass, ms);
            fmt::print(
                "{}: last frame {:.1f} ms; per pass [ms]:{}; tiles: {} one atmosphere, {} G-buffer path, "
                "{} direct light, {} black\n",
                name, stats.seconds * 1e3, split, stats.tiles_one_atmosphere, stats.tiles_gbuffer, stats.tiles_direct,
                stats.tiles_black);
          }
          Gathered& g = gathered[{ri, n}];
          g.peak_memory_mb = std::max(g.peak_memory_mb, peak_memory_mb());
          g.times.insert(g.times.end(), times.begin(), times.end());
          g.cpu_times.insert(g.cpu_times.end(), cpu_times.begin(), cpu_times.end());
          g.stats = stats;
        });
        b->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
      }

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();

  std::vector<Result> results;
  for (const auto& [key, g] : gathered) {
    const Resolution& r = res[key.first];
    Result out{r,
               key.second,
               median(g.times),
               *std::min_element(g.times.begin(), g.times.end()),
               static_cast<int>(g.times.size()),
               0,
               static_cast<std::size_t>((r.width + kTile - 1) / kTile) *
                   static_cast<std::size_t>((r.height + kTile - 1) / kTile)};
    for (const auto& a : g.stats.atmospheres) out.tiles_covered += a.tiles;
    out.peak_memory_mb = g.peak_memory_mb;
    out.cpu_s = median(g.cpu_times);
    results.push_back(out);
  }
  if (results.empty()) {
    fmt::print(stderr, "render_bench: no case ran (check --benchmark_filter)\n");
    return 1;
  }

  print_table(res, max_atm, results, Figure::median);
  print_table(res, max_atm, results, Figure::fastest);
  print_table(res, max_atm, results, Figure::cpu);
  write_csv(opt.csv, device, results);
  fmt::print("csv: {}\n", opt.csv.string());
  if (opt.chart) write_chart(opt.csv, res, device);
  if (opt.viewport) time_projectors(opt, device, scene, with_atmospheres_renderer);
  if (opt.sky_view_error) print_sky_view_error(res, scene, atm_options, tables);
  return failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--present") {  // the live frame (bench/present_bench.h): its own options
      try {
        return zenith::bench::run_present(argc, argv);
      } catch (const std::exception& e) {
        fmt::print(stderr, "render_bench --present: {}\n(render_bench --present --help lists the options)\n", e.what());
        return 2;
      }
    }
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") {
      fmt::print("{}\nGoogle Benchmark's flags:\n", kUsage);
      std::fflush(stdout);
      break;  // benchmark::Initialize prints its flags and exits
    }
  benchmark::Initialize(&argc, argv);  // takes the --benchmark_* flags out of argv
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "render_bench: {}\n(render_bench --help lists the options)\n", e.what());
    return 2;
  }
}
