// Run time against error of the lookup tables, and the Pareto front.
//
// For each method and setting (table sizes, scattering orders, quadrature and
// number of samples along rays, sphere-integral nodes, CPU or GPU precompute)
// this program measures, per atmosphere (earth-advanced, mars):
//
//   precompute_s    wall time of the precompute (GPU: on a headless EGL context
//                   of its own, shader compilation included; CPU: all threads)
//   frame_ms        median wall time of --frames frames of a --frame-size²
//                   fisheye dome master (180°) of a ground scene with those
//                   tables (configs/scenes/earth-ground-noon.json,
//                   mars-ground-day.json; constant albedo), readback included;
//                   the frames of all settings interleaved (bench/lut_frame_timer.h)
//   rms / max       relative error of table-based sky radiance against the
//                   reference solver over the fixed geometries and view
//                   directions of tests/data/reference_*.csv (noon, low sun,
//                   twilight, limb from orbit; 400 000 paths per wavelength and
//                   direction, standard errors ~0.1-3%), after discounting twice
//                   the reference's standard error: e = max(0, |L − L_ref| − 2σ) / L_ref;
//                   pooled over the four cases, and per case (rms_noon, max_noon, ...)
//
// and, over the atmospheres together (preset "all": mean precompute and frame
// time, RMS pooled over every direction and wavelength, largest max), the
// Pareto front for cost = precompute time and for cost = frame time: a setting
// is on the front when no other has both a lower cost and a lower RMS error.
// The recommended default is the cheapest setting (precompute time) whose RMS
// error is within --tolerance (1.2) × the best; it is compared with the
// project's default (paper sizes, 6 orders with the series tail, log-linear, 50 ray samples, 24
// sphere nodes, GPU: apps/table_provider.cpp, atmosphere/lut/precompute_options.h).
//
// Output in --out (default bench/results/ of the source tree):
//   lut_accuracy.csv        one row per setting and atmosphere (and "all")
//   lut_accuracy.png        precompute time against RMS error per atmosphere
//   pareto_precompute.png   "all": precompute time against RMS error, front, pick
//   pareto_frame.png        "all": frame time against RMS error, front
// (gnuplot scripts and data next to them; PNG only with gnuplot installed).
//
//   lut_accuracy_bench [--quick | --smoke] [--no-gpu] [--presets LIST] [--out DIR]
//                      [--frame-size PX] [--frames N] [--no-frames] [--tolerance X]
//                      [--max-rms X] [--no-chart] [--list] [--only TEXT]
//
// --quick: tiny and small tables and the project default (~4 min on 2 cores); --smoke (CTest):
// three tiny settings on Earth, 64² frames. --only: the settings whose label contains TEXT
// (e.g. --only "paper 8 orders GPU" for the project default, "paper 4 orders" for the 4-order variants).
// Settings marked "direct density" compute the scattering density by the
// per-texel sphere sum of the method before spherical harmonics. Exit 1 on any non-finite radiance
// or pixel, or (with --max-rms) any setting's pooled RMS error above the bound.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/parameters.h"
#include "atmosphere/sky_sampling.h"
#include "bench/command_line.h"
#include "bench/lut_frame_timer.h"
#include "bench/pareto.h"
#include "render/gl/egl_context.h"
#include "render/lut/gpu_precompute.h"

using namespace zenith::atmosphere;
namespace fs = std::filesystem;

