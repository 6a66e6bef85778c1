#include "atmosphere/reference/path_integrator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "atmosphere/constants.h"
#include "atmosphere/reference/direction_sampling.h"
#include "atmosphere/reference/optical_depth.h"
#include "atmosphere/reference/phase_sampling.h"
#include "atmosphere/reference/polarization.h"

namespace zenith::atmosphere::reference {

namespace {

const PathSettings& checked(const PathSettings& s) {
  if (s.min_scattering_order < 1 || s.max_scattering_order < s.min_scattering_order)
    throw std::invalid_argument("PathSettings: need 1 <= min_scattering_order <= max_scattering_order");
  if (s.russian_roulette_start_order < 1)
    throw std::invalid_argument("PathSettings: russian_roulette_start_order must be >= 1");
  if (s.majorant_shell_count == 0) throw std::invalid_argument("PathSettings: majorant_shell_count must be > 0");
  if (s.aerosol_depolarizes && !s.polarized)
    throw std::invalid_argument("PathSettings: aerosol_depolarizes is a bound of vector transfer; it needs polarized");
  return s;
}

/// The scalar parts of what scatters at a point with coefficients `c`, for light turned by cos ν.
PolarizedScatterers scatterers(const AtmosphereModel& model, const PathSettings& settings, const LocalCoefficients& c,
                               std::size_t wavelength, double cos_scattering) {
  PolarizedScatterers s;
  s.rayleigh_m1_sr1 = c.rayleigh_scattering_m1 * model.rayleigh_phase_function(cos_scattering);
  if (c.mie_scattering_m1 > 0.0) s.aerosol_m1_sr1 = c.mie_scattering_m1 * model.mie_phase(wavelength, cos_scattering);
  s.depolarization = model.rayleigh_depolarization;
  s.aerosol_depolarizes = settings.aerosol_depolarizes;
  return s;
}

}  // namespace

PathIntegrator::PathIntegrator(const AtmosphereModel& model, const SunDisc& sun, const PathSettings& settings)
    : model_(&model),
      medium_(model),
      majorants_(model, checked(settings).majorant_shell_count),
      tracking_{&medium_, &majorants_},
      sun_(validated(sun)),
      sun_weight_(sun_sample_weight(sun_)),
      settings_(settings) {
  if (!sun_.limb_darkening.empty() && sun_.limb_darkening.size() != model.wavelengths_nm.size())
    throw std::invalid_argument("SunDisc: one limb darkening law per wavelength of the model, or none");
}

double PathIntegrator::transmittance_to_space(const Vec3& point_m, const Vec3& direction, std::size_t i, Pcg32& rng,
                                              std::size_t& violations) const {
  const Ray ray(point_m, direction);
  const AtmosphereInterval interval = atmosphere_interval(ray, model_->ground_radius_m, model_->top_radius_m);
  if (!interval.intersects) return 1.0;
  if (interval.ends_on_ground) return 0.0;
  const double stretch = optical_depth_stretch(*model_, ray, interval.begin_t_m, interval.end_t_m);
  return ratio_tracking_transmittance(tracking_, ray, interval.begin_t_m, stretch, i, rng, violations);
}

double PathIntegrator::direct_irradiance(const Vec3& point_m, const Vec3& normal, std::size_t i, Pcg32& rng,
                                         std::size_t& violations) const {
  const double u1 = rng.uniform(), u2 = rng.uniform();
  const Vec3 to_sun = sample_sun_direction(sun_, u1, u2);
  const double cosine = dot(normal, to_sun);
  if (!(cosine > 0.0) || occulted(sun_.occulter, point_m, to_sun)) return 0.0;
  return sun_weight_ * limb_weight(sun_, to_sun, i) * cosine *
         transmittance_to_space(point_m, to_sun, i, rng, violations);
}

double PathIntegrator::radiance(const Ray& ray, std::size_t i, Pcg32& rng, std::size_t& violations) const {
  return traced(ray, Mat3(1.0), i, rng, violations);
}

double PathIntegrator::analysed_radiance(const Ray& ray, const Mat3& analyser, std::size_t i, Pcg32& rng,
                                         std::size_t& violations) const {
  if (!settings_.polarized)
    throw std::logic_error("PathIntegrator::analysed_radiance: the light's polarization needs polarized settings");
  return traced(ray, analyser, i, rng, violations);
}

double PathIntegrator::traced(const Ray& first_ray, const Mat3& analyser, std::size_t i, Pcg32& rng,
                              std::size_t& violations) const {
  const AtmosphereModel& model = *model_;
  const double ground_radius = model.ground_radius_m;
  double radiance = 0.0, weight = 1.0;
  int order = 0;
  Ray ray = first_ray;
  // Vector transfer: the path's importance for the light's polarization, divided by the scalar weight
  // (polarization.h); the camera measures ⟨A, T⟩ — the radiance where the analyser A is 1.
  Mat3 importance = analyser;
  while (true) {
    const AtmosphereInterval interval = atmosphere_interval(ray, ground_radius, model.top_radius_m);
    if (!interval.intersects) break;
    // s of this straight segment: attenuation s·β_ext, source β_scat (unstretched).
    const double stretch = optical_depth_stretch(model, ray, interval.begin_t_m, interval.end_t_m);
    const FreeFlight flight = sample_free_flight(tracking_, ray, interval.begin_t_m, stretch, i, rng, violations);
    if (flight.event == FreeFlight::Event::Escape) break;  // the sun is reached by next-event estimation only
    ++order;
    const bool counted = order >= settings_.min_scattering_order;
    const bool last = order >= settings_.max_scattering_order;
    const Vec3& d = ray.direction();
    Vec3 vertex = ray.point_at(flight.t_m);
    Vec3 next_direction{};

    if (flight.event == FreeFlight::Event::Scattering) {
      const LocalCoefficients& c = flight.coefficients;
      const double scattering = c.scattering_m1();
      weight *= scattering / (stretch * c.extinction_m1);  // w = β_scat / (s β_ext)
      if (!(weight > 0.0)) break;
      if (counted) {
        // Light from ω_s travels along −ω_s and leaves along −d: cos(scattering angle) = ω_s·d.
        const double u1 = rng.uniform(), u2 = rng.uniform();
        const Vec3 to_sun = sample_sun_direction(sun_, u1, u2);
        const double cos_sun = dot(to_sun, d);
        double phase = 0.0;
        if (settings_.polarized) {
          // The sun's light is unpolarized: T = Π(k_in)/2 along k_in = −ω_s, leaving along −d.
          const Vec3 k_in = -to_sun;
          const Mat3 scattered = scattered_coherency(scatterers(model, settings_, c, i, cos_sun), k_in, -d,
                                                     0.5 * transverse_projector(k_in));
          phase = contract(importance, scattered) / scattering;
        } else {
          phase = medium_.mixture_phase(c, i, cos_sun);
        }
        // An analyser's ⟨A, ·⟩ may be negative or nil where the radiance's is not: the sun is looked
        // at alike for every A, so that one generator state draws one path for all of them.
        if ((settings_.polarized || phase > 0.0) && !occulted(sun_.occulter, vertex, to_sun))
          radiance += weight * sun_weight_ * limb_weight(sun_, to_sun, i) * phase *
                      transmittance_to_space(vertex, to_sun, i, rng, violations);
      }
      if (last) break;
      // One-sample mixture of the Rayleigh and Mie proposals; weight P(ν)/q(ν).
      const double u_component = rng.uniform(), u_lobe = rng.uniform(), u_cos = rng.uniform(), u_phi = rng.uniform();
      const PhaseSample scattered = sample_scattering_cosine(medium_, c, i, u_component, u_lobe, u_cos);
      weight *= scattered.weight;
      next_direction = direction_with_cosine(d, scattered.cos_scattering, u_phi);
      if (settings_.polarized) {
        // Divided by β_scat P(ν), the scalar part the weight already carries.
        const PolarizedScatterers parts = scatterers(model, settings_, c, i, scattered.cos_scattering);
        const double scalar_part = parts.rayleigh_m1_sr1 + parts.aerosol_m1_sr1;
        if (!(scalar_part > 0.0)) break;
        importance = scattered_importance(parts, -next_direction, -d, importance) / scalar_part;
      }
    } else {  // the ground: Lambertian, BRDF a/π
      const Vec3 normal = normalize(vertex);
      vertex = ground_radius * normal;
      const double albedo = model.ground_albedo[i];
      // The ground depolarizes: what leaves it toward −d is Π(−d)/2 per unit radiance.
      const double unpolarized = settings_.polarized ? 0.5 * contract(importance, transverse_projector(d)) : 1.0;
      if (counted && albedo > 0.0)
        radiance += weight * unpolarized * albedo / kPi * direct_irradiance(vertex, normal, i, rng, violations);
      if (settings_.polarized) importance = unpolarized * Mat3(1.0);
      if (last) break;
      weight *= albedo;  // cosine-weighted sampling: (a/π) cos θ / (cos θ/π) = a
      if (!(weight > 0.0)) break;
      const double u1 = rng.uniform(), u2 = rng.uniform();
      next_direction = sample_cosine_hemisphere(normal, u1, u2);
    }

    if (order >= settings_.russian_roulette_start_order) {
      const double survival = std::min(1.0, weight);
      if (survival < 1.0) {
        if (!(rng.uniform() < survival)) break;
        weight /= survival;
      }
    }
    ray = Ray(vertex, next_direction);
  }
  return radiance;
}

}  // namespace zenith::atmosphere::reference
