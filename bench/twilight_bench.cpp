// Zenith radiance through twilight, sun 0° to −18°, from the tables at named
// table sizes against the reference.
//
//   twilight_bench [--preset NAME] [--sizes SPEC[,SPEC...]] [--gpu] [--step-deg 0.25]
//                  [--reference-deg 0,-3,-6,-9,-12,-15,-18] [--reference lit-air|path-tracer]
//                  [--reference-csv FILE]
//                  [--samples N[,N...]] [--batches N] [--threads N] [--cache DIR | --no-cache]
//                  [--orders N] [--no-series-tail]
//                  [--out DIR] [--no-chart]
//
// Table sets (--sizes, default paper,twilight): each SPEC is a named set, its
// sizes and ray samples (docs/lookup-tables.md, "Named sizes";
// atmosphere::apply_table_set) optionally followed by overrides,
// NAME[:KEY=VALUE...], for experiments, e.g. paper:mu_s=64:samples=100 or
// twilight:mu_s=64:samples=50 (the twilight set before 2026-11-27):
//   scattering sizes     r, mu, mu_s, nu;  transmittance t_mu, t_r;  irradiance e_mu_s, e_r
//   precompute options   samples (scattering_samples), sphere (sphere_zenith_samples),
//                        degree (harmonic_degree), t_samples (transmittance_samples),
//                        stride (coarse_ray_stride), orders (max_orders)
// (atmosphere/lut/precompute_options.h). The spec names the set in the output.
// Each set comes from the cache (--cache DIR, default the table cache of every
// zenith command; the cache key holds the sizes and every option above, so no
// experiment reads another's tables), else it is precomputed (on the CPU, or
// with --gpu by the GL precompute on a headless context of its own: Mesa
// llvmpipe here, seconds instead of tens of minutes; the same tables) and
// stored there, with the precompute's time. --orders and --no-series-tail
// change every set's orders from the defaults.
// Then the zenith radiance L(h) seen from 1 m above the ground for sun
// elevations h from 0° down to −18° in --step-deg steps.
// Smoothness: the largest second difference of ln L between neighbouring steps
// (a step in the tables, where an order fades or a texel column ends, shows as
// a spike of |Δ² ln L|; a smooth exponential fall gives ~0), and whether L
// falls monotonically.
// Against the reference at each of --reference-deg: the relative error of each
// set, with the reference's standard error and z = error / standard error.
// The reference is the lit-air estimator (atmosphere/reference/lit_air_estimator.h,
// --samples paths, each estimating every wavelength, one count or one per
// elevation; order 1 by quadrature),
// which reaches the deep twilight, or the path tracer (--samples paths per
// wavelength), which finds the zenith below −10° only a handful of times.
// --reference-csv FILE reuses the reference values, standard errors and order-1
// parts of an earlier run's twilight_reference.csv instead of computing them
// (bench/results/twilight_reference_lit_air.csv holds each elevation's sharpest
// reference so far, its first line the commands that made them: about half an
// hour of runs); every --reference-deg and wavelength must be in it.
//
// Output (DIR = --out, default bench/results; files of presets other than
// earth-advanced carry the preset's name): DIR/twilight_zenith.csv (every
// step), DIR/twilight_reference.csv, DIR/twilight_zenith.png (gnuplot; with
// --no-chart only the data).
#include <fmt/format.h>
#include <fmt/os.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/table_cache.h"
#include "atmosphere/named_inputs.h"
#include "atmosphere/parameters.h"
#include "atmosphere/reference/lit_air_estimator.h"
#include "atmosphere/reference/path_tracer.h"
#include "bench/command_line.h"
#include "core/units.h"
#include "render/gl/egl_context.h"
#include "render/lut/gpu_precompute.h"