namespace {

constexpr const char* kUsage =
    "usage: lut_accuracy_bench [--quick | --smoke] [--no-gpu] [--presets LIST] [--out DIR]\n"
    "                          [--frame-size PX] [--frames N] [--no-frames] [--tolerance X]\n"
    "                          [--max-rms X] [--no-chart] [--list] [--only TEXT]\n"
    "  --quick        tiny and small tables, and the project default (a few minutes)\n"
    "  --smoke        three tiny settings, Earth only, 64x64 frames (the CTest smoke run)\n"
    "  --no-gpu       CPU precompute only (frame times need a GL context: then none)\n"
    "  --presets      atmospheres with reference fixtures (default earth-advanced,mars)\n"
    "  --out          output folder (default bench/results in the source tree)\n"
    "  --frame-size   fisheye dome master of PX x PX for the frame time (default 512)\n"
    "  --frames       timed frames per setting, median reported (default 5)\n"
    "  --no-frames    no frame times\n"
    "  --tolerance    recommended: the cheapest setting with RMS <= X * the best RMS (default 1.2)\n"
    "  --max-rms      fail (exit 1) when a setting's pooled RMS error exceeds X\n"
    "  --no-chart     no gnuplot scripts and PNG\n"
    "  --list         print the settings (with the other options) and exit\n"
    "  --only         only the settings whose label contains TEXT\n";

struct Options {
  bool quick = false, smoke = false, gpu = true, frames = true, chart = true, list = false;
  std::vector<std::string> presets = {"earth-advanced", "mars"};
  fs::path out = fs::path(ZENITH_SOURCE_DIR) / "bench/results";
  int frame_size_px = 512, frame_count = 5;
  double tolerance = 1.2;
  std::optional<double> max_rms;
  std::string only;     ///< --only: a substring of the labels to run
  std::string command;  ///< as run, for the outputs
};

Options parse_options(int argc, char** argv) {
  Options o;
  o.command = "lut_accuracy_bench";
  auto value = [&](int& i, const std::string& flag) -> std::string {
    if (i + 1 >= argc) throw std::invalid_argument(fmt::format("{}: a value is missing", flag));
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      o.quick = true;
    else if (a == "--smoke")
      o.smoke = true;
    else if (a == "--no-gpu")
      o.gpu = false;
    else if (a == "--no-frames")
      o.frames = false;
    else if (a == "--no-chart")
      o.chart = false;
    else if (a == "--list")
      o.list = true;
    else if (a == "--out")
      o.out = value(i, a);
    else if (a == "--only")
      o.only = value(i, a);
    else if (a == "--presets") {
      o.presets.clear();
      std::stringstream list(value(i, a));
      for (std::string item; std::getline(list, item, ',');)
        if (!item.empty()) o.presets.push_back(item);
      if (o.presets.empty()) throw std::invalid_argument("--presets: give at least one");
    } else if (a == "--frame-size") {
      o.frame_size_px = std::stoi(value(i, a));
      if (o.frame_size_px < 16 || o.frame_size_px > 8192)
        throw std::invalid_argument("--frame-size: must be in [16, 8192]");
    } else if (a == "--frames") {
      o.frame_count = std::stoi(value(i, a));
      if (o.frame_count < 1 || o.frame_count > 1000) throw std::invalid_argument("--frames: must be in [1, 1000]");
    } else if (a == "--tolerance") {
      o.tolerance = std::stod(value(i, a));
      if (!(o.tolerance >= 1.0)) throw std::invalid_argument("--tolerance: must be >= 1");
    } else if (a == "--max-rms") {
      o.max_rms = std::stod(value(i, a));
      if (!(*o.max_rms > 0.0)) throw std::invalid_argument("--max-rms: must be > 0");
    } else
      zenith::bench::help_or_unknown_option(a, kUsage);
    if (a != "--out") o.command = fmt::format("{} {}", o.command, a);
    if (a == "--presets" || a == "--frame-size" || a == "--frames" || a == "--tolerance" || a == "--max-rms")
      o.command = fmt::format("{} {}", o.command, argv[i]);
  }
  if (o.smoke) {
    o.presets = {"earth-advanced"};
    o.frame_size_px = std::min(o.frame_size_px, 64);
    o.frame_count = std::min(o.frame_count, 2);
  }
  return o;
}

// ---- the reference fixtures

struct Case {
  std::string preset, name;
  SkyGeometry geometry;
  std::vector<ViewDirection> directions;
  std::vector<std::vector<double>> reference, standard_error;
};

Case read_case(const std::string& preset, const std::string& name, std::size_t channels) {
  const fs::path file = fs::path(ZENITH_SOURCE_DIR) / "tests/data" / fmt::format("reference_{}_{}.csv", preset, name);
  std::ifstream in(file);
  if (!in)
    throw std::runtime_error(
        fmt::format("missing reference fixture {} (scripts/make-reference-fixtures)", file.string()));
  Case c{preset, name, {}, {}, {}, {}};
  std::string line;
  std::getline(in,
               line);  // "# scripts/make-reference-fixtures: zenith sample ... --altitude-m A --sun-zenith-deg Z ..."
  auto arg = [&](const std::string& flag) {
    const std::size_t at = line.find(fmt::format("{} ", flag));
    if (at == std::string::npos)
      throw std::runtime_error(fmt::format("{}: no {} in its first line", file.string(), flag));
    return std::stod(line.substr(at + flag.size() + 1));
  };
  c.geometry.altitude_m = arg("--altitude-m");
  c.geometry.sun_zenith_deg = arg("--sun-zenith-deg");
  std::getline(in, line);  // column names
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    ViewDirection d{};
    s >> d.zenith_deg >> d.azimuth_deg;
    std::vector<double> v;
    for (double x; s >> x;) v.push_back(x);
    if (v.size() < 2 * channels) throw std::runtime_error(fmt::format("{}: a row has too few columns", file.string()));
    c.directions.push_back(d);
    c.reference.emplace_back(v.begin(), v.begin() + static_cast<long>(channels));
    c.standard_error.emplace_back(v.end() - static_cast<long>(channels), v.end());
  }
  return c;
}

