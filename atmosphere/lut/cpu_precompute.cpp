#include "atmosphere/lut/cpu_precompute.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "atmosphere/constants.h"
#include "atmosphere/lut/gauss_legendre.h"
#include "atmosphere/lut/quadrature.h"
#include "atmosphere/lut/series_tail.h"
#include "atmosphere/lut/spherical_harmonics.h"
#include "atmosphere/model_hash.h"
#include "core/parallel_for.h"

namespace zenith::atmosphere::lut {
namespace {

using Channels = std::array<double, kMaxChannels>;

double PrecomputeSeconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Everything the stages share.
class Precompute {
 public:
  Precompute(const AtmosphereModel& model, const PrecomputeOptions& options, PrecomputeReport* report)
      : model_(model),
        options_(options),
        report_(report),
        n_(model.wavelength_count()),
        tables_(LookupTables::allocate({model.ground_radius_m, model.top_radius_m}, options.sizes, n_)),
        queries_(model, tables_) {
    if (n_ > kMaxChannels) throw std::invalid_argument("too many wavelengths for the lookup tables");
    check_precompute_options(options);
  }

  LookupTables run();

 private:
  const ShellGeometry& geometry() const { return tables_.geometry; }
  const TableSizes& sizes() const { return tables_.sizes; }
  void stage(const std::string& name, double fraction, auto&& body);

  void compute_transmittance();
  void compute_single_scattering();
  /// Scattering density J_n from the radiance of order n−1 (`delta_radiance`,
  /// or the single-scattering tables when n = 2) and the ground irradiance of
  /// order n−2 (`delta_irradiance`, or the direct sun when n = 2).
  void compute_scattering_density(int order, Table3D& density);
  /// The same integral by spherical harmonics (PrecomputeOptions::DensityMethod::Harmonics).
  void compute_scattering_density_harmonics(int order, Table3D& density);
  /// The same integral summed per texel (PrecomputeOptions::DensityMethod::Direct).
  void compute_scattering_density_direct(int order, Table3D& density);
  /// Incoming radiance of order n−1 at (r, μs) from direction (μ, ν): the
  /// previous order plus, where the direction hits the ground, the ground's
  /// reflection of the irradiance of order n−2 attenuated to r.
  /// `ground_t`: transmittance to the ground along μ, `ground_distance` the
  /// distance to it (0 at the ground itself), both used when `hits_ground`.
  void incoming_radiance(int order, double r, double mu, double mu_s, const Vec3& omega, const Vec3& sun,
                         bool hits_ground, double ground_distance, const double* ground_t, double* out) const;
  /// Sky irradiance of order n−1 on horizontal surfaces, added to the irradiance table.
  void compute_indirect_irradiance(int order);
  /// Radiance of order n: J_n integrated along every ray; returns Σ L_n.
  double compute_multiple_scattering(const Table3D& density, int sample_stride);

  /// Radiance of order (order−1) arriving at (r) from direction (μ, ν_sun = nu).
  void previous_order_radiance(int order, double r, double mu, double mu_s, double nu, double* out) const;
  double total_radiance_sum() const;