namespace {

using namespace zenith;
using namespace zenith::atmosphere;

std::size_t table_bytes(const lut::LookupTables& t) {
  return sizeof(float) * (t.transmittance.data.size() + t.irradiance.data.size() + t.single_rayleigh.data.size() +
                          t.single_mie.data.size() + t.multiple.data.size());
}

Vec3 sun_direction(double elevation_deg) {
  const double e = elevation_deg * core::kPi / 180.0;
  return Vec3{std::cos(e), 0.0, std::sin(e)};
}

/// A table set of --sizes: "NAME[:KEY=VALUE...]" (the header comment lists the
/// keys) applied to the named sizes and to `base` options.
lut::PrecomputeOptions options_for_spec(const std::string& spec, lut::PrecomputeOptions base) {
  std::stringstream in(spec);
  std::string name;
  std::getline(in, name, ':');
  apply_table_set(name, base);
  for (std::string item; std::getline(in, item, ':');) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--sizes " + spec + ": '" + item + "' is not KEY=VALUE");
    const std::string key = item.substr(0, eq);
    const std::size_t value = std::stoul(item.substr(eq + 1));
    const std::map<std::string, std::size_t*> sizes = {
        {"r", &base.sizes.scattering_r},         {"mu", &base.sizes.scattering_mu},
        {"mu_s", &base.sizes.scattering_mu_s},   {"nu", &base.sizes.scattering_nu},
        {"t_mu", &base.sizes.transmittance_mu},  {"t_r", &base.sizes.transmittance_r},
        {"e_mu_s", &base.sizes.irradiance_mu_s}, {"e_r", &base.sizes.irradiance_r}};
    const std::map<std::string, int*> options = {
        {"samples", &base.scattering_samples}, {"sphere", &base.sphere_zenith_samples},
        {"degree", &base.harmonic_degree},     {"t_samples", &base.transmittance_samples},
        {"stride", &base.coarse_ray_stride},   {"orders", &base.max_orders}};
    if (auto s = sizes.find(key); s != sizes.end())
      *s->second = value;
    else if (auto o = options.find(key); o != options.end())
      *o->second = int(value);
    else
      throw std::invalid_argument("--sizes " + spec + ": unknown key '" + key + "'");
  }
  base.sizes.check();
  lut::check_precompute_options(base);
  return base;
}

/// The tables of one set of --sizes: from the cache when it has them, else
/// precomputed (CPU, or GL with `gpu`) and stored there, with the precompute's
/// cost printed.
lut::LookupTables tables_for(const AtmosphereModel& model, const std::string& spec, lut::PrecomputeOptions options,
                             bool gpu, const std::optional<std::filesystem::path>& cache_directory) {
  options = options_for_spec(spec, options);
  std::optional<lut::TableCache> cache;
  if (cache_directory) {
    cache.emplace(*cache_directory);
    std::string problem;
    if (auto cached = cache->load(model, options, &problem)) {
      fmt::print("{} ({}): tables from {}, {:.1f} MiB\n", spec, options.sizes.describe(), cache->directory().string(),
                 double(table_bytes(*cached)) / 1048576.0);
      return std::move(*cached);
    }
    if (!problem.empty()) fmt::print("ignoring the cached {} tables: {}\n", spec, problem);
  }
  fmt::print("{} ({}): precomputing on the {} ...\n", spec, options.sizes.describe(), gpu ? "GPU (GL)" : "CPU");
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  lut::PrecomputeReport report;
  lut::LookupTables tables = gpu ? render::precompute_tables_gpu(model, options, &report)
                                 : lut::precompute_tables_cpu(model, options, &report);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu_seconds = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;  // all threads
  fmt::print("{}: precompute on {} {:.1f} s wall, {:.1f} s CPU, {:.1f} MiB\n", spec, report.device, seconds,
             cpu_seconds, double(table_bytes(tables)) / 1048576.0);
  if (cache) fmt::print("  stored in {}\n", cache->store(model, options, tables).string());
  return tables;
}

struct Reference {
  Spectrum mean, standard_error, order_one;
};

