#pragma once
// The astronomy layer's direction vectors: three doubles (unit vectors on
// J2000/GCRS or horizon axes, as each caller says) and the few operations the
// catalogue, its zones and the Moon's axes need. Header-only; no GLM in astro.
#include <array>
#include <cmath>

namespace zenith::astro {

using Vec3d = std::array<double, 3>;

inline double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// v / |v| (v ≠ 0).
inline Vec3d normalized(const Vec3d& v) {
  const double n = std::sqrt(dot(v, v));
  return {v[0] / n, v[1] / n, v[2] / n};
}

}  // namespace zenith::astro
