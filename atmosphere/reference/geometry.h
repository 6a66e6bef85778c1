#pragma once
// Ray–sphere geometry of a spherical planet with a spherical-shell atmosphere,
// in double precision, robust from 1 m above the ground to 40 AU away and for
// rays within 1e-6 rad of the horizon.
//
// Positions are planet-centred [m]; directions are unit vectors. A ray is
// x(t) = origin + t·direction, t ≥ 0 the distance along it [m].
#include <optional>
#include <vector>

#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

/// A straight ray stored together with its closest approach to the planet's
/// centre (its perigee). Points are computed as
///   x(t) = perigee_point + (t − perigee_t)·direction,
///   r(t) = √(p² + (t − perigee_t)²),
/// which involves only small numbers near the planet, so positions stay accurate
/// to ~1e-3 m even when the origin is 40 AU (6e12 m) away. Sphere crossings use
/// ρ² − p² = (ρ − p)(ρ + p), free of cancellation for rays that graze a sphere
/// (near the planet p is known to ~1e-9 m, so a ground hit 1e-6 rad below the
/// horizon is placed to ~1e-5 m).
class Ray {
 public:
  /// `direction` need not be normalized (it is normalized here); throws
  /// std::invalid_argument for a zero or non-finite direction.
  Ray(const Vec3& origin_m, const Vec3& direction);

  const Vec3& origin_m() const { return origin_m_; }
  const Vec3& direction() const { return direction_; }
  /// t_c = −origin·direction: distance along the ray to its perigee (negative
  /// when the ray already moves away from the centre).
  double perigee_t_m() const { return perigee_t_m_; }
  /// The point of the line closest to the planet's centre.
  const Vec3& perigee_point_m() const { return perigee_point_m_; }
  /// p = |perigee point|, the impact parameter [m]; constant along the line.
  double impact_parameter_m() const { return impact_parameter_m_; }

  /// x(t) [m].
  Vec3 point_at(double t_m) const { return perigee_point_m_ + (t_m - perigee_t_m_) * direction_; }
  /// r(t) = |x(t)| [m].
  double radius_at(double t_m) const;
  /// Cosine of the zenith angle of the ray at x(t): μ(t) = (t − t_c)/r(t).
  double cos_zenith_at(double t_m) const;

  /// The two parameters t_c ∓ √(ρ² − p²) where the line crosses the sphere of
  /// radius ρ, or nothing when p ≥ ρ (a ray tangent to a sphere does not cross it).
  struct SphereCrossings {
    double entry_t_m, exit_t_m;
  };
  std::optional<SphereCrossings> sphere_crossings(double radius_m) const;

 private:
  Vec3 origin_m_{}, direction_{};
  double perigee_t_m_ = 0.0;
  Vec3 perigee_point_m_{};
  double impact_parameter_m_ = 0.0;
};

/// The part of a ray, from parameter t_min on, that lies inside the atmosphere
/// shell R_ground ≤ r ≤ R_top and before the ground.
struct AtmosphereInterval {
  bool intersects = false;      ///< false: the ray misses the shell (or has left it) after t_min
  double begin_t_m = 0.0;       ///< where the ray is first inside the shell (t_min if it starts inside)
  double end_t_m = 0.0;         ///< where it leaves the top, or hits the ground
  bool ends_on_ground = false;  ///< end_t_m is on the ground sphere
};

/// The atmosphere interval of `ray` from t_min. The ground is hit iff the ray is
/// still moving toward the centre at t_min (t_min < t_c) and p < R_ground; a ray
/// that starts a hair below the ground sphere and points away from the centre
/// (a path leaving the ground after a bounce) does not hit it again.
AtmosphereInterval atmosphere_interval(const Ray& ray, double ground_radius_m, double top_radius_m,
                                       double t_min_m = 0.0);

/// Whether the ray from radius r [m] with cosine μ of its zenith angle hits the
/// sphere of radius R ≤ r: μ < 0 and r²μ² − (r − R)(r + R) > 0 (tangent rays miss).
bool ray_hits_ground(double r_m, double mu, double ground_radius_m);

/// Distance [m] from radius r ≥ R along cosine μ to the ground sphere R:
///   d = (r − R)(r + R) / (−rμ + √(r²μ² − (r − R)(r + R)))   (the near root, without cancellation).
/// Only meaningful when ray_hits_ground(r, μ, R); returns +∞ otherwise.
double distance_to_ground_m(double r_m, double mu, double ground_radius_m);

/// Distance [m] from radius r along cosine μ to where the ray leaves the top
/// sphere R_top. Inside (r ≤ R_top): d = −rμ + √(r²μ² + (R_top − r)(R_top + r)).
/// Outside: the far root of the entry chord, or +∞ if the ray misses the sphere.
/// The (r, μ) form loses precision for r ≫ R_top (μ cannot resolve a planet
/// 1e-6 rad wide); use Ray for distant observers.
double distance_to_top_of_atmosphere_m(double r_m, double mu, double top_radius_m);

/// Distance [m] from radius r > R_top along cosine μ to where the ray enters the
/// top sphere (near root, cancellation-free), or +∞ if it misses; 0 if r ≤ R_top.
double distance_to_atmosphere_entry_m(double r_m, double mu, double top_radius_m);

/// Parameters t > t_min where the ray crosses the boundary of the planet's
/// shadow for a point sun in direction `sun_direction` (unit): the half-cylinder
/// |x − (x·s)s| = R_ground, x·s < 0. Outside the planet this surface is the whole
/// boundary of the shadow, so the sun's visibility along the ray changes only
/// there. Sorted ascending.
std::vector<double> planet_shadow_crossings_t_m(const Ray& ray, const Vec3& sun_direction, double ground_radius_m,
                                                double t_min_m = 0.0);

/// Parameters where the ray crosses the spheres of the given radii, within
/// (t_min, t_max); sorted ascending. Used as quadrature breakpoints.
std::vector<double> sphere_crossings_t_m(const Ray& ray, const std::vector<double>& radii_m, double t_min_m,
                                         double t_max_m);

}  // namespace zenith::atmosphere::reference
