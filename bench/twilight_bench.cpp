// Zenith radiance through twilight, sun 0° to −18°, from the CPU tables at two
// table sizes against the reference path tracer (issue 29, goal 6).
//
//   twilight_bench [--preset NAME] [--sizes paper,paper-mu-s-x2] [--step-deg 0.25]
//                  [--reference-deg 0,-3,-6,-9,-12,-15,-18] [--samples N] [--threads N]
//                  [--out DIR] [--no-chart]
//
// For each table size: the CPU precompute's time and the tables' memory, then
// the zenith radiance L(h) seen from 1 m above the ground for sun elevations h
// from 0° down to −18° in --step-deg steps. Smoothness: the largest second
// difference of ln L between neighbouring steps (a step in the tables, where
// an order fades or a texel column ends, shows as a spike of |Δ² ln L|; a
// smooth exponential fall gives ~0), and whether L falls monotonically.
// Against the path tracer (--samples paths per wavelength at each of
// --reference-deg): the relative error of each size, with the path tracer's
// standard error. The reference is noisy in deep twilight (the zenith ray is
// in the planet's shadow below −10°, so all its light is multiple scattering
// from far-off sunlit air): the standard error column says how far to trust it.
//
// Output: DIR/twilight_zenith.csv (every step), DIR/twilight_reference.csv,
// DIR/twilight_zenith.png (gnuplot; with --no-chart only the data).
#include <fmt/format.h>
#include <fmt/os.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/parameters.h"
#include "atmosphere/reference/path_tracer.h"
#include "bench/command_line.h"
#include "core/units.h"

namespace {

using namespace zenith;
using namespace zenith::atmosphere;

lut::TableSizes sizes_by_name(const std::string& name) {
  if (name == "paper") return lut::TableSizes{};
  if (name == "paper-mu-s-x2") return lut::TableSizes{256, 64, 64, 16, 32, 128, 64, 8};
  if (name == "small") return lut::TableSizes::small();
  throw std::invalid_argument("--sizes: unknown size '" + name + "' (paper, paper-mu-s-x2, small)");
}

std::size_t table_bytes(const lut::LookupTables& t) {
  return sizeof(float) * (t.transmittance.data.size() + t.irradiance.data.size() + t.single_rayleigh.data.size() +
                          t.single_mie.data.size() + t.multiple.data.size());
}

Vec3 sun_direction(double elevation_deg) {
  const double e = elevation_deg * core::kPi / 180.0;
  return Vec3{std::cos(e), 0.0, std::sin(e)};
}

}  // namespace

