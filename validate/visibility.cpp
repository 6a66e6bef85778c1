#include "validate/visibility.h"

#include <cmath>

namespace zenith::validate {

double nanolamberts_from_v_mag_arcsec2(double mu) { return 34.08 * std::exp(20.7233 - 0.92104 * mu); }

double naked_eye_limiting_magnitude(double sky_v_mag_arcsec2) {
  const double b = nanolamberts_from_v_mag_arcsec2(sky_v_mag_arcsec2);
  const bool scotopic = b < 1479.0;
  const double c = std::pow(10.0, scotopic ? -9.80 : -8.35);
  const double k = std::pow(10.0, scotopic ? -1.90 : -5.90);
  const double root = 1.0 + std::sqrt(k * b);
  const double illuminance_ft_cd = c * root * root;
  return -16.57 - 2.5 * std::log10(illuminance_ft_cd);
}

}  // namespace zenith::validate
