#include "atmosphere/reference/single_scattering.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "atmosphere/constants.h"
#include "atmosphere/reference/adaptive_quadrature.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/medium.h"

namespace zenith::atmosphere::reference {

SingleScatteringResult single_scattering_radiance(const AtmosphereModel& model, const Vec3& observer_m,
                                                  const Vec3& view_direction, const Vec3& sun_direction,
                                                  const SingleScatteringOptions& options) {
  const std::size_t n = model.wavelength_count();
  if (length(observer_m) < model.ground_radius_m * (1.0 - 1e-12))
    throw std::invalid_argument("single_scattering_radiance: observer below the ground");
  const Vec3 sun = normalize(sun_direction);
  SingleScatteringResult result;
  result.atmosphere_radiance = Spectrum(n);
  result.atmosphere_error = Spectrum(n);
  result.ground_radiance = Spectrum(n);

  const Ray observer_ray(observer_m, view_direction);
  const AtmosphereInterval interval = atmosphere_interval(observer_ray, model.ground_radius_m, model.top_radius_m);
  if (!interval.intersects) {
    result.converged = true;
    return result;
  }
  // Re-base the ray where it enters the atmosphere (the observer itself when inside).
  const Ray ray(observer_ray.point_at(interval.begin_t_m), observer_ray.direction());
  const double t_end = interval.end_t_m - interval.begin_t_m;
  result.ray_hits_ground = interval.ends_on_ground;

  const double cos_scattering = dot(ray.direction(), sun);
  const double rayleigh_phase = model.rayleigh_phase_function(cos_scattering);
  std::vector<double> mie_phase(n);
  for (std::size_t i = 0; i < n; ++i) mie_phase[i] = model.has_mie() ? model.mie_phase(i, cos_scattering) : 0.0;

  const AtmosphereMedium medium(model);
  std::vector<LocalCoefficients> local(n);
  const VectorIntegrand integrand = [&](double t, std::span<double> value) {
    const Vec3 y = ray.point_at(t);
    const Spectrum sun_transmittance = transmittance_to_sun(model, y, sun, options.optical_depth);
    if (sun_transmittance.all_zero()) {
      std::fill(value.begin(), value.end(), 0.0);
      return;
    }
    const Spectrum view_depth = optical_depth_along_ray(model, ray, 0.0, t, options.optical_depth);
    medium.coefficients(ray.radius_at(t) - model.ground_radius_m, local);
    for (std::size_t i = 0; i < n; ++i)
      value[i] = std::exp(-view_depth[i]) * sun_transmittance[i] *
                 (local[i].rayleigh_scattering_m1 * rayleigh_phase + local[i].mie_scattering_m1 * mie_phase[i]);
  };

  // Breakpoints: the ends, the perigee, the shadow boundary and the fixed altitude levels.
  std::vector<double> breakpoints = {0.0, t_end};
  if (ray.perigee_t_m() > 0.0 && ray.perigee_t_m() < t_end) breakpoints.push_back(ray.perigee_t_m());
  for (double t : planet_shadow_crossings_t_m(ray, sun, model.ground_radius_m, 0.0))
    if (t < t_end) breakpoints.push_back(t);
  for (double t : sphere_crossings_t_m(ray, quadrature_breakpoint_radii_m(model), 0.0, t_end)) breakpoints.push_back(t);
  std::sort(breakpoints.begin(), breakpoints.end());

  const QuadratureResult integral = integrate_adaptive(integrand, breakpoints, n, options);
  for (std::size_t i = 0; i < n; ++i) {
    result.atmosphere_radiance[i] = integral.integral[i];
    result.atmosphere_error[i] = integral.error_estimate[i];
  }
  result.converged = integral.converged;
  result.evaluations = integral.evaluations;

  if (interval.ends_on_ground) {
    const Vec3 ground_point = ray.point_at(t_end);
    const double cos_sun = dot(normalize(ground_point), sun);
    if (cos_sun > 0.0) {
      const Spectrum view_depth = optical_depth_along_ray(model, ray, 0.0, t_end, options.optical_depth);
      const Spectrum sun_transmittance = transmittance_to_sun(model, ground_point, sun, options.optical_depth);
      for (std::size_t i = 0; i < n; ++i)
        result.ground_radiance[i] =
            std::exp(-view_depth[i]) * model.ground_albedo[i] / kPi * cos_sun * sun_transmittance[i];
    }
  }
  return result;
}

}  // namespace zenith::atmosphere::reference