  const AtmosphereModel& model_;
  const PrecomputeOptions& options_;
  PrecomputeReport* report_;
  std::size_t n_;
  LookupTables tables_;
  TableQueries queries_;
  Table3D delta_radiance_;    ///< multiple-scattering radiance of the last order
  Table2D delta_irradiance_;  ///< sky irradiance of the last order
  /// The same of the order before (for the series tail, series_tail.h; kept only with it).
  Table3D previous_delta_radiance_;
  Table2D previous_delta_irradiance_;
  double fraction_done_ = 0.0;
};

template <typename Body>
void run_stage(const std::string& name, double fraction, PrecomputeReport* report, const PrecomputeOptions& options,
               double& done, Body&& body) {
  if (options.progress) options.progress({name, done});
  const auto start = std::chrono::steady_clock::now();
  body();
  if (report) report->stages.push_back({name, PrecomputeSeconds(start)});
  done += fraction;
  if (options.progress) options.progress({name, std::min(done, 1.0)});
}

void Precompute::stage(const std::string& name, double fraction, auto&& body) {
  run_stage(name, fraction, report_, options_, fraction_done_, body);
}

// ---------------------------------------------------------------- transmittance

void Precompute::compute_transmittance() {
  // T(r, μ) = exp(−s(r, μ) ∫₀^d β_ext(h(t)) dt), composite Simpson rule on a uniform
  // grid along the ray to the top (paper eq. 5, with the air-mass stretch s of eq. 21).
  // Simpson, not the trapezoid: with 500 intervals over 100 km the trapezoid's
  // error on a 1.2 km Mie scale height is ~1e-4 in T; Simpson's is ~1e-7.
  Table2D& table = tables_.transmittance;
  const int samples = options_.transmittance_samples + options_.transmittance_samples % 2;  // even
  core::parallel_for(table.height, options_.threads, [&](std::size_t y) {
    Channels beta{}, tau{};
    for (std::size_t x = 0; x < table.width; ++x) {
      double r, mu;
      transmittance_r_mu(geometry(), sizes(), (double(x) + 0.5) / double(table.width),
                         (double(y) + 0.5) / double(table.height), &r, &mu);
      const double d = geometry().distance_to_top_m(r, mu);
      const double dx = d / samples;
      std::fill(tau.begin(), tau.begin() + long(n_), 0.0);
      for (int i = 0; i <= samples; ++i) {
        const double t = i * dx;
        const double r_t = std::sqrt(t * t + 2.0 * r * mu * t + r * r);
        model_.extinction_m1(r_t - geometry().bottom_radius_m, beta.data());
        const double w = (i == 0 || i == samples) ? 1.0 / 3.0 : (i % 2 == 1 ? 4.0 / 3.0 : 2.0 / 3.0);
        for (std::size_t c = 0; c < n_; ++c) tau[c] += w * beta[c] * dx;
      }
      const double stretch = model_.air_mass(r, mu);
      float* out = table.texel(x, y);
      for (std::size_t c = 0; c < n_; ++c) out[c] = float(std::exp(-stretch * tau[c]));
    }
  });
}

// ---------------------------------------------------------------- transmittance along the view rays

/// The samples y_i = x + t_i v, i = 0..N (N = `samples`), of the view ray
/// x = (r, μ) of a scattering table row: their distances t_i
/// (ray_sample_distance_m: crowded toward the ray's lowest point, d the
/// distance to the nearest boundary) and T(x, y_i), by accumulating the
/// optical depth along the ray (paper eq. 5):
///   T(x, y_i) = exp(−s(r, μ) Σ_{k=1..i} ∫_{t_{k−1}}^{t_k} β_ext(h(t)) dt),
/// each interval in kOpticalDepthSubsteps equal parts integrated by
/// integrate_interval from β_ext [m^-1] at their ends, s the air-mass stretch of
/// the ray (constant along it, eq. 21).
///
/// Not the table ratio T_top(x)/T_top(y) (TableQueries::transmittance): along a
/// grazing ray both are long paths whose T changes by orders of magnitude between
/// neighbouring μ texels, and from a ground observer looking at the horizon the
/// ratio is 3–7 % off at 1 km and 10–23 % at 10 km (earth-standard, paper-size
/// tables), which left the horizon row of the sky 4–10 % dark. (Accumulating with
/// one log-linear step per uniform interval was tried before and moved mid-sky
/// pixels: β_ext mixes Rayleigh and aerosol profiles, so that step overestimates
/// τ near the ground; the sub-steps and the crowded samples remove that.)
///
/// The ray depends on the row's r and μ only, not on μs or ν, so this is computed
/// once per row and shared by the row's texels (on the GPU: view_transmittance.comp,
/// the same operations in the same order).
struct ViewRaySamples {
  std::vector<double> distance_m;     ///< t_i, N + 1
  std::vector<double> transmittance;  ///< T(x, y_i), (N + 1) × channels, sample-major
};

ViewRaySamples view_ray_samples(const AtmosphereModel& model, const ShellGeometry& geometry, std::size_t channels,
                                const ScatteringCoordinates& c, int samples, PrecomputeOptions::Quadrature rule) {
  ViewRaySamples out;
  out.distance_m.resize(static_cast<std::size_t>(samples) + 1);
  out.transmittance.assign((static_cast<std::size_t>(samples) + 1) * channels, 0.0);
  const double d = geometry.distance_to_nearest_boundary_m(c.r_m, c.mu, c.ray_hits_ground);
  const double lowest = lowest_point_distance_m(c.r_m, c.mu, d, c.ray_hits_ground);
  const double stretch = model.air_mass(c.r_m, c.mu);
  auto extinction_at = [&](double t, double* beta) {
    const double r_t = std::clamp(std::sqrt(t * t + 2.0 * c.r_m * c.mu * t + c.r_m * c.r_m), geometry.bottom_radius_m,
                                  geometry.top_radius_m);
    model.extinction_m1(r_t - geometry.bottom_radius_m, beta);
  };
  Channels optical_depth{}, previous_beta{}, beta{};
  extinction_at(0.0, previous_beta.data());
  double previous_t = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double t = ray_sample_distance_m(i, samples, d, lowest);
    out.distance_m[static_cast<std::size_t>(i)] = t;
    if (i > 0) {
      const double step = (t - previous_t) / kOpticalDepthSubsteps;
      for (int k = 1; k <= kOpticalDepthSubsteps; ++k) {
        extinction_at(previous_t + k * step, beta.data());
        for (std::size_t ch = 0; ch < channels; ++ch) {
          optical_depth[ch] += integrate_interval(previous_beta[ch], beta[ch], step, rule);
          previous_beta[ch] = beta[ch];
        }
      }
    }
    previous_t = t;
    double* t_out = out.transmittance.data() + static_cast<std::size_t>(i) * channels;
    for (std::size_t ch = 0; ch < channels; ++ch) t_out[ch] = std::exp(-stretch * optical_depth[ch]);
  }
  return out;
}

// ---------------------------------------------------------------- single scattering

void Precompute::compute_single_scattering() {
  // S1_R(x, v) = β_R ∫₀^d T(x, y) T(y, sun) ρ_R(y) dy, likewise for Mie (paper eq. 7,
  // one scattering event), without phase functions. The row's samples along the
  // ray, each interval integrated by integrate_interval (quadrature.h); T(x, y)
  // from the row's view-ray samples (view_ray_samples), T(y, sun) from the table.
  const TableSizes& s = sizes();
  const int samples = options_.scattering_samples;
  const std::size_t width = s.scattering_width(), height = s.scattering_mu;
  core::parallel_for(s.scattering_r * height, options_.threads, [&](std::size_t row) {
    const std::size_t z = row / height, y = row % height;
    Channels t_sun{}, rayleigh{}, mie{}, prev_r{}, prev_m{};
    const ViewRaySamples ray = view_ray_samples(
        model_, geometry(), n_, scattering_texel_coordinates(geometry(), s, 0, y, z, AngleMapping::Distance), samples,
        options_.scattering_quadrature);
    for (std::size_t x = 0; x < width; ++x) {
      const ScatteringCoordinates c = scattering_texel_coordinates(geometry(), s, x, y, z, AngleMapping::Distance);
      std::fill(rayleigh.begin(), rayleigh.end(), 0.0);
      std::fill(mie.begin(), mie.end(), 0.0);
      for (int i = 0; i <= samples; ++i) {
        const double t = ray.distance_m[static_cast<std::size_t>(i)];
        const double dx = i > 0 ? t - ray.distance_m[static_cast<std::size_t>(i) - 1] : 0.0;
        const double r_t = std::clamp(std::sqrt(t * t + 2.0 * c.r_m * c.mu * t + c.r_m * c.r_m),
                                      geometry().bottom_radius_m, geometry().top_radius_m);
        const double mu_s_t = std::clamp((c.r_m * c.mu_s + t * c.nu) / r_t, -1.0, 1.0);
        const double h = r_t - geometry().bottom_radius_m;
        const double* t_view_i = ray.transmittance.data() + static_cast<std::size_t>(i) * n_;
        queries_.transmittance_to_sun(r_t, mu_s_t, t_sun.data());
        const double rho_r = model_.rayleigh_density(h), rho_m = model_.mie_density(h);
        for (std::size_t ch = 0; ch < n_; ++ch) {
          const double tt = t_view_i[ch] * t_sun[ch];
          const double f_r = tt * rho_r, f_m = tt * rho_m;
          if (i > 0) {
            rayleigh[ch] += integrate_interval(prev_r[ch], f_r, dx, options_.scattering_quadrature);
            mie[ch] += integrate_interval(prev_m[ch], f_m, dx, options_.scattering_quadrature);
          }
          prev_r[ch] = f_r;
          prev_m[ch] = f_m;
        }
      }
      float* out_r = tables_.single_rayleigh.texel(x, y, z);
      float* out_m = tables_.single_mie.texel(x, y, z);
      for (std::size_t ch = 0; ch < n_; ++ch) {
        out_r[ch] = float(rayleigh[ch] * model_.rayleigh_scattering_m1[ch]);
        out_m[ch] = float(mie[ch] * model_.mie_scattering_m1[ch]);
      }
    }
  });
}

// ---------------------------------------------------------------- multiple scattering

void Precompute::previous_order_radiance(int order, double r, double mu, double mu_s, double nu, double* out) const {
  const bool hits_ground = geometry().ray_hits_ground(r, mu);
  if (order == 2) {
    // Order 1: the single-scattering tables with their phase functions.
    Channels rayleigh{}, mie{};
    queries_.scattering_terms(r, mu, mu_s, nu, hits_ground, rayleigh.data(), mie.data(), nullptr);
    const double phase_r = model_.rayleigh_phase_function(nu);
    for (std::size_t c = 0; c < n_; ++c) out[c] = rayleigh[c] * phase_r + mie[c] * model_.mie_phase(c, nu);
    return;
  }
  // Orders ≥ 2: the delta table of the last order, read like the final table
  // (geometric in μs: lookup_tables.h).
  sample_scattering_table_geometric_mu_s(
      delta_radiance_, sizes(),
      scattering_uvwz(geometry(), sizes(), r, mu, mu_s, nu, hits_ground, AngleMapping::Blended), out);
}

void Precompute::compute_scattering_density(int order, Table3D& density) {
  if (options_.density_method == PrecomputeOptions::DensityMethod::Harmonics)
    compute_scattering_density_harmonics(order, density);
  else
    compute_scattering_density_direct(order, density);
}

void Precompute::incoming_radiance(int order, double r, double mu, double mu_s, const Vec3& omega, const Vec3& sun,
                                   bool hits_ground, double ground_distance, const double* ground_t,
                                   double* out) const {
  previous_order_radiance(order, r, mu, mu_s, std::clamp(dot(omega, sun), -1.0, 1.0), out);
  if (!hits_ground) return;
  const double rb = geometry().bottom_radius_m;
  const Vec3 ground_normal = normalize(Vec3{0.0, 0.0, r} + omega * ground_distance);
  const double mu_s_ground = std::clamp(dot(ground_normal, sun), -1.0, 1.0);
  Channels ground_e{};
  if (order == 2) {
    queries_.transmittance_to_sun(rb, mu_s_ground, ground_e.data());
    for (std::size_t ch = 0; ch < n_; ++ch) ground_e[ch] *= std::max(mu_s_ground, 0.0);
  } else {
    const IrradianceUV uv = irradiance_uv(geometry(), sizes(), rb, mu_s_ground);
    delta_irradiance_.sample(uv.u_mu_s, uv.v_r, ground_e.data());
  }
  for (std::size_t ch = 0; ch < n_; ++ch) out[ch] += ground_t[ch] * model_.ground_albedo[ch] / kPi * ground_e[ch];
}

void Precompute::compute_scattering_density_harmonics(int order, Table3D& density) {
  // J_n(x, v) = Σ_lm q_l(h) a_lm(r, μs) Y_lm(v) (spherical_harmonics.h): per
  // (r, μs), the incoming radiance is sampled once on a horizon-split
  // Gauss–Legendre × uniform-azimuth rule and projected on the cos(mφ)
  // harmonics (φ from the sun's vertical); every (μ, ν) texel of that column
  // then costs one sum over the harmonics instead of a sphere integral.
  const TableSizes& s = sizes();
  const int nodes = options_.sphere_zenith_samples;
  const int degree = options_.harmonic_degree_used();
  const std::size_t count = harmonic_count(degree);
  // 4·nodes azimuths over the circle (cos(mφ) sampled without aliasing up to
  // m = 2·nodes − 1 ≥ degree): 2·nodes over [0, π), mirrored over (π, 2π).
  const int half_azimuths = 2 * nodes;
  const double d_phi = kPi / half_azimuths;
  // Legendre moments of the phase functions (per channel for the aerosols).
  const std::vector<double> rayleigh_moments =
      phase_legendre_moments([&](double x) { return model_.rayleigh_phase_function(x); }, degree);
  std::vector<std::vector<double>> mie_moments(n_);
  for (std::size_t ch = 0; ch < n_; ++ch)
    mie_moments[ch] = phase_legendre_moments([&](double x) { return model_.mie_phase(ch, x); }, degree);
  const double rb = geometry().bottom_radius_m;
  core::parallel_for(s.scattering_r * s.scattering_mu_s, options_.threads, [&](std::size_t column) {
    const std::size_t z = column / s.scattering_mu_s, xs = column % s.scattering_mu_s;
    const ScatteringCoordinates c0 = scattering_texel_coordinates(geometry(), s, xs, 0, z, AngleMapping::Blended);
    const double r = c0.r_m, mu_s = c0.mu_s;
    const Vec3 sun{std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s)), 0.0, mu_s};
    const HorizonSplitRule rule(rb, r, nodes);

    // ---- projection: a_lm = Σ_j w_j c_m P̄_l^m(μ_j) C_m(μ_j), C_m = ∫ L cos(mφ) dφ
    std::vector<double> coefficients(count * n_, 0.0), legendre(count), by_m(std::size_t(degree + 1) * n_);
    Channels incoming{}, ground_t{};
    for (std::size_t j = 0; j < rule.mu.size(); ++j) {
      const double mu = rule.mu[j], sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
      const bool hits_ground = int(j) < rule.ground_nodes;
      double ground_distance = 0.0;
      if (hits_ground) {
        ground_distance = geometry().distance_to_bottom_m(r, mu);
        queries_.transmittance(r, mu, ground_distance, true, ground_t.data());
      }
      std::fill(by_m.begin(), by_m.end(), 0.0);
      for (int k = 0; k < half_azimuths; ++k) {
        const double phi = (k + 0.5) * d_phi;
        const Vec3 omega{sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu};
        incoming_radiance(order, r, mu, mu_s, omega, sun, hits_ground, ground_distance, ground_t.data(),
                          incoming.data());
        // cos(mφ) by Chebyshev's recurrence; ×2: the mirrored azimuth 2π − φ.
        const double c1 = std::cos(phi);
        double cos_prev = 1.0, cos_m = 1.0;
        for (int m = 0; m <= degree; ++m) {
          const double w = 2.0 * d_phi * cos_m;
          for (std::size_t ch = 0; ch < n_; ++ch) by_m[std::size_t(m) * n_ + ch] += w * incoming[ch];
          const double next = m == 0 ? c1 : 2.0 * c1 * cos_m - cos_prev;
          cos_prev = cos_m;
          cos_m = next;
        }
      }
      normalized_legendre(degree, mu, legendre.data());
      for (int m = 0; m <= degree; ++m) {
        const double cm = azimuth_normalisation(m) * rule.weight[j];
        for (int l = m; l <= degree; ++l) {
          const std::size_t i = harmonic_index(degree, l, m);
          const double w = cm * legendre[i];
          for (std::size_t ch = 0; ch < n_; ++ch) coefficients[i * n_ + ch] += w * by_m[std::size_t(m) * n_ + ch];
        }
      }
    }

    // ---- evaluation: J(μ, ν) = Σ_m cos(mφ_v) c_m Σ_l q_l a_lm P̄_l^m(μ)
    const double h = r - rb;
    const double rho_r = model_.rayleigh_density(h), rho_m = model_.mie_density(h);
    std::vector<double> q(std::size_t(degree + 1) * n_);
    for (int l = 0; l <= degree; ++l)
      for (std::size_t ch = 0; ch < n_; ++ch)
        q[std::size_t(l) * n_ + ch] = model_.rayleigh_scattering_m1[ch] * rho_r * rayleigh_moments[std::size_t(l)] +
                                      model_.mie_scattering_m1[ch] * rho_m * mie_moments[ch][std::size_t(l)];
    const double sin_theta_s = std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s));
    for (std::size_t y = 0; y < s.scattering_mu; ++y) {
      const ScatteringCoordinates cy = scattering_texel_coordinates(geometry(), s, xs, y, z, AngleMapping::Blended);
      const double mu = cy.mu, sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
      normalized_legendre(degree, mu, legendre.data());
      std::fill(by_m.begin(), by_m.end(), 0.0);
      for (int m = 0; m <= degree; ++m) {
        const double cm = azimuth_normalisation(m);
        for (int l = m; l <= degree; ++l) {
          const std::size_t i = harmonic_index(degree, l, m);
          const double w = cm * legendre[i];
          for (std::size_t ch = 0; ch < n_; ++ch)
            by_m[std::size_t(m) * n_ + ch] += w * q[std::size_t(l) * n_ + ch] * coefficients[i * n_ + ch];
        }
      }
      for (std::size_t xn = 0; xn < s.scattering_nu; ++xn) {
        const std::size_t x = xn * s.scattering_mu_s + xs;
        const ScatteringCoordinates c = scattering_texel_coordinates(geometry(), s, x, y, z, AngleMapping::Blended);
        const double denominator = sin_theta * sin_theta_s;
        const double c1 = denominator > 0.0 ? std::clamp((c.nu - mu * mu_s) / denominator, -1.0, 1.0) : 1.0;
        Channels j{};
        double cos_prev = 1.0, cos_m = 1.0;
        for (int m = 0; m <= degree; ++m) {
          for (std::size_t ch = 0; ch < n_; ++ch) j[ch] += cos_m * by_m[std::size_t(m) * n_ + ch];
          const double next = m == 0 ? c1 : 2.0 * c1 * cos_m - cos_prev;
          cos_prev = cos_m;
          cos_m = next;
        }
        float* out = density.texel(x, y, z);
        // The series cut at degree L can ring slightly below zero where J ≈ 0.
        for (std::size_t ch = 0; ch < n_; ++ch) out[ch] = float(std::max(j[ch], 0.0));
      }
    }
  });
}

