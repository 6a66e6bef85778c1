#pragma once
// A minimal double-precision 3-vector for planet-frame geometry (metres).
// Positions are planet-centred: the planet's centre is the origin.
#include <cmath>

namespace zenith::atmosphere {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  friend constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }
  constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) { return *this = *this + o; }
};

constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3 normalize(const Vec3& v) { return v / length(v); }

/// Unit vector from a zenith angle and an azimuth [rad] in the local frame of a
/// point on the +z axis: z is up (zenith), x is azimuth 0, y is azimuth 90°.
inline Vec3 direction_from_angles(double zenith_rad, double azimuth_rad) {
  const double s = std::sin(zenith_rad);
  return {s * std::cos(azimuth_rad), s * std::sin(azimuth_rad), std::cos(zenith_rad)};
}

}  // namespace zenith::atmosphere
