#include "atmosphere/rayleigh_polarization.h"

#include <glm/matrix.hpp>

namespace zenith::atmosphere {

Mat3 transverse_projector(const Vec3& k) { return Mat3(1.0) - glm::outerProduct(k, k); }

double contract(const Mat3& a, const Mat3& b) {
  double sum = 0.0;
  for (int column = 0; column < 3; ++column) sum += dot(a[column], b[column]);
  return sum;
}

double dipole_share(double depolarization) { return (1.0 - depolarization) / (1.0 + 0.5 * depolarization); }

double depolarized_rayleigh_shape(double delta, double cos_scattering) {
  return delta * 0.75 * (1.0 + cos_scattering * cos_scattering) + (1.0 - delta);
}

Mat3 rayleigh_scattered_coherency(double delta, const Vec3& k_out, const Mat3& t_in) {
  const Mat3 across_out = transverse_projector(k_out);
  return delta * 1.5 * (across_out * t_in * across_out) +
         (1.0 - delta) * 0.5 * (t_in[0][0] + t_in[1][1] + t_in[2][2]) * across_out;
}

Mat3 rayleigh_scattered_importance(double delta, const Vec3& k_out, const Mat3& m_out) {
  const Mat3 across_out = transverse_projector(k_out);
  return delta * 1.5 * (across_out * m_out * across_out) +
         (1.0 - delta) * 0.5 * contract(m_out, across_out) * Mat3(1.0);
}

Mat3 once_scattered_rayleigh_coherency(double delta, const Vec3& k_in, const Vec3& k_out) {
  return rayleigh_scattered_coherency(delta, k_out, 0.5 * transverse_projector(k_in)) /
         depolarized_rayleigh_shape(delta, dot(k_in, k_out));
}

}  // namespace zenith::atmosphere
