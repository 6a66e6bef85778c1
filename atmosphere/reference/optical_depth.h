#pragma once
// Optical depth and transmittance along straight segments, by adaptive
// Gauss–Kronrod quadrature of the model's extinction (paper eq. 1 and 5).
//
// Air-mass convention (docs/physics.md, "Pickering air mass"): the stretch s ≥ 1
// of the model multiplies the optical depth of a straight ray and is constant
// along it (it depends only on the ray's impact parameter):
//   τ(x, y) = s · ∫_x^y β_ext(h(t)) dt,     T(x, y) = exp(−τ(x, y)).
// s is obtained from AtmosphereModel::air_mass(r, μ) at the point of the segment
// closest to the ray's perigee, the same point for both directions of travel,
// so τ(x, y) = τ(y, x) to rounding.
//
// Only the spherical shell R_ground ≤ r ≤ R_top is atmosphere: the parts of a
// segment above the top contribute nothing.
#include <cstddef>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/reference/adaptive_quadrature.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

/// The quadrature's tolerances for optical depths: per wavelength, it stops
/// when its error estimate is below max(absolute_tolerance, relative_tolerance · τ).
struct OpticalDepthOptions : QuadratureOptions {
  OpticalDepthOptions()
      : QuadratureOptions{.relative_tolerance = 1e-10, .absolute_tolerance = 1e-13, .max_panels = 2000} {}
};

/// The stretch s of the straight line carrying `ray`, evaluated with
/// model.air_mass(r, μ) at the point of [begin_t, end_t] nearest the perigee
/// (identical for both directions of travel). 1 when the model has no stretch.
double optical_depth_stretch(const AtmosphereModel& model, const Ray& ray, double begin_t_m, double end_t_m);

/// Altitudes where the reference solver's quadratures always cut a ray (its
/// integrands change fastest low down): h_k = H_atm (k/8)², k = 1..7, as radii [m].
std::vector<double> quadrature_breakpoint_radii_m(const AtmosphereModel& model);

/// The radii where optical-depth quadrature cuts a ray: quadrature_breakpoint_radii_m
/// plus every knot altitude of the model's tabulated profiles (ozone). A PCHIP
/// profile is only C¹ at its knots; between them β_ext is analytic along the ray,
/// so Gauss–Kronrod converges at once instead of bisecting toward each knot.
std::vector<double> optical_depth_breakpoint_radii_m(const AtmosphereModel& model);

/// τ(t0 → t1) along `ray` [dimensionless], per wavelength, including the stretch:
///   τ_i = s ∫_{t0}^{t1} β_ext,i(r(t) − R_ground) dt.
/// The range is clipped to the top sphere; the ground is not checked (the caller
/// keeps [t0, t1] above it, e.g. with atmosphere_interval). The integral is cut at
/// the perigee and at optical_depth_breakpoint_radii_m.
Spectrum optical_depth_along_ray(const AtmosphereModel& model, const Ray& ray, double t0_m, double t1_m,
                                 const OpticalDepthOptions& options = {});

/// τ of the segment from → to [dimensionless], per wavelength. A segment that
/// passes through the solid planet (more than 1 mm of it below the ground
/// sphere) is opaque: every value is +∞. Endpoints may lie anywhere, including
/// outside the atmosphere (e.g. 40 AU away).
Spectrum optical_depth(const AtmosphereModel& model, const Vec3& from_m, const Vec3& to_m,
                       const OpticalDepthOptions& options = {});

/// T(from, to) = exp(−τ(from, to)); reciprocal: T(a, b) = T(b, a).
Spectrum transmittance(const AtmosphereModel& model, const Vec3& from_m, const Vec3& to_m,
                       const OpticalDepthOptions& options = {});

/// Transmittance from `point_m` to the sun, treated as a point in direction
/// `sun_direction` (unit): exp(−τ) to the top of the atmosphere, 0 when the ray
/// toward the sun hits the ground (point-sun visibility), 1 when it never
/// crosses the atmosphere.
Spectrum transmittance_to_sun(const AtmosphereModel& model, const Vec3& point_m, const Vec3& sun_direction,
                              const OpticalDepthOptions& options = {});

}  // namespace zenith::atmosphere::reference
