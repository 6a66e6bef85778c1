// How close N scattering orders come to the converged series, with and
// without the series tail (atmosphere/lut/series_tail.h), texel by texel.
//
// For each atmosphere, the GPU precompute computes a reference with
// --reference-orders orders (24: the orders after it add less than 1e-8 of
// Earth's radiance) and no tail, then every N of --orders with the tail and
// without it, with the same table sizes and quadrature. It compares each table
// set with the reference:
//
//   radiance   every texel and wavelength of the scattering tables: the total
//              in-scattered radiance S = S_R·P_R(ν) + S_M·P_M(ν) + S_multiple
//              (the phases at the texel's ν), relative error
//              |S − S_ref| / S_ref where S_ref > 1e-6 of its wavelength's
//              largest value (the dark texels below it are skipped): RMS,
//              99th percentile, max;
//   irradiance the sky irradiance table, the same statistics;
//   seconds    the precompute's wall time (the stage sum), shader compilation
//              included in the first precompute only (one GL context).
//
//   series_tail_bench [--presets earth-advanced,mars] [--tables paper|small]
//                     [--orders 3,4,5,6,8] [--reference-orders 24] [--out DIR]
//
// Prints a table and writes series_tail.csv into --out (default
// bench/results/ of the source tree). docs/lookup-tables.md, "Closing the series".
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "atmosphere/lut/parameterization.h"
#include "atmosphere/lut/precompute_options.h"
#include "atmosphere/named_inputs.h"
#include "bench/command_line.h"
#include "render/gl/egl_context.h"
#include "render/lut/gpu_precompute.h"
#include "render/lut/table_provider.h"

namespace {

namespace fs = std::filesystem;
namespace lut = zenith::atmosphere::lut;
using zenith::atmosphere::AtmosphereModel;

struct Options {
  std::vector<std::string> presets = {"earth-advanced", "mars"};
  std::string tables = "paper";
  std::vector<int> orders = {3, 4, 5, 6, 8};
  int reference_orders = 24;
  fs::path out = fs::path(ZENITH_SOURCE_DIR) / "bench/results";
};

Options parse(int argc, char** argv) {
  Options o;
  for (zenith::bench::CommandLine args(argc, argv); args.next();) {
    const std::string& a = args.option();
    if (a == "--presets") {
      o.presets = zenith::bench::split_list(args.value());
    } else if (a == "--tables") {
      o.tables = args.value();
    } else if (a == "--orders") {
      o.orders = zenith::bench::split_int_list(args.value());
    } else if (a == "--reference-orders") {
      o.reference_orders = std::stoi(args.value());
    } else if (a == "--out") {
      o.out = args.value();
    } else {
      throw std::invalid_argument("unknown argument " + a +
                                  " (--presets LIST --tables NAME --orders LIST --reference-orders N --out DIR)");
    }
  }
  return o;
}

/// RMS, 99th percentile and max of relative errors.
struct ErrorStats {
  double rms = 0.0, p99 = 0.0, max = 0.0;
};

ErrorStats stats_of(std::vector<double>& errors) {
  ErrorStats s;
  if (errors.empty()) return s;
  double sum = 0.0;
  for (double e : errors) sum += e * e;
  s.rms = std::sqrt(sum / double(errors.size()));
  std::sort(errors.begin(), errors.end());
  s.p99 = errors[std::min(errors.size() - 1, std::size_t(0.99 * double(errors.size())))];
  s.max = errors.back();
  return s;
}

/// S = S_R·P_R + S_M·P_M + S_multiple of every texel and channel.
std::vector<double> total_radiance(const AtmosphereModel& model, const lut::LookupTables& t) {
  const lut::TableSizes& s = t.sizes;
  const std::size_t n = t.channels;
  std::vector<double> out(s.scattering_width() * s.scattering_mu * s.scattering_r * n);
  std::size_t i = 0;
  for (std::size_t z = 0; z < s.scattering_r; ++z)
    for (std::size_t y = 0; y < s.scattering_mu; ++y)
      for (std::size_t x = 0; x < s.scattering_width(); ++x) {
        const lut::ScatteringCoordinates c =
            lut::scattering_texel_coordinates(t.geometry, s, x, y, z, lut::AngleMapping::Distance);
        const double phase_r = model.rayleigh_phase_function(c.nu);
        const float *r = t.single_rayleigh.texel(x, y, z), *m = t.single_mie.texel(x, y, z),
                    *ms = t.multiple.texel(x, y, z);
        for (std::size_t ch = 0; ch < n; ++ch) out[i++] = r[ch] * phase_r + m[ch] * model.mie_phase(ch, c.nu) + ms[ch];
      }
  return out;
}

/// Relative errors of `values` against `reference` (channel-minor, `channels`
/// per texel) where the reference exceeds 1e-6 of its channel's largest value.
ErrorStats compare(const std::vector<double>& values, const std::vector<double>& reference, std::size_t channels) {
  std::vector<double> largest(channels, 0.0);
  for (std::size_t i = 0; i < reference.size(); ++i)
    largest[i % channels] = std::max(largest[i % channels], reference[i]);
  std::vector<double> errors;
  errors.reserve(reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double ref = reference[i];
    if (!(ref > 1e-6 * largest[i % channels])) continue;
    errors.push_back(std::abs(values[i] - ref) / ref);
  }
  return stats_of(errors);
}

std::vector<double> as_double(const std::vector<float>& v) { return {v.begin(), v.end()}; }

struct Row {
  std::string preset;
  int orders = 0;
  bool tail = false;
  double seconds = 0.0;
  ErrorStats radiance, irradiance;
  double tail_fraction = 0.0;
};

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  zenith::render::gl::HeadlessContext context;
  std::vector<Row> rows;
  for (const std::string& preset : o.presets) {
    const auto loaded = zenith::atmosphere::load_atmosphere_argument(preset);
    const AtmosphereModel& model = loaded.model;
    lut::PrecomputeOptions base;
    zenith::atmosphere::apply_table_set(o.tables, base);
    auto run = [&](int orders, bool tail, lut::PrecomputeReport& report) {
      lut::PrecomputeOptions options = base;
      options.max_orders = orders;
      options.series_tail = tail;
      return zenith::render::precompute_tables_gpu(model, options, &report, &context);
    };
    std::fprintf(stderr, "%s: reference, %d orders without the tail...\n", preset.c_str(), o.reference_orders);
    lut::PrecomputeReport reference_report;
    const lut::LookupTables reference = run(o.reference_orders, false, reference_report);
    const std::vector<double> ref_radiance = total_radiance(model, reference);
    const std::vector<double> ref_irradiance = as_double(reference.irradiance.data);
    for (int orders : o.orders)
      for (bool tail : {false, true}) {
        if (tail && orders < 3) continue;  // the tail starts from the third order
        std::fprintf(stderr, "%s: %d orders%s...\n", preset.c_str(), orders, tail ? " and the tail" : "");
        lut::PrecomputeReport report;
        const lut::LookupTables t = run(orders, tail, report);
        Row row{preset, orders, tail, report.total_seconds(), {}, {}, report.tail_fraction};
        row.radiance = compare(total_radiance(model, t), ref_radiance, t.channels);
        row.irradiance = compare(as_double(t.irradiance.data), ref_irradiance, t.channels);
        rows.push_back(row);
      }
  }

