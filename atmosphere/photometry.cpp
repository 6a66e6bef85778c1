#include "atmosphere/photometry.h"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <string>

#include "atmosphere/reference_data.h"
#include "atmosphere/spectrum.h"

namespace zenith::atmosphere {
namespace {

SpectralTable load_two_column_csv(std::string_view name) {
  std::istringstream in{std::string(embedded_file(name))};
  std::string line;
  std::vector<std::pair<double, double>> samples;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    const auto comma = line.find(',');
    samples.emplace_back(std::stod(line.substr(0, comma)), std::stod(line.substr(comma + 1)));
  }
  return SpectralTable(std::move(samples));
}

}  // namespace

double solar_irradiance_W_m2_nm(double wavelength_nm) {
  static const SpectralTable table = load_two_column_csv("data/solar_irradiance_kurucz.csv");
  return table(wavelength_nm);
}

double photopic_efficiency(double wavelength_nm) {
  static const SpectralTable table = load_two_column_csv("data/cie_photopic_luminosity_1924.csv");
  if (wavelength_nm < 380.0 || wavelength_nm > 780.0) return 0.0;
  return table(wavelength_nm);
}

std::vector<double> luminance_weights(std::span<const double> wavelengths_nm) {
  const std::size_t n = wavelengths_nm.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return wavelengths_nm[a] < wavelengths_nm[b]; });
  std::vector<double> w(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    double width = 100.0;
    if (n > 1) {
      const double lo =
          k > 0 ? wavelengths_nm[order[k - 1]] : 2 * wavelengths_nm[order[k]] - wavelengths_nm[order[k + 1]];
      const double hi =
          k + 1 < n ? wavelengths_nm[order[k + 1]] : 2 * wavelengths_nm[order[k]] - wavelengths_nm[order[k - 1]];
      width = 0.5 * (hi - lo);
    }
    w[order[k]] = 683.0 * photopic_efficiency(wavelengths_nm[order[k]]) * width;
  }
  return w;
}

}  // namespace zenith::atmosphere
