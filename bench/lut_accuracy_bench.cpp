// Run time against error of the lookup tables.
//
// For each method and setting (table sizes, scattering orders, quadrature along
// rays, CPU or GPU precompute) this program measures the precompute time and
// the RMS and maximum relative error of table-based sky radiance against the
// reference solver, over the fixed set of geometries and view directions of
// tests/data/reference_*.csv (Earth and Mars: noon, low sun, twilight, limb from
// orbit; 400 000 paths per wavelength and direction, standard errors ~0.1-3%).
// It prints a table, writes CSV, and (with gnuplot installed) a PNG chart.
//
//   build/bench/lut_accuracy_bench [--quick] [--out DIR] [--no-gpu]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "atmosphere/lut/cpu_precompute.h"
#include "atmosphere/parameters.h"
#include "atmosphere/sky_sampling.h"
#include "render/lut/gpu_precompute.h"

using namespace zenith::atmosphere;

namespace {

struct Case {
  std::string preset, name;
  SkyGeometry geometry;
  std::vector<ViewDirection> directions;
  std::vector<std::vector<double>> reference, standard_error;
};

Case read_case(const std::string& preset, const std::string& name, std::size_t channels) {
  std::ifstream in(std::string(ZENITH_SOURCE_DIR) + "/tests/data/reference_" + preset + "_" + name + ".csv");
  if (!in) throw std::runtime_error("missing fixture for " + preset + " " + name);
  Case c{preset, name, {}, {}, {}, {}};
  std::string line;
  std::getline(in, line);
  auto arg = [&](const std::string& flag) { return std::stod(line.substr(line.find(flag + " ") + flag.size() + 1)); };
  c.geometry.altitude_m = arg("--altitude-m");
  c.geometry.sun_zenith_deg = arg("--sun-zenith-deg");
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    ViewDirection d{};
    s >> d.zenith_deg >> d.azimuth_deg;
    std::vector<double> v;
    double x;
    while (s >> x) v.push_back(x);
    c.directions.push_back(d);
    c.reference.emplace_back(v.begin(), v.begin() + long(channels));
    c.standard_error.emplace_back(v.end() - long(channels), v.end());
  }
  return c;
}

