#include "astro/v_band.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "atmosphere/photometry.h"

namespace zenith::astro {
namespace {

constexpr double kSigma_nm = kVFwhm_nm / 2.3548200450309493;  // FWHM = 2√(2 ln 2) σ
// The band integral runs over ±4σ (the Gaussian's tails beyond hold 6e-5) in 1 nm steps.
constexpr double kHalfSpan_nm = 4.0 * kSigma_nm;

double interpolate(std::span<const double> x, std::span<const double> y, double at) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  if (at <= x[order.front()]) return y[order.front()];
  if (at >= x[order.back()]) return y[order.back()];
  for (std::size_t k = 1; k < order.size(); ++k) {
    const double x0 = x[order[k - 1]], x1 = x[order[k]];
    if (at <= x1) return y[order[k - 1]] + (y[order[k]] - y[order[k - 1]]) * (at - x0) / (x1 - x0);
  }
  return y[order.back()];
}

}  // namespace

double v_response(double wavelength_nm) {
  const double d = (wavelength_nm - kVCentre_nm) / kSigma_nm;
  return std::exp(-0.5 * d * d);
}

double v_band_mean(const std::function<double(double)>& spectrum) {
  double num = 0.0, den = 0.0;
  for (double l = kVCentre_nm - kHalfSpan_nm; l <= kVCentre_nm + kHalfSpan_nm; l += 1.0) {
    const double w = v_response(l) * l;  // photon weighting
    num += w * spectrum(l);
    den += w;
  }
  return num / den;
}

double v_band_mean(std::span<const double> wavelengths_nm, std::span<const double> values) {
  if (wavelengths_nm.empty() || wavelengths_nm.size() != values.size()) return 0.0;
  return v_band_mean([&](double l) { return interpolate(wavelengths_nm, values, l); });
}

double v_magnitude(double e) {
  return e > 0.0 ? -2.5 * std::log10(e / kVZeroPoint_W_m2_nm) : std::numeric_limits<double>::infinity();
}
double v_irradiance_W_m2_nm(double v_mag) { return kVZeroPoint_W_m2_nm * std::pow(10.0, -0.4 * v_mag); }
double v_surface_brightness(double l) { return v_magnitude(l * kSteradianPerArcsec2); }
double v_radiance_W_m2_sr_nm(double mu) { return v_irradiance_W_m2_nm(mu) / kSteradianPerArcsec2; }

double luminance_cd_m2(const std::function<double(double)>& radiance) {
  double sum = 0.0;
  for (double l = 380.0; l <= 780.0; l += 1.0) sum += atmosphere::photopic_efficiency(l) * radiance(l);
  return 683.0 * sum;  // 1 nm steps
}

}  // namespace zenith::astro
