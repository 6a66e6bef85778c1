#include "atmosphere/mie.h"

#include <cmath>

#include "atmosphere/constants.h"

namespace zenith::atmosphere {

double turbidity_concentration(double turbidity) { return (0.65 * turbidity - 0.65) * 1e-16; }

double mie_scattering_from_turbidity(double wavelength_nm, double turbidity, double junge_exponent, double K) {
  const double lambda_m = wavelength_nm * 1e-9;
  return 0.434 * turbidity_concentration(turbidity) * kPi * std::pow(2.0 * kPi / lambda_m, junge_exponent - 2.0) * K;
}

namespace {

/// K(w) = ½ + e^{−w}/w + (e^{−w} − 1)/w² (van de Hulst's ADA kernel).
/// For small |w| its Taylor series Σ_{n≥1} (−1)^{n+1} (n+1)/(n+2)! wⁿ avoids the
/// cancellation of the three O(1/w²) terms.
std::complex<double> ada_kernel(std::complex<double> w) {
  if (std::abs(w) < 0.25) {
    std::complex<double> sum = 0.0, power = w;
    double factorial = 6.0;  // (n+2)! for n = 1
    for (int n = 1; n <= 14; ++n) {
      const double sign = (n % 2 == 1) ? 1.0 : -1.0;
      sum += sign * double(n + 1) / factorial * power;
      power *= w;
      factorial *= double(n + 3);
    }
    return sum;
  }
  const std::complex<double> e = std::exp(-w);
  return 0.5 + e / w + (e - 1.0) / (w * w);
}

}  // namespace

double anomalous_diffraction_extinction_efficiency(double wavelength_nm, std::complex<double> index, double radius_m) {
  const double lambda_m = wavelength_nm * 1e-9;
  const double m_minus_1 = index.real() - 1.0;
  const double rho = 4.0 * kPi * radius_m * m_minus_1 / lambda_m;
  const double tan_beta = index.imag() / m_minus_1;
  return 4.0 * ada_kernel(std::complex<double>(rho * tan_beta, rho)).real();
}

double anomalous_diffraction_absorption_efficiency(double wavelength_nm, double imag_index, double radius_m) {
  const double y = 4.0 * kPi * radius_m * imag_index / (wavelength_nm * 1e-9);
  if (y < 1e-3) return 4.0 * y / 3.0 - y * y;  // series: 4y/3 − y² + 8y³/15 − ...
  const double e = std::exp(-2.0 * y);
  return 1.0 + e / y + (e - 1.0) / (2.0 * y * y);
}

double mie_extinction_anomalous_diffraction(double wavelength_nm, std::complex<double> index, double mean_radius_m,
                                            double number_density_m3) {
  return kPi * mean_radius_m * mean_radius_m *
         anomalous_diffraction_extinction_efficiency(wavelength_nm, index, mean_radius_m) * number_density_m3;
}

}  // namespace zenith::atmosphere
