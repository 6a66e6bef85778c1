#include "atmosphere/reference/lit_air_estimator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "atmosphere/constants.h"
#include "atmosphere/reference/delta_tracking.h"
#include "atmosphere/reference/direction_sampling.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/majorant_grid.h"
#include "atmosphere/reference/medium.h"
#include "atmosphere/reference/optical_depth.h"
#include "atmosphere/reference/parallel_estimator.h"
#include "atmosphere/reference/phase_sampling.h"

namespace zenith::atmosphere::reference {

SingleScatteringOptions lit_air_vertex_quadrature() {
  SingleScatteringOptions o;
  o.relative_tolerance = 1e-3;
  o.absolute_tolerance = 1e-22;
  o.optical_depth.relative_tolerance = 1e-5;
  return o;
}

OpticalDepthOptions lit_air_flight_quadrature() {
  OpticalDepthOptions o;
  o.relative_tolerance = 1e-5;
  return o;
}

namespace {

void check(const LitAirOptions& o) {
  if (o.samples == 0 || o.batches == 0 || o.samples % o.batches != 0)
    throw std::invalid_argument("LitAirOptions: samples must be > 0 and a multiple of batches (> 0)");
  if (o.min_scattering_order < 1 || o.max_scattering_order < o.min_scattering_order)
    throw std::invalid_argument("LitAirOptions: need 1 <= min_scattering_order <= max_scattering_order");
  if (o.russian_roulette_start_order < 1)
    throw std::invalid_argument("LitAirOptions: russian_roulette_start_order must be >= 1");
  if (o.majorant_shell_count == 0) throw std::invalid_argument("LitAirOptions: majorant_shell_count must be > 0");
  if (!(o.tracked_flight_fraction > 0.0 && o.tracked_flight_fraction <= 1.0))
    throw std::invalid_argument("LitAirOptions: tracked_flight_fraction must be in (0, 1]");
  if (!(o.lobe_fraction >= 0.0 && o.lobe_fraction < 1.0 && o.lobe_fraction_sunlit >= 0.0 && o.aureole_fraction >= 0.0 &&
        o.lobe_fraction_sunlit + o.aureole_fraction < 1.0))
    throw std::invalid_argument("LitAirOptions: lobe fractions must be >= 0 and leave the phase proposal some");
  if (!(o.aureole_asymmetry >= 0.0 && o.aureole_asymmetry < 1.0))
    throw std::invalid_argument("LitAirOptions: aureole_asymmetry must be in [0, 1)");
  if (!(o.lobe_mu_width > 0.0 && o.lobe_azimuth_scale_rad > 0.0 && std::abs(o.lobe_mu_above_horizon) <= 1.0))
    throw std::invalid_argument("LitAirOptions: lobe widths must be > 0 and |lobe_mu_above_horizon| <= 1");
}

/// The twilight lobe at a vertex: μ = ω·up from a Cauchy density about
/// μ₀ = μ_h + Δμ (μ_h the horizon's dip there, Δμ = lobe_mu_above_horizon) of
/// width w truncated to [−1, 1] (inverse CDF μ = μ₀ + w tan(A + u(B − A)),
/// A, B = atan((∓1 − μ₀)/w)), and the azimuth φ from the sun's from a Cauchy of
/// scale γ wrapped onto (−π, π], whose density is the wrapped Cauchy
///   p_φ = (1 − ρ²) / (2π (1 + ρ² − 2ρ cos φ)),  ρ = e^{−γ}.
/// dω = dμ dφ, so the density in solid angle is p_μ(μ) p_φ(φ) [sr^-1].
class TwilightLobe {
 public:
  TwilightLobe(const LitAirOptions& o, double ground_radius_m, const Vec3& vertex_m, const Vec3& sun)
      : width_(o.lobe_mu_width), gamma_(o.lobe_azimuth_scale_rad) {
    up_ = normalize(vertex_m);
    // The horizon's dip at the vertex: μ_h = −√(1 − (R_ground/r)²).
    const double ratio = std::min(1.0, ground_radius_m / length(vertex_m));
    mu0_ = std::clamp(o.lobe_mu_above_horizon - std::sqrt(std::max(0.0, 1.0 - ratio * ratio)), -1.0, 1.0);
    const Vec3 horizontal = sun - dot(sun, up_) * up_;
    toward_sun_ = length(horizontal) > 1e-9 ? normalize(horizontal) : Frame::around(up_).u;
    side_ = cross(up_, toward_sun_);
    atan_low_ = std::atan((-1.0 - mu0_) / width_);
    atan_high_ = std::atan((1.0 - mu0_) / width_);
    rho_ = std::exp(-gamma_);
  }