void Precompute::compute_scattering_density_direct(int order, Table3D& density) {
  // J_n(x, v) = ∫_4π [β_R ρ_R P_R(v·ω) + β_M ρ_M P_M(v·ω)] L_{n−1}(x, ω) dω, where
  // L_{n−1} includes, for directions that hit the ground, the ground's reflection
  // of the irradiance of order n−2 (albedo/π · E_{n−2}, attenuated).
  const TableSizes& s = sizes();
  // Directions: Gauss–Legendre in μ = cos θ (gauss_legendre.h), uniform in φ.
  const int n_theta = options_.sphere_zenith_samples, n_phi = 2 * n_theta;
  const GaussLegendre rule(n_theta);
  const double d_phi = 2.0 * kPi / n_phi;
  const std::size_t width = s.scattering_width(), height = s.scattering_mu;
  const double rb = geometry().bottom_radius_m;
  core::parallel_for(s.scattering_r * height, options_.threads, [&](std::size_t row) {
    const std::size_t z = row / height, y = row % height;
    Channels incoming{}, ground_t{}, j{};
    for (std::size_t x = 0; x < width; ++x) {
      const ScatteringCoordinates c = scattering_texel_coordinates(geometry(), s, x, y, z, AngleMapping::Blended);
      // Local frame: zenith z, view ω in the xz-plane, sun from μs and ν.
      const Vec3 view{std::sqrt(std::max(0.0, 1.0 - c.mu * c.mu)), 0.0, c.mu};
      const double sun_x = view.x == 0.0 ? 0.0 : (c.nu - c.mu * c.mu_s) / view.x;
      const double sun_y = std::sqrt(std::max(1.0 - sun_x * sun_x - c.mu_s * c.mu_s, 0.0));
      const Vec3 sun{sun_x, sun_y, c.mu_s};
      const double h = c.r_m - rb;
      const double rho_r = model_.rayleigh_density(h), rho_m = model_.mie_density(h);
      std::fill(j.begin(), j.end(), 0.0);
      for (int it = 0; it < n_theta; ++it) {
        const double cos_theta = rule.nodes[std::size_t(it)];
        const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
        const bool hits_ground = geometry().ray_hits_ground(c.r_m, cos_theta);
        // Ground seen in this direction: distance, transmittance, and its normal's height.
        double ground_distance = 0.0;
        if (hits_ground) {
          ground_distance = geometry().distance_to_bottom_m(c.r_m, cos_theta);
          queries_.transmittance(c.r_m, cos_theta, ground_distance, true, ground_t.data());
        }
        for (int ip = 0; ip < n_phi; ++ip) {
          const double phi = (ip + 0.5) * d_phi;
          const Vec3 omega{sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
          const double d_omega = rule.weights[std::size_t(it)] * d_phi;
          incoming_radiance(order, c.r_m, cos_theta, c.mu_s, omega, sun, hits_ground, ground_distance, ground_t.data(),
                            incoming.data());
          const double cos_scatter = std::clamp(dot(view, omega), -1.0, 1.0);
          const double phase_r = model_.rayleigh_phase_function(cos_scatter);
          for (std::size_t ch = 0; ch < n_; ++ch) {
            const double beta = model_.rayleigh_scattering_m1[ch] * rho_r * phase_r +
                                model_.mie_scattering_m1[ch] * rho_m * model_.mie_phase(ch, cos_scatter);
            j[ch] += incoming[ch] * beta * d_omega;
          }
        }
      }
      float* out = density.texel(x, y, z);
      for (std::size_t ch = 0; ch < n_; ++ch) out[ch] = float(j[ch]);
    }
  });
}

void Precompute::compute_indirect_irradiance(int order) {
  // E_{n−1}(r, μs) = ∫_{upper hemisphere} L_{n−1}(x, ω) cos θ dω, Gauss–Legendre
  // in μ ∈ [0, 1] (half as many nodes as the sphere integral), uniform in φ.
  const TableSizes& s = sizes();
  const int n_theta = std::max(1, options_.sphere_zenith_samples / 2), n_phi = 4 * n_theta;
  const GaussLegendre rule(n_theta);
  const double d_phi = 2.0 * kPi / n_phi;
  Table2D next(s.irradiance_mu_s, s.irradiance_r, n_);
  core::parallel_for(s.irradiance_r, options_.threads, [&](std::size_t y) {
    Channels incoming{}, e{};
    for (std::size_t x = 0; x < s.irradiance_mu_s; ++x) {
      double r, mu_s;
      irradiance_r_mu_s(geometry(), s, (double(x) + 0.5) / double(s.irradiance_mu_s),
                        (double(y) + 0.5) / double(s.irradiance_r), &r, &mu_s);
      const Vec3 sun{std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s)), 0.0, mu_s};
      std::fill(e.begin(), e.end(), 0.0);
      for (int it = 0; it < n_theta; ++it) {
        const double mu = 0.5 + 0.5 * rule.nodes[std::size_t(it)];  // [−1, 1] → [0, 1]
        const double sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
        for (int ip = 0; ip < n_phi; ++ip) {
          const double phi = (ip + 0.5) * d_phi;
          const Vec3 omega{sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu};
          previous_order_radiance(order, r, omega.z, mu_s, std::clamp(dot(omega, sun), -1.0, 1.0), incoming.data());
          const double w = mu * 0.5 * rule.weights[std::size_t(it)] * d_phi;
          for (std::size_t ch = 0; ch < n_; ++ch) e[ch] += incoming[ch] * w;
        }
      }
      float* out = next.texel(x, y);
      float* total = tables_.irradiance.texel(x, y);
      for (std::size_t ch = 0; ch < n_; ++ch) {
        out[ch] = float(e[ch]);
        total[ch] += float(e[ch]);
      }
    }
  });
  if (options_.series_tail) previous_delta_irradiance_ = std::move(delta_irradiance_);
  delta_irradiance_ = std::move(next);
}