/// The zenith reference at one sun elevation, with progress on stderr.
Reference reference_at(const AtmosphereModel& model, const Vec3& camera, double elevation_deg, const std::string& kind,
                       std::size_t samples, std::size_t batches, unsigned threads) {
  const Vec3 zenith{0.0, 0.0, 1.0};
  const reference::SunDisc sun{sun_direction(elevation_deg), 4.65e-3};
  const auto start = std::chrono::steady_clock::now();
  Reference r;
  if (kind == "path-tracer") {
    reference::PathTracerOptions options;
    options.samples_per_wavelength = samples;
    options.thread_count = threads;
    const auto estimate = reference::path_traced_radiance(model, camera, zenith, sun, options);
    r = {estimate.mean, estimate.standard_error, Spectrum(model.wavelength_count())};
  } else {
    reference::LitAirOptions options;
    options.samples = samples;
    options.batches = batches;
    options.thread_count = threads;
    options.progress = [&](std::size_t done, std::size_t total) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print(stderr, "\r  sun {:.1f}°: {} / {} paths, {:.0f} s", elevation_deg, done, total, seconds);
      std::fflush(stderr);
    };
    const auto estimate = reference::lit_air_radiance(model, camera, zenith, sun, options);
    fmt::print(stderr, "\n");
    fmt::print("  {:.2f} lit-air quadratures per path\n",
               double(estimate.single_scattering_quadratures) / double(samples));
    r = {estimate.mean, estimate.standard_error, estimate.order_one};
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("  ({}: {} paths{}, {:.0f} s)\n", kind, samples, kind == "path-tracer" ? " per wavelength" : "", seconds);
  return r;
}