// ---- settings

struct Setting {
  std::string label;
  std::string sizes_name;
  lut::PrecomputeOptions options;
  bool gpu = false;
  bool project_default = false;  ///< the settings `zenith` uses unless told otherwise
};

lut::TableSizes sizes_by_name(const std::string& name) {
  if (name == "tiny") return lut::TableSizes{64, 16, 32, 8, 8, 16, 16, 4};
  if (name == "small") return lut::TableSizes::small();
  if (name == "medium") return lut::TableSizes{128, 32, 64, 16, 16, 64, 32, 8};
  if (name == "paper") return lut::TableSizes{};
  // Paper sizes with twice the texels in one dimension of the scattering tables
  // (which resolution Mars' twilight needs: docs/lookup-tables.md, "Closing the series").
  if (name == "paper-mu-s-x2") return lut::TableSizes{256, 64, 64, 16, 32, 128, 64, 8};
  if (name == "paper-nu-x2") return lut::TableSizes{256, 64, 64, 16, 32, 128, 32, 16};
  throw std::invalid_argument(fmt::format("no table sizes named '{}'", name));
}

struct Variant {
  Variant(int orders_, bool trapezoid_ = false, int ray_samples_ = 50,
          int sphere_ = lut::PrecomputeOptions{}.sphere_zenith_samples, bool direct_ = false,
          int coarse_stride_ = lut::PrecomputeOptions{}.coarse_ray_stride)
      : orders(orders_),
        trapezoid(trapezoid_),
        ray_samples(ray_samples_),
        sphere(sphere_),
        direct_density(direct_),
        coarse_stride(coarse_stride_) {}
  int orders;
  bool trapezoid;
  int ray_samples;      ///< PrecomputeOptions::scattering_samples
  int sphere;           ///< PrecomputeOptions::sphere_zenith_samples
  bool direct_density;  ///< PrecomputeOptions::DensityMethod::Direct (else Harmonics)
  int coarse_stride;    ///< PrecomputeOptions::coarse_ray_stride
  bool series_tail = lut::PrecomputeOptions{}.series_tail;  ///< PrecomputeOptions::series_tail
  Variant without_tail() const {
    Variant v = *this;
    v.series_tail = false;
    return v;
  }
};

Setting make_setting(const std::string& sizes, const Variant& v, bool gpu) {
  Setting s;
  s.sizes_name = sizes;
  s.gpu = gpu;
  s.options.sizes = sizes_by_name(sizes);
  s.options.max_orders = v.orders;
  s.options.scattering_quadrature =
      v.trapezoid ? lut::PrecomputeOptions::Quadrature::Trapezoid : lut::PrecomputeOptions::Quadrature::LogLinear;
  s.options.scattering_samples = v.ray_samples;
  s.options.sphere_zenith_samples = v.sphere;
  s.options.coarse_ray_stride = v.coarse_stride;
  s.options.series_tail = v.series_tail;
  s.options.density_method = v.direct_density ? lut::PrecomputeOptions::DensityMethod::Direct
                                              : lut::PrecomputeOptions::DensityMethod::Harmonics;
  s.label = fmt::format("{} {} order{}", sizes, v.orders, v.orders == 1 ? "" : "s");
  if (v.trapezoid) s.label = fmt::format("{} trapezoid", s.label);
  if (v.ray_samples != 50) s.label = fmt::format("{} {} ray samples", s.label, v.ray_samples);
  const lut::PrecomputeOptions defaults;
  if (v.sphere != defaults.sphere_zenith_samples) s.label = fmt::format("{} sphere {}", s.label, v.sphere);
  if (v.direct_density) s.label = fmt::format("{} direct density", s.label);
  if (v.coarse_stride != defaults.coarse_ray_stride)
    s.label = fmt::format("{} coarse rays every {}", s.label, v.coarse_stride);
  if (v.series_tail != defaults.series_tail && v.orders >= 3)
    s.label = fmt::format("{} {}", s.label, v.series_tail ? "series tail" : "no tail");
  s.label = fmt::format("{} {}", s.label, gpu ? "GPU" : "CPU");
  s.project_default = gpu && sizes == "paper" && v.orders == defaults.max_orders && !v.trapezoid && !v.direct_density &&
                      v.ray_samples == defaults.scattering_samples && v.sphere == defaults.sphere_zenith_samples &&
                      v.coarse_stride == defaults.coarse_ray_stride && v.series_tail == defaults.series_tail;
  return s;
}

