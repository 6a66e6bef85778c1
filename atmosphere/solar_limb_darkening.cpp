#include "atmosphere/solar_limb_darkening.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "atmosphere/reference_data.h"
#include "core/strings.h"

namespace zenith::atmosphere {

double LimbDarkening::intensity(double mu) const {
  const double m = std::clamp(mu, 0.0, 1.0);
  double sum = 0.0;  // Horner: a_0 + μ (a_1 + μ (a_2 + …))
  for (std::size_t k = coefficients.size(); k-- > 0;) sum = coefficients[k] + m * sum;
  return sum;
}

double LimbDarkening::mean_over_centre() const {
  double m = 0.0;
  for (std::size_t k = 0; k < coefficients.size(); ++k) m += 2.0 * coefficients[k] / double(k + 2);
  return m;
}

LimbDarkening solar_limb_darkening(double wavelength_nm) {
  if (!(wavelength_nm >= 100.0 && wavelength_nm <= 10000.0))
    throw std::invalid_argument(
        core::cat("limb darkening: wavelength ", wavelength_nm, " nm must be in [100, 10000] nm"));
  const std::vector<LimbDarkeningRow>& rows = neckel_labs_1994_limb_darkening();
  const auto above = std::lower_bound(rows.begin(), rows.end(), wavelength_nm,
                                      [](const LimbDarkeningRow& r, double nm) { return r.wavelength_nm < nm; });
  const LimbDarkeningRow& lo = above == rows.begin() ? rows.front() : *(above - 1);
  const LimbDarkeningRow& hi = above == rows.end() ? rows.back() : *above;
  const double t =
      hi.wavelength_nm > lo.wavelength_nm
          ? std::clamp((wavelength_nm - lo.wavelength_nm) / (hi.wavelength_nm - lo.wavelength_nm), 0.0, 1.0)
          : 0.0;
  LimbDarkening law;
  double sum = 0.0;
  for (std::size_t k = 0; k < law.coefficients.size(); ++k) {
    law.coefficients[k] = (1.0 - t) * lo.coefficients[k] + t * hi.coefficients[k];
    sum += law.coefficients[k];
  }
  // The printed coefficients sum to 1 within 2e-5; I(1)/I(1) = 1 exactly.
  for (double& a : law.coefficients) a /= sum;
  return law;
}

std::vector<LimbDarkening> solar_limb_darkening(const std::vector<double>& wavelengths_nm) {
  std::vector<LimbDarkening> laws;
  for (double nm : wavelengths_nm) laws.push_back(solar_limb_darkening(nm));
  return laws;
}

void check_limb_darkening(const LimbDarkening& law, std::string_view who) {
  double sum = 0.0;
  for (double a : law.coefficients) {
    if (!std::isfinite(a))
      throw std::invalid_argument(core::cat(who, ": limb darkening coefficient ", a, " is not finite"));
    sum += a;
  }
  if (!(std::abs(sum - 1.0) <= 1e-3))
    throw std::invalid_argument(core::cat(who, ": limb darkening coefficients sum to ", sum, ", not 1 (within 1e-3)"));
  for (int i = 0; i <= 10; ++i)
    if (!(law.intensity(0.1 * i) >= 0.0))
      throw std::invalid_argument(core::cat(who, ": limb darkening I(mu)/I(1) is negative at mu = ", 0.1 * i));
}

}  // namespace zenith::atmosphere
