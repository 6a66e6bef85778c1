#include "astro/star_photometry.h"

#include <algorithm>
#include <cmath>

#include "astro/v_band.h"

namespace zenith::astro {

double ballesteros_temperature_K(double b_minus_v) {
  const double bv = std::clamp(b_minus_v, -0.4, 2.5);
  return 4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62));
}

void star_irradiance_W_m2_nm(double v_mag, double b_minus_v, std::span<const double> wavelengths_nm,
                             std::span<double> out) {
  const double t = ballesteros_temperature_K(b_minus_v);
  const double band = v_band_mean([t](double l) { return planck_W_m2_sr_nm(l, t); });
  const double scale = v_irradiance_W_m2_nm(v_mag) / band;
  for (std::size_t i = 0; i < wavelengths_nm.size() && i < out.size(); ++i)
    out[i] = scale * planck_W_m2_sr_nm(wavelengths_nm[i], t);
}

std::vector<double> star_irradiance_W_m2_nm(double v_mag, double b_minus_v, std::span<const double> wavelengths_nm) {
  std::vector<double> out(wavelengths_nm.size());
  star_irradiance_W_m2_nm(v_mag, b_minus_v, wavelengths_nm, out);
  return out;
}

}  // namespace zenith::astro
