#pragma once
// Exact single scattering along a view ray, by adaptive quadrature: the
// deterministic half of the reference solver.
//
// For an observer at x looking along v, with the sun a POINT in direction s at
// the centre of its disc (irradiance 1 per wavelength, see sun_disc.h):
//
//   L1(x, v) = ∫_{t0}^{t1} T(x, y) [β_R(y) P_R(ν) + β_M(y) P_M(ν)] T_sun(y) dt     [sr^-1]
//
// with y = x + t v, ν = v·s the cosine of the scattering angle, β the
// unstretched scattering coefficients (paper eq. 1), T(x, y) = exp(−s_v τ(x, y))
// the view ray's transmittance with its stretch s_v, and T_sun(y) the
// transmittance to the sun from y (0 where the planet hides the sun's centre:
// the point-sun shadow, whose boundary along the ray is found analytically and
// used as a breakpoint). [t0, t1] is the part of the ray in the atmosphere; an
// observer outside it starts where the ray enters. The finite disc is not
// integrated over: the difference to a disc-averaged L1 is of order α² away from
// the sun's aureole and from the shadow boundary (α the angular radius).
//
// Ground term, returned separately (rays that hit the ground at g with normal n):
//   L_ground = T(x, g) · (a/π) · max(0, n·s) · T_sun(g)                         [sr^-1]
// (Lambertian albedo a, direct sun only). L1 + L_ground is the order-1 part of
// the path tracer's sky radiance.
#include <cstddef>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/reference/optical_depth.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

/// The tolerances of the outer (along-the-ray) quadrature, per wavelength:
/// error estimate ≤ max(absolute_tolerance, relative_tolerance · L1).
struct SingleScatteringOptions : QuadratureOptions {
  SingleScatteringOptions()
      : QuadratureOptions{.relative_tolerance = 1e-7, .absolute_tolerance = 1e-16, .max_panels = 4000} {}
  /// Tolerances of the optical depths evaluated at every node.
  OpticalDepthOptions optical_depth;
};

struct SingleScatteringResult {
  Spectrum atmosphere_radiance;  ///< L1 [sr^-1 per unit solar irradiance]
  Spectrum atmosphere_error;     ///< the quadrature's error estimate of L1 [sr^-1]
  Spectrum ground_radiance;      ///< L_ground; zero unless ray_hits_ground [sr^-1]
  bool ray_hits_ground = false;
  bool converged = false;       ///< the quadrature met its tolerance
  std::size_t evaluations = 0;  ///< integrand evaluations of the outer quadrature
};

/// L1 and L_ground for an observer at `observer_m` (planet-centred, at or above
/// the ground) looking along `view_direction`, with the sun's centre in
/// `sun_direction`. Directions need not be normalized. A ray that misses the
/// atmosphere gives zeros.
SingleScatteringResult single_scattering_radiance(const AtmosphereModel& model, const Vec3& observer_m,
                                                  const Vec3& view_direction, const Vec3& sun_direction,
                                                  const SingleScatteringOptions& options = {});

}  // namespace zenith::atmosphere::reference
