#pragma once
// Local frames and the direction distributions the path tracer samples.
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

/// Right-handed orthonormal basis (u, v, w) with w a given unit vector (the
/// branchless construction of Duff et al. 2017, valid for every w).
struct Frame {
  Vec3 u{}, v{}, w{};
  static Frame around(const Vec3& w);
  /// x u + y v + z w.
  Vec3 to_world(double x, double y, double z) const { return x * u + y * v + z * w; }
};

/// Unit vector at angle θ from `axis` (cos θ given) and azimuth φ = 2π u [rad].
Vec3 direction_with_cosine(const Vec3& axis, double cos_theta, double u);

/// Cosine-weighted direction on the hemisphere around `normal`
/// (pdf cos θ / π [sr^-1]), from two uniform numbers in [0, 1).
Vec3 sample_cosine_hemisphere(const Vec3& normal, double u1, double u2);

}  // namespace zenith::atmosphere::reference