/// The references of an earlier run's twilight_reference.csv by (elevation,
/// wavelength): its reference, standard_error and order_one columns.
std::map<std::pair<long, long>, std::array<double, 3>> read_reference_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("--reference-csv: cannot read " + path.string());
  std::map<std::pair<long, long>, std::array<double, 3>> out;
  bool header = false;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("sun_elevation_deg,wavelength_nm,reference,standard_error,order_one", 0) != 0)
        throw std::runtime_error("--reference-csv " + path.string() + ": not a twilight_reference.csv (header)");
      header = true;
      continue;
    }
    std::stringstream fields(line);
    std::array<double, 5> v{};
    std::string field;
    for (double& x : v) {
      if (!std::getline(fields, field, ','))
        throw std::runtime_error("--reference-csv " + path.string() + ": short row");
      x = std::stod(field);
    }
    out[{std::lround(v[0] * 1000.0), std::lround(v[1] * 1000.0)}] = {v[2], v[3], v[4]};
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) try {
  std::string preset = "earth-advanced";
  std::vector<std::string> size_names = {"paper", "twilight"};
  double step_deg = 0.25;
  std::vector<std::string> reference_deg = {"0", "-3", "-6", "-9", "-12", "-15", "-18"};
  std::string reference_kind = "lit-air";
  std::vector<std::string> samples_text = {"20000"};  // one count, or one per --reference-deg
  std::size_t batches = 20;
  unsigned threads = 0;
  lut::PrecomputeOptions precompute;  // the defaults but for the sizes, unless --orders / --no-series-tail
  bool chart = true, gpu = false;
  std::optional<std::filesystem::path> reference_file;
  std::optional<std::filesystem::path> cache_directory = lut::default_cache_directory();
  std::filesystem::path out = std::filesystem::path(ZENITH_SOURCE_DIR) / "bench" / "results";
  for (bench::CommandLine args(argc, argv); args.next();) {
    const std::string& a = args.option();
    if (a == "--preset")
      preset = args.value();
    else if (a == "--sizes")
      size_names = bench::split_list(args.value());
    else if (a == "--step-deg")
      step_deg = std::stod(args.value());
    else if (a == "--reference-deg")
      reference_deg = bench::split_list(args.value());
    else if (a == "--reference")
      reference_kind = args.value();
    else if (a == "--reference-csv")
      reference_file = std::filesystem::path(args.value());
    else if (a == "--gpu")
      gpu = true;
    else if (a == "--samples")
      samples_text = bench::split_list(args.value());
    else if (a == "--batches")
      batches = std::stoul(args.value());
    else if (a == "--threads")
      threads = unsigned(std::stoul(args.value()));
    else if (a == "--orders")
      precompute.max_orders = std::stoi(args.value());
    else if (a == "--no-series-tail")
      precompute.series_tail = false;
    else if (a == "--cache")
      cache_directory = std::filesystem::path(args.value());
    else if (a == "--no-cache")
      cache_directory.reset();
    else if (a == "--out")
      out = args.value();
    else if (a == "--no-chart")
      chart = false;
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (!(step_deg > 0.0 && step_deg <= 3.0)) throw std::invalid_argument("--step-deg: must be in (0, 3]");
  if (reference_kind != "lit-air" && reference_kind != "path-tracer")
    throw std::invalid_argument("--reference: '" + reference_kind + "' is not lit-air or path-tracer");
  std::vector<std::size_t> samples;
  for (const std::string& text : samples_text) samples.push_back(std::stoul(text));
  if (samples.size() == 1) samples.assign(reference_deg.size(), samples.front());
  if (samples.size() != reference_deg.size())
    throw std::invalid_argument("--samples: give one count or one per --reference-deg");
  for (std::size_t count : samples) {
    if (count == 0) throw std::invalid_argument("--samples: must be > 0");
    if (reference_kind == "lit-air" && (batches == 0 || count % batches != 0))
      throw std::invalid_argument("--batches: must be > 0 and divide every --samples count");
  }
  precompute.threads = threads;
  std::filesystem::create_directories(out);
  const std::string suffix = preset == "earth-advanced" ? "" : "_" + preset;
  const auto zenith_csv = out / ("twilight_zenith" + suffix + ".csv");
  const auto reference_csv = out / ("twilight_reference" + suffix + ".csv");

  const AtmosphereModel model = load_preset(preset).model;
  const std::size_t channels = model.wavelength_count();
  const Vec3 camera{0.0, 0.0, model.ground_radius_m + 1.0};
  const Vec3 zenith{0.0, 0.0, 1.0};
  std::vector<double> elevations;
  for (int i = 0; i * step_deg <= 18.0 + 1e-9; ++i) elevations.push_back(-i * step_deg);

  // zenith radiance per size, per elevation, per wavelength
  std::map<std::string, std::vector<Spectrum>> by_size;
  for (const std::string& name : size_names) {
    const lut::LookupTables tables = tables_for(model, name, precompute, gpu, cache_directory);
    const lut::TableQueries queries(model, tables);
    std::vector<Spectrum>& radiance = by_size[name];
    for (double h : elevations) radiance.push_back(queries.sky_radiance(camera, zenith, sun_direction(h)));
    // Smoothness: the largest |Δ² ln L| over interior steps, and monotonic fall.
    double worst_second_difference = 0.0, worst_at = 0.0;
    bool monotonic = true;
    for (std::size_t k = 1; k + 1 < radiance.size(); ++k)
      for (std::size_t c = 0; c < channels; ++c) {
        const double d2 = std::log(radiance[k + 1][c]) - 2.0 * std::log(radiance[k][c]) + std::log(radiance[k - 1][c]);
        if (std::abs(d2) > worst_second_difference) worst_second_difference = std::abs(d2), worst_at = elevations[k];
      }
    for (std::size_t k = 1; k < radiance.size(); ++k)
      for (std::size_t c = 0; c < channels; ++c) monotonic = monotonic && radiance[k][c] < radiance[k - 1][c];
    fmt::print("{}: zenith radiance falls {} from 0° to −18°; max |Δ² ln L| over {}° steps {:.4f} (at {:.2f}°)\n", name,
               monotonic ? "monotonically" : "NOT monotonically", step_deg, worst_second_difference, worst_at);
    std::fflush(stdout);  // progress through a pipe: each size's line as it is measured
  }

  {
    std::ofstream csv(zenith_csv);
    csv << "sun_elevation_deg";
    for (const std::string& name : size_names)
      for (std::size_t c = 0; c < channels; ++c) csv << ',' << name << '_' << model.wavelengths_nm[c] << "nm";
    csv << '\n';
    for (std::size_t k = 0; k < elevations.size(); ++k) {
      csv << elevations[k];
      for (const std::string& name : size_names)
        for (std::size_t c = 0; c < channels; ++c) csv << ',' << fmt::format("{:.6e}", by_size[name][k][c]);
      csv << '\n';
    }
  }

  // Read before the output (which may be the same file) is opened.
  std::map<std::pair<long, long>, std::array<double, 3>> stored_references;
  std::string stored_command;
  if (reference_file) {
    stored_references = read_reference_csv(*reference_file);
    std::ifstream in(*reference_file);
    std::getline(in, stored_command);
    if (stored_command.rfind("# ", 0) != 0) stored_command.clear();
  }
  std::ofstream ref_csv(reference_csv);
  ref_csv << "# build/bench/twilight_bench";  // the command first (gnuplot skips it; fixtures keep it)
  for (int a = 1; a < argc; ++a) ref_csv << ' ' << argv[a];
  ref_csv << '\n';
  if (reference_file)  // where the reference values come from, and the command that computed them
    ref_csv << "# reference from " << reference_file->filename().string() << ": " << stored_command.substr(2) << '\n';
  ref_csv << "sun_elevation_deg,wavelength_nm,reference,standard_error,order_one";
  for (const std::string& name : size_names) ref_csv << ',' << name << ',' << name << "_relative_error";
  ref_csv << '\n';
  for (std::size_t e = 0; e < reference_deg.size(); ++e) {
    const double h = std::stod(reference_deg[e]);
    Reference r;
    if (reference_file) {
      r = {Spectrum(channels), Spectrum(channels), Spectrum(channels)};
      for (std::size_t c = 0; c < channels; ++c) {
        const auto found =
            stored_references.find({std::lround(h * 1000.0), std::lround(model.wavelengths_nm[c] * 1000.0)});
        if (found == stored_references.end())
          throw std::runtime_error(fmt::format("--reference-csv {}: no reference at sun {}° and {} nm",
                                               reference_file->string(), h, model.wavelengths_nm[c]));
        r.mean[c] = found->second[0];
        r.standard_error[c] = found->second[1];
        r.order_one[c] = found->second[2];
      }
    } else {
      r = reference_at(model, camera, h, reference_kind, samples[e], batches, threads);
    }
    for (std::size_t c = 0; c < channels; ++c) {
      const double relative_se = r.standard_error[c] / r.mean[c];
      std::string line =
          fmt::format("sun {:6.1f}°  {:.0f} nm  reference {:.4e} ± {:.2f} % (order 1 {:.1f} %)", h,
                      model.wavelengths_nm[c], r.mean[c], 100.0 * relative_se, 100.0 * r.order_one[c] / r.mean[c]);
      ref_csv << h << ',' << model.wavelengths_nm[c] << ',' << fmt::format("{:.6e}", r.mean[c]) << ','
              << fmt::format("{:.6e}", r.standard_error[c]) << ',' << fmt::format("{:.6e}", r.order_one[c]);
      for (const std::string& name : size_names) {
        // the table value at the nearest step of the sweep
        std::size_t k = std::size_t(std::lround(-h / step_deg));
        k = std::min(k, elevations.size() - 1);
        const double value = by_size[name][k][c];
        const double error = value / r.mean[c] - 1.0;
        line += fmt::format("  {} {:+.2f} % (z {:+.1f})", name, 100.0 * error, error / relative_se);
        ref_csv << ',' << fmt::format("{:.6e}", value) << ',' << fmt::format("{:.5f}", error);
      }
      ref_csv << '\n';
      fmt::print("{}\n", line);
    }
    std::fflush(stdout);
  }
  ref_csv.close();

  if (chart) {
    const auto script = out / ("twilight_zenith" + suffix + ".gp");
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900,600\nset output '" << (out / ("twilight_zenith" + suffix + ".png")).string()
       << "'\n"
       << "set datafile separator ','\nset logscale y\nset key top right\nset grid\n"
       << "set xlabel 'sun elevation [deg]'\nset ylabel 'zenith radiance [sr^-1 per unit solar irradiance]'\n"
       << "set title 'Zenith radiance through twilight (" << preset << ", 550 nm)'\nplot ";
    std::size_t c550 = 0;
    for (std::size_t c = 0; c < channels; ++c)
      if (std::abs(model.wavelengths_nm[c] - 550.0) < std::abs(model.wavelengths_nm[c550] - 550.0)) c550 = c;
    for (std::size_t s = 0; s < size_names.size(); ++s)
      gp << "'" << zenith_csv.string() << "' using 1:" << 2 + s * channels + c550 << " with lines title '"
         << size_names[s] << "', ";
    gp << "'" << reference_csv.string() << "' using ($2==" << model.wavelengths_nm[c550]
       << "?$1:1/0):3:4 with yerrorbars title 'reference (" << reference_kind << ")'\n";
    gp.close();
    if (std::system(("gnuplot " + script.string() + " 2>/dev/null").c_str()) != 0)
      fmt::print("gnuplot failed: the data is in {}\n", out.string());
  }
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "twilight_bench: {}\n", e.what());
  return 1;
}