int main(int argc, char** argv) try {
  std::string preset = "earth-advanced";
  std::vector<std::string> size_names = {"paper", "paper-mu-s-x2"};
  double step_deg = 0.25;
  std::vector<std::string> reference_deg = {"0", "-3", "-6", "-9", "-12", "-15", "-18"};
  std::size_t samples = 100000;
  unsigned threads = 0;
  bool chart = true;
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
    else if (a == "--samples")
      samples = std::stoul(args.value());
    else if (a == "--threads")
      threads = unsigned(std::stoul(args.value()));
    else if (a == "--out")
      out = args.value();
    else if (a == "--no-chart")
      chart = false;
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (!(step_deg > 0.0 && step_deg <= 3.0)) throw std::invalid_argument("--step-deg: must be in (0, 3]");
  std::filesystem::create_directories(out);

  const AtmosphereModel model = load_preset(preset).model;
  const std::size_t channels = model.wavelength_count();
  const Vec3 camera{0.0, 0.0, model.ground_radius_m + 1.0};
  const Vec3 zenith{0.0, 0.0, 1.0};
  std::vector<double> elevations;
  for (int i = 0; i * step_deg <= 18.0 + 1e-9; ++i) elevations.push_back(-i * step_deg);

  // zenith radiance per size, per elevation, per wavelength
  std::map<std::string, std::vector<Spectrum>> by_size;
  for (const std::string& name : size_names) {
    lut::PrecomputeOptions options;
    options.sizes = sizes_by_name(name);
    options.threads = threads;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const lut::LookupTables tables = lut::precompute_tables_cpu(model, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu_seconds =
        double(std::clock() - cpu_start) / CLOCKS_PER_SEC;  // all threads: a loaded machine's honest cost
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
    fmt::print(
        "{} ({}): CPU precompute {:.1f} s wall, {:.1f} s CPU, {:.1f} MiB; zenith radiance falls {} from 0° to "
        "−18°; max |Δ² ln L| over {}° steps {:.4f} (at {:.2f}°)\n",
        name, options.sizes.describe(), seconds, cpu_seconds, double(table_bytes(tables)) / 1048576.0,
        monotonic ? "monotonically" : "NOT monotonically", step_deg, worst_second_difference, worst_at);
    std::fflush(stdout);  // progress through a pipe: each size's line as it is measured
  }

  {
    std::ofstream csv(out / "twilight_zenith.csv");
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

  std::ofstream ref_csv(out / "twilight_reference.csv");
  ref_csv << "sun_elevation_deg,wavelength_nm,reference,standard_error";
  for (const std::string& name : size_names) ref_csv << ',' << name << ',' << name << "_relative_error";
  ref_csv << '\n';
  for (const std::string& text : reference_deg) {
    const double h = std::stod(text);
    reference::PathTracerOptions options;
    options.samples_per_wavelength = samples;
    options.thread_count = threads;
    const auto start = std::chrono::steady_clock::now();
    const auto estimate =
        reference::path_traced_radiance(model, camera, zenith, reference::SunDisc{sun_direction(h), 4.65e-3}, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (std::size_t c = 0; c < channels; ++c) {
      std::string line = fmt::format("sun {:6.1f}°  {:.0f} nm  reference {:.4e} ± {:.1f} %", h, model.wavelengths_nm[c],
                                     estimate.mean[c], 100.0 * estimate.standard_error[c] / estimate.mean[c]);
      ref_csv << h << ',' << model.wavelengths_nm[c] << ',' << estimate.mean[c] << ',' << estimate.standard_error[c];
      for (const std::string& name : size_names) {
        // the table value at the nearest step of the sweep
        std::size_t k = std::size_t(std::lround(-h / step_deg));
        k = std::min(k, elevations.size() - 1);
        const double value = by_size[name][k][c];
        const double error = value / estimate.mean[c] - 1.0;
        line += fmt::format("  {} {:+.2f} %", name, 100.0 * error);
        ref_csv << ',' << value << ',' << error;
      }
      ref_csv << '\n';
      fmt::print("{}\n", line);
    }
    fmt::print("  ({} paths per wavelength, {:.0f} s)\n", samples, seconds);
    std::fflush(stdout);
  }
  ref_csv.close();

  if (chart) {
    const auto script = out / "twilight_zenith.gp";
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900,600\nset output '" << (out / "twilight_zenith.png").string() << "'\n"
       << "set datafile separator ','\nset logscale y\nset key top right\nset grid\n"
       << "set xlabel 'sun elevation [deg]'\nset ylabel 'zenith radiance [sr^-1 per unit solar irradiance]'\n"
       << "set title 'Zenith radiance through twilight (" << preset << ", 550 nm)'\nplot ";
    std::size_t c550 = 0;
    for (std::size_t c = 0; c < channels; ++c)
      if (std::abs(model.wavelengths_nm[c] - 550.0) < std::abs(model.wavelengths_nm[c550] - 550.0)) c550 = c;
    for (std::size_t s = 0; s < size_names.size(); ++s)
      gp << "'" << (out / "twilight_zenith.csv").string() << "' using 1:" << 2 + s * channels + c550
         << " with lines title '" << size_names[s] << "', ";
    gp << "'" << (out / "twilight_reference.csv").string() << "' using ($2==" << model.wavelengths_nm[c550]
       << "?$1:1/0):3:4 with yerrorbars title 'path tracer'\n";
    gp.close();
    if (std::system(("gnuplot " + script.string() + " 2>/dev/null").c_str()) != 0)
      fmt::print("gnuplot failed: the data is in {}\n", out.string());
  }
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "twilight_bench: {}\n", e.what());
  return 1;
}