std::vector<Setting> settings_for(const Options& o) {
  std::vector<Setting> out;
  auto add = [&](const std::string& sizes, Variant v, bool gpu) {
    if (gpu && !o.gpu) return;
    Setting s = make_setting(sizes, v, gpu);
    if (s.label.find(o.only) == std::string::npos) return;
    out.push_back(std::move(s));
  };
  if (o.smoke) {
    add("tiny", {2}, false);
    add("tiny", {2}, true);
    add("small", {2}, true);
    return out;
  }
  // GPU: every dimension around small, medium and paper sizes.
  add("tiny", {4}, true);
  if (o.quick) add("tiny", {2}, true);
  add("small", {1}, true);
  add("small", {2}, true);
  add("small", {4}, true);
  add("small", {4, true}, true);
  add("small", {4, false, 50, 8}, true);
  if (o.quick) {
    add("paper", {lut::kDefaultScatteringOrders}, true);  // the project default, to compare the pick with
    add("tiny", {4}, false);
    add("small", {4}, false);
    return out;
  }
  add("small", {4, false, 25}, true);
  add("medium", {2}, true);
  add("medium", {4}, true);
  add("medium", {6}, true);
  add("medium", {4, false, 50, 8}, true);
  add("paper", {2}, true);
  add("paper", {4}, true);
  add("paper", {5}, true);
  add("paper", {6}, true);
  add("paper", {8}, true);
  if (lut::kDefaultScatteringOrders != 5 && lut::kDefaultScatteringOrders != 6 && lut::kDefaultScatteringOrders != 8)
    add("paper", {lut::kDefaultScatteringOrders}, true);
  // The orders after the last dropped, as before the series tail.
  add("paper", Variant{4}.without_tail(), true);
  add("paper", Variant{8}.without_tail(), true);
  add("paper", Variant{16}.without_tail(), true);  // the series summed to 16 orders: what the tail stands for
  add("paper-mu-s-x2", {lut::kDefaultScatteringOrders}, true);
  add("paper-nu-x2", {lut::kDefaultScatteringOrders}, true);
  const int sphere = lut::PrecomputeOptions{}.sphere_zenith_samples;
  add("paper", {lut::kDefaultScatteringOrders, false, 50, sphere, false, 1}, true);  // every sample at every order
  add("paper", {4, false, 50, 8}, true);
  add("paper", {4, false, 50, 16}, true);
  add("paper", {4, false, 50, 32}, true);
  // The scattering density of the method before spherical harmonics: the per-texel sphere sum.
  add("small", {4, false, 50, sphere, true}, true);
  add("paper", {4, false, 50, sphere, true}, true);
  // CPU: the same tables (same errors) at other precompute times.
  add("small", {4}, false);
  add("medium", {4}, false);
  return out;
}

/// The scene of the frame-time measurement for an atmosphere with reference fixtures.
fs::path frame_scene_for(const std::string& preset) {
  const fs::path scenes = fs::path(ZENITH_SOURCE_DIR) / "configs/scenes";
  if (preset.rfind("earth", 0) == 0) return scenes / "earth-ground-noon.json";
  if (preset == "mars") return scenes / "mars-ground-day.json";
  throw std::invalid_argument(fmt::format("no frame-time scene for '{}'", preset));
}

// ---- measurements

constexpr const char* kCases[] = {"noon", "low_sun", "twilight", "orbit_limb"};

struct Row {
  std::size_t setting = 0;
  std::string preset;
  std::string device;
  double precompute_s = NAN, frame_ms = NAN, frame_ms_min = NAN;
  double rms = NAN, max = NAN, table_mb = 0.0;
  std::vector<std::pair<double, double>> case_rms_max;  ///< per case of kCases
  double sum_squares = 0.0;                             ///< of the relative errors, for pooling
  std::size_t values = 0;                               ///< compared
  std::size_t nonfinite = 0;                            ///< NaN/Inf radiances from the tables + pixels of the frame
  std::size_t frame_index = SIZE_MAX;                   ///< in the atmosphere's LutFrameTimer
  bool front_precompute = false, front_frame = false, recommended = false;
};

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  q += '"';
  return q;
}

