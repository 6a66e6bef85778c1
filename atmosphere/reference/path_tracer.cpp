#include "atmosphere/reference/path_tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/matrix.hpp>

#include "atmosphere/constants.h"
#include "atmosphere/reference/direction_sampling.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/parallel_estimator.h"
#include "atmosphere/reference/path_integrator.h"

namespace zenith::atmosphere::reference {

namespace {

PathSettings path_settings(const PathTracerOptions& o) {
  if (o.samples_per_wavelength == 0)
    throw std::invalid_argument("PathTracerOptions: samples_per_wavelength must be > 0");
  PathSettings s;
  s.min_scattering_order = o.min_scattering_order;
  s.max_scattering_order = o.max_scattering_order;
  s.russian_roulette_start_order = o.russian_roulette_start_order;
  s.majorant_shell_count = o.majorant_shell_count;
  s.polarized = o.polarized;
  s.aerosol_depolarizes = o.aerosol_depolarizes;
  return s;
}

ParallelEstimatorSettings estimator_settings(const AtmosphereModel& model, const PathTracerOptions& o,
                                             std::size_t components) {
  ParallelEstimatorSettings s;
  s.wavelength_count = model.wavelength_count();
  s.samples_per_wavelength = o.samples_per_wavelength;
  s.components = components;
  s.seed = o.seed;
  s.thread_count = o.thread_count;
  return s;
}

/// The view ray from where it enters the atmosphere (the observer's own point when inside it); none where
/// it misses the atmosphere. Throws std::invalid_argument naming `caller` for an observer below the ground.
std::optional<Ray> view_ray_in_atmosphere(const AtmosphereModel& model, const Vec3& observer_m,
                                          const Vec3& view_direction, const char* caller) {
  if (length(observer_m) < model.ground_radius_m * (1.0 - 1e-12))
    throw std::invalid_argument(std::string(caller) + ": observer below the ground");
  const Ray observer_ray(observer_m, view_direction);
  const AtmosphereInterval interval = atmosphere_interval(observer_ray, model.ground_radius_m, model.top_radius_m);
  if (!interval.intersects) return std::nullopt;
  return Ray(observer_ray.point_at(interval.begin_t_m), observer_ray.direction());
}

/// Runs `sample(integrator, wavelength, rng, values, violations)` for every path of every wavelength, all on
/// one PathIntegrator, each path writing `components` values; the majorant violations are counted into
/// `majorant_violations`.
template <class PathSample>
SampleMoments run_paths(const AtmosphereModel& model, const SunDisc& sun, const PathSettings& settings,
                        const PathTracerOptions& options, std::size_t components, std::size_t& majorant_violations,
                        const PathSample& sample) {
  const PathIntegrator integrator(model, sun, settings);
  std::atomic<std::size_t> violations{0};
  SampleMoments moments = run_parallel_estimator(estimator_settings(model, options, components),
                                                 [&](std::size_t i, std::size_t, Pcg32& rng, std::span<double> values) {
                                                   std::size_t local_violations = 0;
                                                   sample(integrator, i, rng, values, local_violations);
                                                   if (local_violations != 0) violations += local_violations;
                                                 });
  majorant_violations = violations;
  return moments;
}

}  // namespace

RadianceEstimate path_traced_radiance(const AtmosphereModel& model, const Vec3& observer_m, const Vec3& view_direction,
                                      const SunDisc& sun, const PathTracerOptions& options) {
  const PathSettings settings = path_settings(options);
  const std::size_t n = model.wavelength_count();
  const std::optional<Ray> view = view_ray_in_atmosphere(model, observer_m, view_direction, "path_traced_radiance");
  RadianceEstimate estimate;
  estimate.mean = Spectrum(n);
  estimate.standard_error = Spectrum(n);
  estimate.samples = options.samples_per_wavelength;
  if (!view) return estimate;
  const Ray& first_ray = *view;

  const SampleMoments moments =
      run_paths(model, sun, settings, options, 1, estimate.majorant_violations,
                [&](const PathIntegrator& integrator, std::size_t i, Pcg32& rng, std::span<double> values,
                    std::size_t& violations) { values[0] = integrator.radiance(first_ray, i, rng, violations); });
  for (std::size_t i = 0; i < n; ++i) {
    estimate.mean[i] = moments.mean[i];
    estimate.standard_error[i] = moments.standard_error[i];
  }
  return estimate;
}

StokesEstimate path_traced_stokes(const AtmosphereModel& model, const Vec3& observer_m, const Vec3& view_direction,
                                  const Vec3& reference_axis, const SunDisc& sun, const PathTracerOptions& options) {
  if (!options.polarized)
    throw std::invalid_argument("path_traced_stokes: the light's polarization needs PathTracerOptions::polarized");
  const PathSettings settings = path_settings(options);
  const std::size_t n = model.wavelength_count();
  const std::optional<Ray> view = view_ray_in_atmosphere(model, observer_m, view_direction, "path_traced_stokes");
  const Vec3 v = normalize(view_direction);
  const Vec3 across = reference_axis - dot(reference_axis, v) * v;
  if (!(length(across) > 1e-9 * length(reference_axis)))
    throw std::invalid_argument("path_traced_stokes: the reference axis lies along the view direction");
  const Vec3 e1 = normalize(across), e2 = cross(e1, v);
  const Mat3 intensity(1.0);
  const Mat3 stokes_q = glm::outerProduct(e1, e1) - glm::outerProduct(e2, e2);
  const Mat3 stokes_u = glm::outerProduct(e1, e2) + glm::outerProduct(e2, e1);

  StokesEstimate estimate;
  estimate.i = estimate.q = estimate.u = Spectrum(n);
  estimate.i_standard_error = estimate.q_standard_error = estimate.u_standard_error = Spectrum(n);
  estimate.samples = options.samples_per_wavelength;
  if (!view) return estimate;
  const Ray& first_ray = *view;

  const SampleMoments moments =
      run_paths(model, sun, settings, options, 3, estimate.majorant_violations,
                [&](const PathIntegrator& integrator, std::size_t i, Pcg32& rng, std::span<double> values,
                    std::size_t& violations) {
                  // One path for the three analysers: each starts from the same generator state.
                  Pcg32 q_rng = rng, u_rng = rng;
                  std::size_t same_path = 0;
                  values[0] = integrator.analysed_radiance(first_ray, intensity, i, rng, violations);
                  values[1] = integrator.analysed_radiance(first_ray, stokes_q, i, q_rng, same_path);
                  values[2] = integrator.analysed_radiance(first_ray, stokes_u, i, u_rng, same_path);
                });
  for (std::size_t i = 0; i < n; ++i) {
    estimate.i[i] = moments.mean[i];
    estimate.i_standard_error[i] = moments.standard_error[i];
    estimate.q[i] = moments.mean[n + i];
    estimate.q_standard_error[i] = moments.standard_error[n + i];
    estimate.u[i] = moments.mean[2 * n + i];
    estimate.u_standard_error[i] = moments.standard_error[2 * n + i];
  }
  return estimate;
}

double degree_of_linear_polarization(double i, double q, double u) { return i > 0.0 ? std::hypot(q, u) / i : 0.0; }

double polarization_angle_rad(double q, double u) { return 0.5 * std::atan2(u, q); }

GroundIrradianceEstimate ground_irradiance(const AtmosphereModel& model, const Vec3& ground_point_m, const SunDisc& sun,
                                           const PathTracerOptions& options) {
  const PathSettings settings = path_settings(options);
  const std::size_t n = model.wavelength_count();
  if (!(length(ground_point_m) > 0.0)) throw std::invalid_argument("ground_irradiance: point at the planet's centre");
  const Vec3 normal = normalize(ground_point_m);
  const Vec3 point = model.ground_radius_m * normal;

  GroundIrradianceEstimate estimate;
  const SampleMoments moments =
      run_paths(model, sun, settings, options, 3, estimate.majorant_violations,
                [&](const PathIntegrator& integrator, std::size_t i, Pcg32& rng, std::span<double> values,
                    std::size_t& violations) {
                  const double direct = integrator.direct_irradiance(point, normal, i, rng, violations);
                  const double u1 = rng.uniform(), u2 = rng.uniform();
                  const Ray sky_ray(point, sample_cosine_hemisphere(normal, u1, u2));
                  const double diffuse = kPi * integrator.radiance(sky_ray, i, rng, violations);
                  values[0] = direct;
                  values[1] = diffuse;
                  values[2] = direct + diffuse;
                });
  estimate.direct_mean = estimate.direct_standard_error = Spectrum(n);
  estimate.diffuse_mean = estimate.diffuse_standard_error = Spectrum(n);
  estimate.total_mean = estimate.total_standard_error = Spectrum(n);
  for (std::size_t i = 0; i < n; ++i) {
    estimate.direct_mean[i] = moments.mean[i];
    estimate.direct_standard_error[i] = moments.standard_error[i];
    estimate.diffuse_mean[i] = moments.mean[n + i];
    estimate.diffuse_standard_error[i] = moments.standard_error[n + i];
    estimate.total_mean[i] = moments.mean[2 * n + i];
    estimate.total_standard_error[i] = moments.standard_error[2 * n + i];
  }
  estimate.samples = options.samples_per_wavelength;
  return estimate;
}

}  // namespace zenith::atmosphere::reference