  Vec3 sample(double u_mu, double u_phi) const {
    const double mu = std::clamp(mu0_ + width_ * std::tan(atan_low_ + u_mu * (atan_high_ - atan_low_)), -1.0, 1.0);
    const double phi = std::remainder(gamma_ * std::tan(kPi * (u_phi - 0.5)), 2.0 * kPi);
    const double sine = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    return normalize(sine * (std::cos(phi) * toward_sun_ + std::sin(phi) * side_) + mu * up_);
  }

  double pdf(const Vec3& w) const {
    const double mu = std::clamp(dot(w, up_), -1.0, 1.0);
    const double phi = std::atan2(dot(w, side_), dot(w, toward_sun_));
    const double x = (mu - mu0_) / width_;
    const double p_mu = 1.0 / ((atan_high_ - atan_low_) * width_ * (1.0 + x * x));
    const double p_phi = (1.0 - rho_ * rho_) / (2.0 * kPi * (1.0 + rho_ * rho_ - 2.0 * rho_ * std::cos(phi)));
    return p_mu * p_phi;
  }

 private:
  double mu0_, width_, gamma_, atan_low_ = 0.0, atan_high_ = 0.0, rho_ = 0.0;
  Vec3 up_{}, toward_sun_{}, side_{};
};

/// One path's estimator (the derivation is in lit_air_estimator.h).
class LitAirPath {
 public:
  LitAirPath(const AtmosphereModel& model, const SunDisc& sun, const LitAirOptions& options)
      : model_(model),
        options_(options),
        sun_(sun.direction),
        n_(model.wavelength_count()),
        medium_(model),
        majorants_(model, options.majorant_shell_count),
        tracking_{&medium_, &majorants_} {}

  /// Adds the path's orders ≥ 2 (those counted) to `out` (one value per wavelength).
  void sample(const Ray& first_ray, Pcg32& rng, std::span<double> out, std::size_t& violations,
              std::size_t& quadratures) const {
    std::vector<double> weight(n_, 1.0), factor(n_);
    std::vector<LocalCoefficients> local(n_);
    Ray ray = first_ray;
    for (int vertex_index = 1;; ++vertex_index) {
      const AtmosphereInterval interval = atmosphere_interval(ray, model_.ground_radius_m, model_.top_radius_m);
      if (!interval.intersects) return;
      const double stretch = optical_depth_stretch(model_, ray, interval.begin_t_m, interval.end_t_m);
      // The flight: delta tracking at a uniformly drawn hero wavelength (probability a),
      // else a point uniform on the segment.
      const double a = options_.tracked_flight_fraction, length_m = interval.end_t_m - interval.begin_t_m;
      FreeFlight flight;
      if (rng.uniform() < a) {
        const std::size_t hero = std::min(n_ - 1, std::size_t(rng.uniform() * double(n_)));
        flight = sample_free_flight(tracking_, ray, interval.begin_t_m, stretch, hero, rng, violations);
        if (flight.event == FreeFlight::Event::Escape) return;
      } else {
        flight.event = FreeFlight::Event::Scattering;
        flight.t_m = interval.begin_t_m + rng.uniform() * length_m;
      }
      const Spectrum depth =
          optical_depth_along_ray(model_, ray, interval.begin_t_m, flight.t_m, options_.flight_optical_depth);
      const bool ground = flight.event == FreeFlight::Event::Ground;
      Vec3 vertex = ray.point_at(flight.t_m);
      if (ground) vertex = model_.ground_radius_m * normalize(vertex);
      // The mixture density of this vertex, and W_λ ← W_λ T_λ β_scat,λ / p.
      double density = 0.0;
      if (ground) {
        for (std::size_t h = 0; h < n_; ++h) density += std::exp(-depth[h]);
        density *= a / double(n_);
        for (std::size_t i = 0; i < n_; ++i) weight[i] *= std::exp(-depth[i]) / density;
      } else {
        medium_.coefficients(ray.radius_at(flight.t_m) - model_.ground_radius_m, local);
        for (std::size_t h = 0; h < n_; ++h) density += stretch * local[h].extinction_m1 * std::exp(-depth[h]);
        density = a * density / double(n_) + (1.0 - a) / length_m;
        for (std::size_t i = 0; i < n_; ++i) weight[i] *= std::exp(-depth[i]) * local[i].scattering_m1() / density;
      }
      if (!(density > 0.0) || std::all_of(weight.begin(), weight.end(), [](double w) { return !(w > 0.0); })) return;

      // One direction ω from the lit-air proposal serves both the next-event
      // estimate of order k + 1 and the path's way on to y_{k+1}: W_λ ← W_λ f_λ(ω)/q(ω).
      const Vec3 next = sample_direction(vertex, ray.direction(), ground, local, rng, factor);
      const int lit_air_order = vertex_index + 1;
      if (lit_air_order >= options_.min_scattering_order &&
          std::any_of(factor.begin(), factor.end(), [](double x) { return x > 0.0; })) {
        const SingleScatteringResult lit =
            single_scattering_radiance(model_, vertex, next, sun_, options_.vertex_single_scattering);
        ++quadratures;
        for (std::size_t i = 0; i < n_; ++i)
          out[i] += weight[i] * factor[i] * (lit.atmosphere_radiance[i] + lit.ground_radiance[i]);
      }
      if (lit_air_order >= options_.max_scattering_order) return;
      for (std::size_t i = 0; i < n_; ++i) weight[i] *= factor[i];
      if (vertex_index >= options_.russian_roulette_start_order) {
        const double survival = std::min(1.0, *std::max_element(weight.begin(), weight.end()));
        if (!(survival > 0.0)) return;
        if (survival < 1.0) {
          if (!(rng.uniform() < survival)) return;
          for (double& w : weight) w /= survival;
        }
      }
      ray = Ray(vertex, next);
    }
  }