  fmt::print("Tables {} against {} orders, relative error of the in-scattered radiance (every texel and wavelength)\n",
             o.tables, o.reference_orders);
  fmt::print("{:<16} {:>6} {:>5} {:>9} {:>10} {:>10} {:>10} {:>12} {:>12} {:>9}\n", "preset", "orders", "tail",
             "seconds", "rad RMS", "rad p99", "rad max", "irrad RMS", "irrad max", "tail %");
  fs::create_directories(o.out);
  std::ofstream csv(o.out / "series_tail.csv");
  csv << "preset,tables,orders,series_tail,precompute_s,radiance_rms,radiance_p99,radiance_max,irradiance_rms,"
         "irradiance_p99,irradiance_max,tail_fraction,reference_orders\n";
  for (const Row& r : rows) {
    fmt::print("{:<16} {:>6} {:>5} {:>9.2f} {:>10.2e} {:>10.2e} {:>10.2e} {:>12.2e} {:>12.2e} {:>9.3f}\n", r.preset,
               r.orders, r.tail ? "yes" : "no", r.seconds, r.radiance.rms, r.radiance.p99, r.radiance.max,
               r.irradiance.rms, r.irradiance.max, 100.0 * r.tail_fraction);
    csv << fmt::format("{},{},{},{},{:.3f},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.5f},{}\n", r.preset, o.tables,
                       r.orders, r.tail ? 1 : 0, r.seconds, r.radiance.rms, r.radiance.p99, r.radiance.max,
                       r.irradiance.rms, r.irradiance.p99, r.irradiance.max, r.tail_fraction, o.reference_orders);
  }
  fmt::print("written {}\n", (o.out / "series_tail.csv").string());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "series_tail_bench: %s\n", e.what());
  return 1;
}
