#include "atmosphere/phase_functions.h"

#include <cmath>

#include "atmosphere/constants.h"

namespace zenith::atmosphere {

double rayleigh_phase_classic(double cos_theta) { return 0.75 * (1.0 + cos_theta * cos_theta) * kInv4Pi; }

double rayleigh_phase_penndorf(double cos_theta) {
  return kPenndorfA * (1.0 + kPenndorfB * cos_theta * cos_theta) * kInv4Pi;
}

double rayleigh_phase_depolarized(double cos_theta, double depolarization) {
  const double gamma = depolarization / (2.0 - depolarization);
  return 3.0 / (4.0 * (1.0 + 2.0 * gamma)) * ((1.0 + 3.0 * gamma) + (1.0 - gamma) * cos_theta * cos_theta) * kInv4Pi;
}

double henyey_greenstein(double cos_theta, double g) {
  const double denom = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (denom * std::sqrt(denom)) * kInv4Pi;
}

double double_henyey_greenstein(double cos_theta, double g1, double g2, double alpha) {
  return alpha * henyey_greenstein(cos_theta, g1) + (1.0 - alpha) * henyey_greenstein(cos_theta, g2);
}

double cornette_shanks(double cos_theta, double g) {
  const double denom = 1.0 + g * g - 2.0 * g * cos_theta;
  return 3.0 * (1.0 - g * g) * (1.0 + cos_theta * cos_theta) / (2.0 * (2.0 + g * g) * denom * std::sqrt(denom)) *
         kInv4Pi;
}

}  // namespace zenith::atmosphere