 private:
  /// q_scatter(ν) = (1/n) Σ_h q_h(ν), the density of a direction drawn from a
  /// uniformly chosen wavelength's phase proposal [sr^-1].
  double scattering_mixture_pdf(const std::vector<LocalCoefficients>& local, double cos_scattering) const {
    double q = 0.0;
    for (std::size_t h = 0; h < n_; ++h) q += scattering_proposal_pdf(medium_, local[h], h, cos_scattering);
    return q / double(n_);
  }

  /// A direction ω at `vertex` (path direction `d` arriving there) from the
  /// lit-air proposal q = f_lobe q_lobe + f_sun HG_g(ω·s) + (1 − f_lobe − f_sun) q_scatter
  /// (the ground: cos θ/π instead of q_scatter); `factor` receives f_λ(ω)/q(ω),
  /// f_λ the mixture phase P_λ(ω·d) (the ground: a_λ/π n·ω).
  Vec3 sample_direction(const Vec3& vertex, const Vec3& d, bool ground, const std::vector<LocalCoefficients>& local,
                        Pcg32& rng, std::vector<double>& factor) const {
    const TwilightLobe lobe(options_, model_.ground_radius_m, vertex, sun_);
    // A vertex in the planet's shadow sees the lit air in the lobe; a sunlit one
    // is surrounded by it, and the phase proposal suits it better.
    const double r = length(vertex);
    const bool shadowed = ray_hits_ground(r, dot(vertex, sun_) / r, model_.ground_radius_m);
    const double f = shadowed ? options_.lobe_fraction : options_.lobe_fraction_sunlit;
    // The sun's aureole (Mie's forward peak around the sun, seen from a sunlit vertex).
    const double f_sun = shadowed ? 0.0 : options_.aureole_fraction;
    const double g = options_.aureole_asymmetry;
    const Vec3 normal = normalize(vertex);
    const double u_choice = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(),
                 u4 = rng.uniform(), u5 = rng.uniform();
    Vec3 w{};
    if (u_choice < f) {
      w = lobe.sample(u1, u2);
    } else if (u_choice < f + f_sun) {
      w = direction_with_cosine(sun_, sample_henyey_greenstein_cosine(g, u1), u2);
    } else if (ground) {
      w = sample_cosine_hemisphere(normal, u1, u2);
    } else {
      const std::size_t h = std::min(n_ - 1, std::size_t(u3 * double(n_)));
      const PhaseSample s = sample_scattering_cosine(medium_, local[h], h, u4, u1, u2);
      w = direction_with_cosine(d, s.cos_scattering, u5);
    }
    double q = f * lobe.pdf(w);
    if (f_sun > 0.0) q += f_sun * henyey_greenstein_proposal_pdf(g, dot(w, sun_));
    if (ground) {
      const double n_dot_w = dot(normal, w);
      if (n_dot_w > 0.0) q += (1.0 - f - f_sun) * n_dot_w / kPi;
      for (std::size_t i = 0; i < n_; ++i)
        factor[i] = n_dot_w > 0.0 && q > 0.0 ? model_.ground_albedo[i] / kPi * n_dot_w / q : 0.0;
    } else {
      const double cosine = dot(w, d);
      q += (1.0 - f - f_sun) * scattering_mixture_pdf(local, cosine);
      for (std::size_t i = 0; i < n_; ++i) factor[i] = q > 0.0 ? medium_.mixture_phase(local[i], i, cosine) / q : 0.0;
    }
    return w;
  }

