#include "astro/v_band.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "atmosphere/photometry.h"
#include "atmosphere/spectrum.h"

namespace zenith::astro {
namespace {

constexpr double kSigma_nm = kVFwhm_nm / 2.3548200450309493;  // FWHM = 2√(2 ln 2) σ
// The band integral runs over ±4σ (the Gaussian's tails beyond hold 6e-5) in 1 nm steps.
constexpr double kHalfSpan_nm = 4.0 * kSigma_nm;

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

double v_band_mean_of_line(double wavelength_nm, double line) {
  double den = 0.0;
  for (double l = kVCentre_nm - kHalfSpan_nm; l <= kVCentre_nm + kHalfSpan_nm; l += 1.0) den += v_response(l) * l;
  return line * v_response(wavelength_nm) * wavelength_nm / den;
}

double v_band_mean(std::span<const double> wavelengths_nm, std::span<const double> values) {
  if (wavelengths_nm.empty() || wavelengths_nm.size() != values.size()) return 0.0;
  std::vector<std::pair<double, double>> samples;
  for (std::size_t i = 0; i < values.size(); ++i) samples.emplace_back(wavelengths_nm[i], values[i]);
  const atmosphere::SpectralTable table(std::move(samples));  // linear between samples, nearest outside
  return v_band_mean([&](double l) { return table(l); });
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