double Precompute::compute_multiple_scattering(const Table3D& density, int sample_stride) {
  // L_n(x, v) = ∫₀^d T(x, y) J_n(y, v) dy along the ray (same rule as single
  // scattering, the row's samples and T(x, y) from view_ray_samples; every
  // sample_stride-th of them and the last, next_ray_sample). J is read
  // geometrically in μs (sample_scattering_table_geometric_mu_s): through the
  // deep twilight it falls about e-fold per degree of the sun's depression, 3–4°
  // per μs texel there, and a linear read overshoots.
  const TableSizes& s = sizes();
  const int samples = options_.scattering_samples;
  const std::size_t width = s.scattering_width(), height = s.scattering_mu;
  Table3D next(width, height, s.scattering_r, n_);
  std::vector<double> row_sums(s.scattering_r * height, 0.0);
  core::parallel_for(s.scattering_r * height, options_.threads, [&](std::size_t row) {
    const std::size_t z = row / height, y = row % height;
    Channels j{}, sum{}, prev{};
    // The row's ray: T, r and μ and the (u_r, u_μ) texture coordinates at its
    // samples, the same for every (μs, ν) texel (view_ray.glsl on the GPU).
    const ScatteringCoordinates ray = scattering_texel_coordinates(geometry(), s, 0, y, z, AngleMapping::Blended);
    const ViewRaySamples view = view_ray_samples(model_, geometry(), n_, ray, samples, options_.scattering_quadrature);
    const int stride = coarse_ray_stride_for(ray.mu, ray.ray_hits_ground, sample_stride);
    const std::size_t sample_count = static_cast<std::size_t>(samples) + 1;
    std::vector<ScatteringUVWZ> ray_uv(sample_count);
    std::vector<double> ray_r_m(sample_count), ray_mu(sample_count);
    for (std::size_t i = 0; i < sample_count; ++i) {
      const double t = view.distance_m[i];
      ray_r_m[i] = std::clamp(std::sqrt(t * t + 2.0 * ray.r_m * ray.mu * t + ray.r_m * ray.r_m),
                              geometry().bottom_radius_m, geometry().top_radius_m);
      ray_mu[i] = std::clamp((ray.r_m * ray.mu + t) / ray_r_m[i], -1.0, 1.0);
      ray_uv[i] = scattering_uvwz(geometry(), s, ray_r_m[i], ray_mu[i], ray.mu_s, ray.nu, ray.ray_hits_ground,
                                  AngleMapping::Blended);
    }
    for (std::size_t x = 0; x < width; ++x) {
      const ScatteringCoordinates c = scattering_texel_coordinates(geometry(), s, x, y, z, AngleMapping::Blended);
      std::fill(sum.begin(), sum.end(), 0.0);
      double previous_t = 0.0;
      for (int i = 0; i <= samples; i = next_ray_sample(i, stride, samples)) {
        const double t = view.distance_m[static_cast<std::size_t>(i)];
        const double dx = t - previous_t;
        previous_t = t;
        const double mu_s_t = std::clamp((c.r_m * c.mu_s + t * c.nu) / ray_r_m[i], -1.0, 1.0);
        ScatteringUVWZ uv = ray_uv[i];
        uv.u_mu_s = scattering_u_mu_s(geometry(), s, mu_s_t, AngleMapping::Blended);
        uv.u_nu = scattering_u_nu(ray_mu[i], mu_s_t, c.nu);  // ν is constant along the ray, the azimuth is not
        sample_scattering_table_geometric_mu_s(density, s, uv, j.data());
        const double* t_view_i = view.transmittance.data() + static_cast<std::size_t>(i) * n_;
        for (std::size_t ch = 0; ch < n_; ++ch) {
          const double f = t_view_i[ch] * j[ch];
          if (i > 0) sum[ch] += integrate_interval(prev[ch], f, dx, options_.scattering_quadrature);
          prev[ch] = f;
        }
      }
      float* out = next.texel(x, y, z);
      float* total = tables_.multiple.texel(x, y, z);
      for (std::size_t ch = 0; ch < n_; ++ch) {
        out[ch] = float(sum[ch]);
        total[ch] += float(sum[ch]);
        row_sums[row] += sum[ch];
      }
    }
  });
  if (options_.series_tail) previous_delta_radiance_ = std::move(delta_radiance_);
  delta_radiance_ = std::move(next);
  double total = 0.0;
  for (double v : row_sums) total += v;
  return total;
}