  const AtmosphereModel& model_;
  const LitAirOptions& options_;
  Vec3 sun_{};
  std::size_t n_;
  AtmosphereMedium medium_;
  MajorantGrid majorants_;
  TrackingMedium tracking_;
};

}  // namespace

LitAirEstimate lit_air_radiance(const AtmosphereModel& model, const Vec3& observer_m, const Vec3& view_direction,
                                const SunDisc& sun_in, const LitAirOptions& options) {
  check(options);
  const SunDisc sun = validated(sun_in);
  // Its sunlit-air sums take the whole disc; an eclipse needs the path tracer.
  if (sun.occulter.radius_m > 0.0 || !sun.limb_darkening.empty())
    throw std::invalid_argument(
        "lit_air_radiance: an occulter or a limb-darkened disc is the path tracer's (path_tracer.h)");
  const std::size_t n = model.wavelength_count();
  if (length(observer_m) < model.ground_radius_m * (1.0 - 1e-12))
    throw std::invalid_argument("lit_air_radiance: observer below the ground");
  LitAirEstimate estimate;
  estimate.mean = estimate.standard_error = estimate.order_one = Spectrum(n);
  estimate.samples = options.samples;

  const Ray observer_ray(observer_m, view_direction);
  const AtmosphereInterval interval = atmosphere_interval(observer_ray, model.ground_radius_m, model.top_radius_m);
  if (!interval.intersects) return estimate;
  const Ray first_ray(observer_ray.point_at(interval.begin_t_m), observer_ray.direction());

  if (options.min_scattering_order <= 1) {
    const SingleScatteringResult first = single_scattering_radiance(model, observer_m, view_direction, sun.direction);
    for (std::size_t i = 0; i < n; ++i) estimate.order_one[i] = first.atmosphere_radiance[i] + first.ground_radiance[i];
  }
  if (options.max_scattering_order >= 2) {
    const LitAirPath path(model, sun, options);
    std::atomic<std::size_t> violations{0}, quadratures{0};
    const std::size_t per_batch = options.samples / options.batches;
    // Pooled moments of equal batches (Chan et al.): mean of means, and the sum of
    // squared deviations Σ[(N_b − 1) var_b + N_b (m_b − m)²].
    std::vector<std::vector<double>> batch_means, batch_variances;
    for (std::size_t b = 0; b < options.batches; ++b) {
      ParallelEstimatorSettings settings;
      settings.wavelength_count = 1;
      settings.samples_per_wavelength = per_batch;
      settings.components = n;
      settings.seed = options.seed + b * 0x9E3779B97F4A7C15ull;
      settings.thread_count = options.thread_count;
      const SampleMoments moments =
          run_parallel_estimator(settings, [&](std::size_t, std::size_t, Pcg32& rng, std::span<double> values) {
            std::fill(values.begin(), values.end(), 0.0);
            std::size_t local_violations = 0, local_quadratures = 0;
            path.sample(first_ray, rng, values, local_violations, local_quadratures);
            if (local_violations != 0) violations += local_violations;
            quadratures += local_quadratures;
          });
      batch_means.push_back(moments.mean);
      std::vector<double> variance(n);
      for (std::size_t i = 0; i < n; ++i)
        variance[i] = moments.standard_error[i] * moments.standard_error[i] * double(per_batch);
      batch_variances.push_back(variance);
      if (options.progress) options.progress((b + 1) * per_batch, options.samples);
    }
    const double batches = double(options.batches), total = double(options.samples);
    for (std::size_t i = 0; i < n; ++i) {
      double mean = 0.0;
      for (const auto& m : batch_means) mean += m[i] / batches;
      double squares = 0.0;
      for (std::size_t b = 0; b < options.batches; ++b) {
        const double deviation = batch_means[b][i] - mean;
        squares += (double(per_batch) - 1.0) * batch_variances[b][i] + double(per_batch) * deviation * deviation;
      }
      estimate.mean[i] = mean;
      estimate.standard_error[i] = total > 1.0 ? std::sqrt(squares / (total - 1.0) / total) : 0.0;
    }
    estimate.majorant_violations = violations;
    estimate.single_scattering_quadratures = quadratures;
  }
  for (std::size_t i = 0; i < n; ++i) estimate.mean[i] += estimate.order_one[i];
  return estimate;
}

}  // namespace zenith::atmosphere::reference