struct Setting {
  std::string label;
  lut::PrecomputeOptions options;
  bool gpu = false;
};

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, gpu = true;
  std::filesystem::path out = "bench-results";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--no-gpu") gpu = false;
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else {
      fmt::print(stderr, "usage: lut_accuracy_bench [--quick] [--no-gpu] [--out DIR]\n");
      return 2;
    }
  }
  std::filesystem::create_directories(out);

  std::vector<Setting> settings;
  auto add = [&](std::string label, lut::TableSizes sizes, int orders, bool log_linear, int sphere, bool on_gpu) {
    lut::PrecomputeOptions o;
    o.sizes = sizes;
    o.max_orders = orders;
    o.sphere_zenith_samples = sphere;
    o.scattering_quadrature =
        log_linear ? lut::PrecomputeOptions::Quadrature::LogLinear : lut::PrecomputeOptions::Quadrature::Trapezoid;
    settings.push_back({std::move(label) + (on_gpu ? " GPU" : " CPU"), o, on_gpu});
  };
  const lut::TableSizes small = lut::TableSizes::small();
  const lut::TableSizes medium{128, 32, 64, 16, 16, 64, 32, 8};
  const lut::TableSizes paper{};
  for (bool on_gpu : {false, true}) {
    if (on_gpu && !gpu) continue;
    add("small 4 orders", small, 4, true, 8, on_gpu);
    add("small 4 orders trapezoid", small, 4, false, 8, on_gpu);
    add("small 2 orders", small, 2, true, 8, on_gpu);
    if (!quick || on_gpu) add("medium 4 orders", medium, 4, true, 16, on_gpu);
    if (on_gpu) add("paper 4 orders", paper, 4, true, 16, on_gpu);
    if (!quick && on_gpu) add("paper 8 orders", paper, 8, true, 16, on_gpu);
  }

  std::ofstream csv(out / "lut_accuracy.csv");
  csv << "setting,preset,precompute_s,rms_relative_error,max_relative_error,table_MB\n";
  fmt::print("{:<34} {:<15} {:>12} {:>10} {:>10} {:>9}\n", "setting", "atmosphere", "precompute s", "RMS err",
             "max err", "tables MB");
  for (const std::string preset : {"earth-advanced", "mars"}) {
    const AtmosphereModel model = load_preset(preset).model;
    std::vector<Case> cases;
    for (const char* name : {"noon", "low_sun", "twilight", "orbit_limb"})
      cases.push_back(read_case(preset, name, model.wavelength_count()));
    for (const Setting& s : settings) {
      const auto start = std::chrono::steady_clock::now();
      lut::LookupTables tables;
      try {
        tables = s.gpu ? zenith::render::precompute_tables_gpu(model, s.options)
                       : lut::precompute_tables_cpu(model, s.options);
      } catch (const std::exception& e) {
        fmt::print(stderr, "{}: {}\n", s.label, e.what());
        continue;
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const lut::TableQueries q(model, tables);
      double sum = 0.0, worst = 0.0;
      int n = 0;
      for (const Case& c : cases) {
        const auto values = sample_radiance(q, c.geometry, c.directions);
        for (std::size_t i = 0; i < values.size(); ++i)
          for (std::size_t ch = 0; ch < model.wavelength_count(); ++ch) {
            const double ref = c.reference[i][ch];
            const double err = std::max(0.0, std::abs(values[i].radiance[ch] - ref) - 2.0 * c.standard_error[i][ch]) / ref;
            sum += err * err;
            worst = std::max(worst, err);
            ++n;
          }
      }
      const double bytes = 4.0 * double(model.wavelength_count()) *
                           double(tables.transmittance.data.size() / tables.channels + tables.irradiance.data.size() / tables.channels +
                                  3 * tables.multiple.data.size() / tables.channels);
      const double rms = std::sqrt(sum / n);
      fmt::print("{:<34} {:<15} {:>12.2f} {:>10.4f} {:>10.4f} {:>9.1f}\n", s.label, preset, seconds, rms, worst, bytes / 1e6);
      csv << '"' << s.label << "\"," << preset << ',' << seconds << ',' << rms << ',' << worst << ',' << bytes / 1e6 << '\n';
      csv.flush();
    }
  }
  csv.close();

  // Chart: precompute time against RMS error, one series per atmosphere.
  std::ofstream gp(out / "lut_accuracy.gp");
  gp << "set terminal pngcairo size 900,600\nset output '" << (out / "lut_accuracy.png").string() << "'\n"
     << "set datafile separator ','\nset logscale x\nset xlabel 'precompute time [s]'\n"
     << "set ylabel 'RMS relative error of sky radiance vs reference'\nset grid\nset key top right\n"
     << "set title 'zenith lookup tables: run time against error'\n"
     << "plot '" << (out / "lut_accuracy.csv").string()
     << "' using (strcol(2) eq 'earth-advanced' ? $3 : 1/0):4:(strcol(1)) with labels point pt 7 offset 1,0.5 "
        "font ',7' title 'Earth (advanced)', \\\n"
     << "     '' using (strcol(2) eq 'mars' ? $3 : 1/0):4 with points pt 5 title 'Mars'\n";
  gp.close();
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0 &&
      std::system(("gnuplot " + (out / "lut_accuracy.gp").string()).c_str()) == 0)
    fmt::print("chart: {}\n", (out / "lut_accuracy.png").string());
  else
    fmt::print("gnuplot not found: chart script left in {}\n", (out / "lut_accuracy.gp").string());
  fmt::print("csv: {}\n", (out / "lut_accuracy.csv").string());
  return 0;
}
