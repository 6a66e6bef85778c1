#include "atmosphere/reference/polarization.h"

#include <cmath>

#include <glm/matrix.hpp>

namespace zenith::atmosphere::reference {

namespace {

/// [K]v = axis × v.
Mat3 cross_product_matrix(const Vec3& axis) {
  // GLM is column-major: the three arguments of each line are one column.
  return Mat3(0.0, axis.z, -axis.y,  //
              -axis.z, 0.0, axis.x,  //
              axis.y, -axis.x, 0.0);
}

}  // namespace

Mat3 rotation_between(const Vec3& k_in, const Vec3& k_out) {
  const Vec3 axis = cross(k_in, k_out);
  const double sine = length(axis), cosine = dot(k_in, k_out);
  if (sine < 1e-12) {
    if (cosine > 0.0) return Mat3(1.0);
    // Backward: a half turn about any axis across k_in, R = 2 a aᵀ − 1.
    const Vec3 helper = std::abs(k_in.x) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
    const Vec3 a = normalize(cross(k_in, helper));
    return 2.0 * glm::outerProduct(a, a) - Mat3(1.0);
  }
  // Rodrigues: R = 1 + sin θ K + (1 − cos θ) K², K the cross product with the unit axis.
  const Mat3 k = cross_product_matrix(axis / sine);
  return Mat3(1.0) + sine * k + (1.0 - cosine) * (k * k);
}

Mat3 scattered_coherency(const PolarizedScatterers& s, const Vec3& k_in, const Vec3& k_out, const Mat3& t_in) {
  const double delta = atmosphere::dipole_share(s.depolarization);
  Mat3 out(0.0);
  if (s.rayleigh_m1_sr1 > 0.0)
    out += (s.rayleigh_m1_sr1 / atmosphere::depolarized_rayleigh_shape(delta, dot(k_in, k_out))) *
           atmosphere::rayleigh_scattered_coherency(delta, k_out, t_in);
  if (s.aerosol_m1_sr1 > 0.0) {
    if (s.aerosol_depolarizes) {
      out += (0.5 * s.aerosol_m1_sr1 * contract(Mat3(1.0), t_in)) * transverse_projector(k_out);
    } else {
      const Mat3 r = rotation_between(k_in, k_out);
      out += s.aerosol_m1_sr1 * (r * t_in * glm::transpose(r));
    }
  }
  return out;
}

Mat3 scattered_importance(const PolarizedScatterers& s, const Vec3& k_in, const Vec3& k_out, const Mat3& m_out) {
  const double delta = atmosphere::dipole_share(s.depolarization);
  Mat3 in(0.0);
  if (s.rayleigh_m1_sr1 > 0.0)
    in += (s.rayleigh_m1_sr1 / atmosphere::depolarized_rayleigh_shape(delta, dot(k_in, k_out))) *
          atmosphere::rayleigh_scattered_importance(delta, k_out, m_out);
  if (s.aerosol_m1_sr1 > 0.0) {
    if (s.aerosol_depolarizes) {
      // The adjoint of T ↦ tr(T) Π_out/2: M ↦ ⟨M, Π_out⟩/2 · 1.
      in += (0.5 * s.aerosol_m1_sr1 * contract(m_out, transverse_projector(k_out))) * Mat3(1.0);
    } else {
      const Mat3 r = rotation_between(k_in, k_out);
      in += s.aerosol_m1_sr1 * (glm::transpose(r) * m_out * r);
    }
  }
  return in;
}

}  // namespace zenith::atmosphere::reference