double Precompute::total_radiance_sum() const {
  // Σ over texels and channels of the in-scattered radiance with phases applied.
  const TableSizes& s = sizes();
  double total = 0.0;
  for (std::size_t z = 0; z < s.scattering_r; ++z)
    for (std::size_t y = 0; y < s.scattering_mu; ++y)
      for (std::size_t x = 0; x < s.scattering_width(); ++x) {
        const ScatteringCoordinates c = scattering_texel_coordinates(geometry(), s, x, y, z, AngleMapping::Distance);
        // Single terms at their own texel's geometry; the multiple table is a plain sum.
        const double phase_r = model_.rayleigh_phase_function(c.nu);
        const float *r = tables_.single_rayleigh.texel(x, y, z), *m = tables_.single_mie.texel(x, y, z),
                    *ms = tables_.multiple.texel(x, y, z);
        for (std::size_t ch = 0; ch < n_; ++ch) total += r[ch] * phase_r + m[ch] * model_.mie_phase(ch, c.nu) + ms[ch];
      }
  return total;
}

LookupTables Precompute::run() {
  const int orders = options_.max_orders;
  // Rough shares of the run time, for the progress bar.
  const double share_multiple = orders > 1 ? 0.85 / (orders - 1) : 0.0;
  stage("transmittance", 0.05, [&] { compute_transmittance(); });
  stage("single scattering", orders > 1 ? 0.10 : 0.95, [&] { compute_single_scattering(); });
  std::vector<double> order_sums;
  order_sums.push_back(total_radiance_sum());
  int used = 1;
  Table3D density(sizes().scattering_width(), sizes().scattering_mu, sizes().scattering_r, n_);
  for (int order = 2; order <= orders; ++order) {
    const std::string prefix = "order " + std::to_string(order) + ": ";
    stage(prefix + "scattering density", share_multiple * 0.6, [&] { compute_scattering_density(order, density); });
    stage(prefix + "sky irradiance", share_multiple * 0.1, [&] { compute_indirect_irradiance(order); });
    double added = 0.0;
    stage(prefix + "multiple scattering", share_multiple * 0.3,
          [&] { added = compute_multiple_scattering(density, options_.ray_sample_stride(order)); });
    order_sums.push_back(added);
    used = order;
    double total = 0.0;
    for (double v : order_sums) total += v;
    if (options_.tolerance > 0.0 && total > 0.0 && added < options_.tolerance * total) break;
  }
  // The orders after the last one, as its geometric tail (series_tail.h): from
  // the third order on, where the two last orders are both multiple scattering.
  double tail_sum = 0.0;
  if (options_.series_tail && used >= 3) {
    stage("series tail", 0.0, [&] {
      tail_sum = add_series_tail(delta_radiance_, previous_delta_radiance_, tables_.multiple);
      add_series_tail(delta_irradiance_, previous_delta_irradiance_, tables_.irradiance);
    });
  }
  tables_.scattering_orders = used;
  tables_.hash = lookup_table_hash(model_);
  if (report_) {
    report_->set_order_sums(order_sums, tail_sum);
    report_->device = "CPU (" + std::to_string(core::resolve_thread_count(options_.threads)) + " threads)";
  }
  if (options_.progress) options_.progress({"done", 1.0});
  return std::move(tables_);
}

}  // namespace

void PrecomputeReport::set_order_sums(const std::vector<double>& order_sums, double tail_sum) {
  orders_used = int(order_sums.size());
  double total = tail_sum;
  for (double v : order_sums) total += v;
  order_fraction.clear();
  for (double v : order_sums) order_fraction.push_back(total > 0.0 ? v / total : 0.0);
  tail_fraction = total > 0.0 ? tail_sum / total : 0.0;
}

double PrecomputeReport::total_seconds() const {
  double s = 0.0;
  for (const auto& st : stages) s += st.seconds;
  return s;
}

LookupTables precompute_tables_cpu(const AtmosphereModel& model, const PrecomputeOptions& options,
                                   PrecomputeReport* report) {
  options.sizes.check();
  return Precompute(model, options, report).run();
}

}  // namespace zenith::atmosphere::lut
