#include "atmosphere/reference/optical_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atmosphere/reference/adaptive_quadrature.h"
#include "atmosphere/reference/medium.h"

namespace zenith::atmosphere::reference {

double optical_depth_stretch(const AtmosphereModel& model, const Ray& ray, double begin_t_m, double end_t_m) {
  if (!model.air_mass.enabled()) return 1.0;
  const double t = std::clamp(ray.perigee_t_m(), std::min(begin_t_m, end_t_m), std::max(begin_t_m, end_t_m));
  return model.air_mass(ray.radius_at(t), ray.cos_zenith_at(t));
}

std::vector<double> quadrature_breakpoint_radii_m(const AtmosphereModel& model) {
  std::vector<double> radii;
  for (int k = 1; k < 8; ++k) radii.push_back(model.ground_radius_m + model.atmosphere_height_m() * (k * k) / 64.0);
  return radii;
}

std::vector<double> optical_depth_breakpoint_radii_m(const AtmosphereModel& model) {
  std::vector<double> radii = quadrature_breakpoint_radii_m(model);
  auto add_knots = [&](const DensityProfile& profile) {
    if (profile.kind() != DensityProfile::Kind::Tabulated) return;
    for (double altitude : profile.table().knots_x())
      if (altitude > 0.0 && altitude < model.atmosphere_height_m()) radii.push_back(model.ground_radius_m + altitude);
  };
  add_knots(model.rayleigh_density);
  if (model.has_mie()) add_knots(model.mie_density);
  for (const Absorber& a : model.absorbers) add_knots(a.profile);
  std::sort(radii.begin(), radii.end());
  radii.erase(std::unique(radii.begin(), radii.end()), radii.end());
  return radii;
}

Spectrum optical_depth_along_ray(const AtmosphereModel& model, const Ray& ray, double t0_m, double t1_m,
                                 const OpticalDepthOptions& options) {
  const std::size_t n = model.wavelength_count();
  Spectrum tau(n);
  const auto top = ray.sphere_crossings(model.top_radius_m);
  if (!top) return tau;
  const double a = std::max(t0_m, top->entry_t_m);
  const double b = std::min(t1_m, top->exit_t_m);
  if (!(b > a)) return tau;

  std::vector<double> breakpoints = {a};
  if (ray.perigee_t_m() > a && ray.perigee_t_m() < b) breakpoints.push_back(ray.perigee_t_m());
  for (double t : sphere_crossings_t_m(ray, optical_depth_breakpoint_radii_m(model), a, b)) breakpoints.push_back(t);
  breakpoints.push_back(b);
  std::sort(breakpoints.begin(), breakpoints.end());

  const AtmosphereMedium medium(model);
  const double ground = model.ground_radius_m;
  const VectorIntegrand extinction = [&](double t, std::span<double> value) {
    medium.extinction_m1(ray.radius_at(t) - ground, value);
  };
  const QuadratureResult integral = integrate_adaptive(extinction, breakpoints, n, options);
  const double stretch = optical_depth_stretch(model, ray, a, b);
  for (std::size_t i = 0; i < n; ++i) tau[i] = stretch * integral.integral[i];
  return tau;
}

Spectrum optical_depth(const AtmosphereModel& model, const Vec3& from_m, const Vec3& to_m,
                       const OpticalDepthOptions& options) {
  const std::size_t n = model.wavelength_count();
  const Vec3 delta = to_m - from_m;
  const double segment_length = length(delta);
  if (!(segment_length > 0.0)) return Spectrum(n);
  const Ray ray(from_m, delta);
  if (const auto planet = ray.sphere_crossings(model.ground_radius_m)) {
    const double overlap = std::min(segment_length, planet->exit_t_m) - std::max(0.0, planet->entry_t_m);
    if (overlap > 1e-3) return Spectrum(n, std::numeric_limits<double>::infinity());
  }
  return optical_depth_along_ray(model, ray, 0.0, segment_length, options);
}

Spectrum transmittance(const AtmosphereModel& model, const Vec3& from_m, const Vec3& to_m,
                       const OpticalDepthOptions& options) {
  Spectrum t = optical_depth(model, from_m, to_m, options);
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = std::exp(-t[i]);
  return t;
}

Spectrum transmittance_to_sun(const AtmosphereModel& model, const Vec3& point_m, const Vec3& sun_direction,
                              const OpticalDepthOptions& options) {
  const std::size_t n = model.wavelength_count();
  const Ray ray(point_m, sun_direction);
  const AtmosphereInterval interval = atmosphere_interval(ray, model.ground_radius_m, model.top_radius_m);
  if (!interval.intersects) return Spectrum(n, 1.0);
  if (interval.ends_on_ground) return Spectrum(n, 0.0);
  Spectrum t = optical_depth_along_ray(model, ray, interval.begin_t_m, interval.end_t_m, options);
  for (std::size_t i = 0; i < n; ++i) t[i] = std::exp(-t[i]);
  return t;
}

}  // namespace zenith::atmosphere::reference