std::string number(double v, const char* format = "{:.6g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string();
}

/// Marks the Pareto fronts and the recommended setting among `rows` (one group).
/// The frame-time front counts GPU settings only: a CPU setting makes the same
/// tables as its GPU twin, so its frames are the same work (and its frame time
/// differs only by noise).
void mark_fronts(std::vector<Row*>& rows, const std::vector<Setting>& settings, double tolerance) {
  std::vector<zenith::bench::CostError> by_precompute, by_frame;
  for (const Row* r : rows) {
    by_precompute.push_back({r->precompute_s, r->rms});
    by_frame.push_back({settings[r->setting].gpu ? r->frame_ms : NAN, r->rms});
  }
  const auto fp = zenith::bench::pareto_front(by_precompute), ff = zenith::bench::pareto_front(by_frame);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i]->front_precompute = fp[i];
    rows[i]->front_frame = ff[i];
  }
  if (auto pick = zenith::bench::cheapest_within(by_precompute, tolerance)) rows[*pick]->recommended = true;
}

int run(const Options& opt) {
  const std::vector<Setting> settings = settings_for(opt);
  if (opt.list) {
    for (const Setting& s : settings)
      fmt::print("{:<36} {}{}\n", s.label, s.options.sizes.describe(), s.project_default ? "  (project default)" : "");
    return 0;
  }
  fs::create_directories(opt.out);

  // The frames' context (also names the GL device of the GPU precompute).
  std::optional<zenith::render::gl::HeadlessContext> context;
  std::string gl_renderer = "none";
  if (opt.gpu) {
    try {
      context.emplace();
      gl_renderer = context->renderer();
    } catch (const std::exception& e) {
      fmt::print(stderr, "no GL context ({}): no frame times, the GPU settings will fail\n", e.what());
    }
  }
  const bool frames = opt.frames && context.has_value();
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  fmt::print("lut_accuracy_bench: {} settings x {} atmospheres; GL: {}; CPU precompute: {} threads; frames: {}\n",
             settings.size(), opt.presets.size(), gl_renderer, threads,
             frames ? fmt::format("{0}x{0} fisheye 180deg, median of {1}", opt.frame_size_px, opt.frame_count)
                    : std::string("off"));

  std::vector<Row> rows;
  for (const std::string& preset : opt.presets) {
    const AtmosphereModel model = load_preset(preset).model;
    std::vector<Case> cases;
    for (const char* name : kCases) cases.push_back(read_case(preset, name, model.wavelength_count()));
    std::optional<zenith::bench::LutFrameTimer> timer;
    if (frames) {
      timer.emplace(frame_scene_for(preset), opt.frame_size_px);
      if (lookup_table_hash(timer->model()) != lookup_table_hash(model))
        throw std::runtime_error(
            fmt::format("the frame-time scene's atmosphere is not the preset '{}' as loaded here "
                        "(other wavelengths?)",
                        preset));
    }
    for (std::size_t si = 0; si < settings.size(); ++si) {
      const Setting& s = settings[si];
      Row row;
      row.setting = si;
      row.preset = preset;
      lut::PrecomputeReport report;
      const auto start = std::chrono::steady_clock::now();
      lut::LookupTables tables;
      try {
        // GPU: a context of its own per precompute (its creation and the shader
        // compilation are part of the cost), as `zenith precompute` does.
        tables = s.gpu ? zenith::render::precompute_tables_gpu(model, s.options, &report)
                       : lut::precompute_tables_cpu(model, s.options, &report);
      } catch (const std::exception& e) {
        fmt::print(stderr, "{} ({}): {}\n", s.label, preset, e.what());
        continue;
      }
      row.precompute_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      row.device =
          report.device.empty() ? (s.gpu ? gl_renderer : fmt::format("CPU ({} threads)", threads)) : report.device;

      double worst = 0.0;
      {
        const lut::TableQueries q(model, tables);  // holds a reference: gone before the tables move
        for (const Case& c : cases) {
          double case_sum_squares = 0.0, case_worst = 0.0;
          std::size_t case_values = 0;
          const auto values = sample_radiance(q, c.geometry, c.directions);
          for (std::size_t i = 0; i < values.size(); ++i)
            for (std::size_t ch = 0; ch < model.wavelength_count(); ++ch) {
              const double v = values[i].radiance[ch], ref = c.reference[i][ch];
              if (!std::isfinite(v)) {  // std::max below would hide a NaN
                ++row.nonfinite;
                continue;
              }
              const double err = std::max(0.0, std::abs(v - ref) - 2.0 * c.standard_error[i][ch]) / ref;
              row.sum_squares += err * err;
              worst = std::max(worst, err);
              ++row.values;
              case_sum_squares += err * err;
              case_worst = std::max(case_worst, err);
              ++case_values;
            }
          row.case_rms_max.emplace_back(case_values > 0 ? std::sqrt(case_sum_squares / double(case_values)) : NAN,
                                        case_worst);
        }
      }
      row.rms = row.values > 0 ? std::sqrt(row.sum_squares / double(row.values)) : NAN;
      row.max = worst;
      row.table_mb =
          4.0 *
          double(tables.transmittance.data.size() + tables.irradiance.data.size() + 3 * tables.multiple.data.size()) /
          1e6;      // as float32, 3 scattering tables
      if (timer) {  // its untimed frame now, the timed ones below with the other settings'
        context->make_current();
        std::size_t nonfinite_pixels = 0;
        row.frame_index = timer->add(std::move(tables), &nonfinite_pixels);
        row.nonfinite += nonfinite_pixels;
      }
      std::string per_case;
      for (std::size_t ci = 0; ci < row.case_rms_max.size(); ++ci)
        per_case +=
            fmt::format("  {} {:.4f}/{:.3f}", kCases[ci], row.case_rms_max[ci].first, row.case_rms_max[ci].second);
      fmt::print("{:<36} {:<15} precompute {:8.2f} s   RMS {:.4f}   max {:.4f}{}   (RMS/max:{})\n", s.label, preset,
                 row.precompute_s, row.rms, row.max,
                 row.nonfinite ? fmt::format("  {} NON-FINITE", row.nonfinite) : std::string(), per_case);
      std::fflush(stdout);
      rows.push_back(row);
    }
    if (timer) {
      fmt::print("timing {} frames of each setting ({}), interleaved\n", opt.frame_count, preset);
      const std::vector<zenith::bench::FrameTiming> timings = timer->time_all(opt.frame_count);
      for (Row& r : rows)
        if (r.preset == preset && r.frame_index < timings.size()) {
          r.frame_ms = timings[r.frame_index].median_ms;
          r.frame_ms_min = timings[r.frame_index].min_ms;
        }
    }
  }

  fmt::print("\n{:<36} {:<15} {:>12} {:>10} {:>10} {:>10} {:>9}\n", "setting", "atmosphere", "precompute s", "frame ms",
             "RMS err", "max err", "tables MB");
  for (const Row& r : rows)
    fmt::print("{:<36} {:<15} {:>12.2f} {:>10.1f} {:>10.4f} {:>10.4f} {:>9.1f}\n", settings[r.setting].label, r.preset,
               r.precompute_s, r.frame_ms, r.rms, r.max, r.table_mb);

  // "all": every atmosphere together, for the settings measured on each.
  std::vector<Row> pooled;
  for (std::size_t si = 0; si < settings.size(); ++si) {
    std::vector<const Row*> parts;
    for (const Row& r : rows)
      if (r.setting == si) parts.push_back(&r);
    if (parts.size() != opt.presets.size()) continue;
    Row all;
    all.setting = si;
    all.preset = "all";
    all.device = parts.front()->device;
    all.precompute_s = all.frame_ms = all.frame_ms_min = all.max = all.table_mb = 0.0;
    for (const Row* p : parts) {
      all.precompute_s += p->precompute_s / double(parts.size());
      all.frame_ms += p->frame_ms / double(parts.size());
      all.frame_ms_min += p->frame_ms_min / double(parts.size());
      all.max = std::max(all.max, p->max);
      all.table_mb += p->table_mb / double(parts.size());
      all.sum_squares += p->sum_squares;
      all.values += p->values;
      all.nonfinite += p->nonfinite;
    }
    all.rms = all.values > 0 ? std::sqrt(all.sum_squares / double(all.values)) : NAN;
    pooled.push_back(all);
  }
  rows.insert(rows.end(), pooled.begin(), pooled.end());

  std::map<std::string, std::vector<Row*>> groups;
  for (Row& r : rows) groups[r.preset].push_back(&r);
  for (auto& [preset, group] : groups) mark_fronts(group, settings, opt.tolerance);

  // CSV: the first six columns as before this file had fronts and frames.
  const fs::path csv_path = opt.out / "lut_accuracy.csv";
  {
    std::ofstream csv(csv_path);
    csv << "setting,preset,precompute_s,rms_relative_error,max_relative_error,table_MB,frame_ms,frame_ms_min,"
           "backend,device,sizes,table_sizes,orders,quadrature,ray_samples,sphere_samples,nonfinite,"
           "pareto_precompute,pareto_frame,recommended,project_default,frame_size_px,tolerance,density";
    for (const char* c : kCases) csv << ",rms_" << c << ",max_" << c;
    csv << '\n';
    for (const Row& r : rows) {
      const Setting& s = settings[r.setting];
      csv << csv_field(s.label) << ',' << r.preset << ',' << number(r.precompute_s) << ',' << number(r.rms) << ','
          << number(r.max) << ',' << number(r.table_mb, "{:.2f}") << ',' << number(r.frame_ms, "{:.3f}") << ','
          << number(r.frame_ms_min, "{:.3f}") << ',' << (s.gpu ? "GPU" : "CPU") << ',' << csv_field(r.device) << ','
          << s.sizes_name << ',' << csv_field(s.options.sizes.describe()) << ',' << s.options.max_orders << ','
          << (s.options.scattering_quadrature == lut::PrecomputeOptions::Quadrature::LogLinear ? "log-linear"
                                                                                               : "trapezoid")
          << ',' << s.options.scattering_samples << ',' << s.options.sphere_zenith_samples << ',' << r.nonfinite << ','
          << int(r.front_precompute) << ',' << int(r.front_frame) << ',' << int(r.recommended) << ','
          << int(s.project_default) << ',' << (frames ? opt.frame_size_px : 0) << ',' << opt.tolerance << ','
          << (settings[r.setting].label.find("direct density") != std::string::npos ? "direct" : "harmonics");
      for (std::size_t ci = 0; ci < std::size(kCases); ++ci) {
        if (ci < r.case_rms_max.size())
          csv << ',' << number(r.case_rms_max[ci].first) << ',' << number(r.case_rms_max[ci].second);
        else
          csv << ",,";  // "all": pooled over atmospheres, no per-case split
      }
      csv << '\n';
    }
    if (!csv.flush()) throw std::runtime_error(fmt::format("cannot write {}", csv_path.string()));
  }

  // The recommendation, against the project's default.
  const std::vector<Row*>& all = groups.count("all") ? groups["all"] : groups[opt.presets.front()];
  const Row* pick = nullptr;
  const Row* project = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const Row* r : all) {
    if (r->recommended) pick = r;
    if (settings[r->setting].project_default) project = r;
    if (std::isfinite(r->rms)) best = std::min(best, r->rms);
  }
  fmt::print("\nPareto front ({}; cost = precompute time):", all.empty() ? "-" : all.front()->preset);
  for (const Row* r : all)
    if (r->front_precompute) fmt::print(" [{}]", settings[r->setting].label);
  fmt::print("\nPareto front (cost = frame time, GPU settings):");
  for (const Row* r : all)
    if (r->front_frame) fmt::print(" [{}]", settings[r->setting].label);
  fmt::print("\n");
  auto describe = [&](const Row* r) {
    return fmt::format("{}: RMS {:.4f}, max {:.3f}, precompute {:.1f} s, frame {:.1f} ms", settings[r->setting].label,
                       r->rms, r->max, r->precompute_s, r->frame_ms);
  };
  if (pick)
    fmt::print("recommended default (cheapest precompute with RMS <= {:.2g} x the best, {:.4f}): {}\n", opt.tolerance,
               best, describe(pick));
  if (project)
    fmt::print("project default (paper sizes, {} orders, log-linear, 50 ray samples, sphere 16, GPU): {}{}\n",
               lut::kDefaultScatteringOrders, describe(project), pick == project ? " (the same)" : "");
  else
    fmt::print("project default (paper sizes, {} orders, GPU): not measured in this run\n",
               lut::kDefaultScatteringOrders);

  if (opt.chart) {
    const std::string machine = fmt::format("GL: {}; CPU: {} threads", gl_renderer, threads);
    std::vector<zenith::bench::ChartPoint> by_precompute, by_frame;
    std::optional<std::size_t> pick_index;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Row* r = all[i];
      by_precompute.push_back({{r->precompute_s, r->rms}, settings[r->setting].label, r->front_precompute});
      if (settings[r->setting].gpu)
        by_frame.push_back({{r->frame_ms, r->rms}, settings[r->setting].label, r->front_frame});
      if (r->recommended) pick_index = i;
    }
    std::string presets = opt.presets.front();
    for (std::size_t i = 1; i < opt.presets.size(); ++i) presets = fmt::format("{} + {}", presets, opt.presets[i]);
    const std::string scope = opt.presets.size() > 1 ? fmt::format("{} (mean cost, pooled RMS)", presets) : presets;
    bool drawn = zenith::bench::write_pareto_chart(
        opt.out / "pareto_precompute.png", by_precompute, pick_index,
        {fmt::format("zenith lookup tables: precompute time against error, {}", scope),
         fmt::format("{}; {}", machine, opt.command), "precompute time [s]",
         "RMS relative error of sky radiance vs the reference solver"});
    if (frames)
      drawn = zenith::bench::write_pareto_chart(
                  opt.out / "pareto_frame.png", by_frame, std::nullopt,
                  {fmt::format("zenith lookup tables: frame time against error, {}", scope),
                   fmt::format("{0}x{0} fisheye dome master, median of {1} frames; {2}; {3}", opt.frame_size_px,
                               opt.frame_count, machine, opt.command),
                   "frame time [ms]", "RMS relative error of sky radiance vs the reference solver"}) &&
              drawn;

    // Per atmosphere: precompute time against RMS error (the chart this program always drew).
    std::ofstream gp(opt.out / "lut_accuracy.gp");
    gp << "set terminal pngcairo size 900,600\nset output '" << (opt.out / "lut_accuracy.png").string() << "'\n"
       << "set termoption noenhanced\nset datafile separator ','\nset logscale x\nset xlabel 'precompute time [s]'\n"
       << "set ylabel 'RMS relative error of sky radiance vs reference'\nset grid\nset key top right\n"
       << "set title 'zenith lookup tables: run time against error (" << machine << ")'\n"
       << "plot '" << csv_path.string() << "' using (strcol(2) eq '" << opt.presets.front()
       << "' ? $3 : 1/0):4:(strcol(1)) with labels point pt 7 offset 1,0.5 left font ',7' title '"
       << opt.presets.front() << "'";
    for (std::size_t i = 1; i < opt.presets.size(); ++i)
      gp << ", \\\n     '' using (strcol(2) eq '" << opt.presets[i] << "' ? $3 : 1/0):4 with points pt " << 4 + i
         << " title '" << opt.presets[i] << "'";
    gp << '\n';
    gp.close();
    drawn = std::system(fmt::format("gnuplot '{}' 2>/dev/null", (opt.out / "lut_accuracy.gp").string()).c_str()) == 0 &&
            drawn;
    if (drawn)
      fmt::print("charts: {}, pareto_precompute.png{}\n", (opt.out / "lut_accuracy.png").string(),
                 frames ? ", pareto_frame.png" : "");
    else
      fmt::print("gnuplot not found or failed: chart scripts (.gp) left in {}\n", opt.out.string());
  }
  fmt::print("csv: {}\n", csv_path.string());

  // Bounds (CTest smoke run and CI): no NaN/Inf anywhere, RMS within --max-rms.
  int failures = 0;
  for (const Row& r : rows) {
    if (r.preset == "all") continue;
    const std::string& label = settings[r.setting].label;
    if (r.nonfinite > 0) {
      fmt::print(stderr, "FAIL {} ({}): {} non-finite values\n", label, r.preset, r.nonfinite);
      ++failures;
    }
    if (opt.max_rms && !(r.rms <= *opt.max_rms)) {
      fmt::print(stderr, "FAIL {} ({}): RMS relative error {:.4f} exceeds the bound {:.4f}\n", label, r.preset, r.rms,
                 *opt.max_rms);
      ++failures;
    }
  }
  if (rows.empty()) {
    fmt::print(stderr, "lut_accuracy_bench: no setting could be measured\n");
    return 1;
  }
  return failures > 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse_options(argc, argv));
  } catch (const std::exception& e) {
    fmt::print(stderr, "lut_accuracy_bench: {}\n(lut_accuracy_bench --help lists the options)\n", e.what());
    return 2;
  }
}
