#pragma once
// Sky radiance in deep twilight: a path estimator whose last bounce is
// next-event estimation toward the sunlit air, with that air's single
// scattering integrated deterministically. The path tracer (path_tracer.h)
// reaches the sun only by next-event estimation from its own vertices; with the
// sun more than ~10° below the horizon every vertex near the zenith column is in
// the planet's shadow, so 10⁶ paths find the light a handful of times. Here the
// last step of every path goes to the lit air by quadrature instead.
//
// Quantity, scene and conventions as path_tracer.h: the sky radiance L(x, −v)
// arriving at x along the view direction v, all orders ≥ 1, L0 excluded,
// radiances in sr^-1 per unit solar irradiance; the same model, phase functions,
// Lambertian ground and air-mass stretch (attenuation s·β_ext, source β_scat).
//
// Derivation. Write L1(y, ω) + L_g(y, ω) for the single-scattered radiance and
// the directly lit ground's radiance arriving at y from direction ω
// (single_scattering.h: the sun a point at the disc's centre). Order m ≥ 2 of
// L(x) is an integral over paths x → y_1 → … → y_{m−1} of the path throughput
// times [L1 + L_g](y_{m−1}, ω_{m−1}):
//   L_m = ∫ T(x, y_1) f_1 ∫ … T(y_{m−2}, y_{m−1}) f_{m−1} [L1 + L_g](y_{m−1}, ω) dω dy…,
// f_k = β_R P_R(ν) + β_M P_M(ν) at a scattering vertex (ν = ω·d, d the path
// direction arriving at y_k: light from ω travels along −ω and leaves along −d)
// and (a/π) n·ω at the ground. The estimator samples that chain:
//  * Order 1 is not sampled: L1 + L_g of the view ray itself, by quadrature
//    (zero variance).
//  * Vertices by spectral one-sample MIS and a defensive mixture: with
//    probability a (tracked_flight_fraction) a "hero" wavelength h is drawn
//    uniformly and the free flight is delta-tracked at h (density
//    s β_ext,h(y) T_h(x, y), or the ground with probability T_h(x, g)); otherwise
//    the vertex is uniform on the ray's segment of length ℓ in the atmosphere
//    (the air high up, thin but in sight of the lit air, is reached as often as
//    it matters). Every wavelength λ is weighted by its own integrand over the
//    mixture density
//      p(y) = a (1/n) Σ_h s β_ext,h(y) T_h(x, y) + (1 − a)/ℓ,   W_λ ← W_λ T_λ(x, y) β_scat,λ(y) / p(y)
//    (ground: W_λ ← W_λ T_λ(x, g) / (a (1/n) Σ_h T_h(x, g))). T along the segment is
//    evaluated by quadrature for all wavelengths at once, so one path and one
//    L1 quadrature serve every wavelength.
//  * Next-event estimation toward the lit air at each vertex y_k gives order
//    k + 1: one direction ω from the proposal
//      q(ω) = f_lobe q_lobe(ω) + f_sun HG_g(ω·s) + (1 − f_lobe − f_sun) q_scatter(ω),
//    f_lobe = lobe_fraction at a vertex in the planet's shadow (lobe_fraction_sunlit
//    at a sunlit one, which the lit air surrounds); f_sun = 0 in the shadow,
//    aureole_fraction at a sunlit vertex, where the Mie forward peak of the air
//    around the sun's direction s is the brightest part of L1; q_scatter the mixture over
//    wavelengths of the phase proposals (hero drawn uniformly; q_scatter(ν) =
//    (1/n) Σ_h q_h(ν), phase_sampling.h), at the ground cos θ/π; q_lobe a
//    density toward where single-scattered light comes from in twilight: the
//    sun's azimuth (wrapped Cauchy in azimuth about it, scale γ) just above the
//    limb (Cauchy in μ = ω·up about μ₀ = μ_h + Δμ of width w, truncated to
//    [−1, 1], μ_h = −√(1 − (R_ground/r)²) the horizon's dip at the vertex);
//    dω = dμ dφ, so q_lobe = p_μ p_φ exactly. The contribution is
//      W_λ P_λ(ν) [L1 + L_g]_λ(y_k, ω) / q(ω)   (P_λ the mixture phase; ground: a_λ/π n·ω),
//    with L1 + L_g by quadrature (the planet's shadow handled exactly).
//  * The path goes on to y_{k+1} along the same ω, W_λ ← W_λ P_λ(ν)/q(ω) (ground:
//    a_λ/π n·ω/q(ω)): each order is an unbiased estimate of its own integral
//    (the orders are correlated, which costs nothing), and the next vertex lies
//    on the way to the lit air. Each order is counted exactly once: order 1 by
//    quadrature, order m ≥ 2 by the lit-air estimate at vertex m − 1. The sun
//    itself is never sampled by the path.
//  * From russian_roulette_start_order on, a path survives with probability
//    min(1, max_λ W_λ) and W is divided by it (unbiased).
// Every factor is exact except the point sun of L1 (single_scattering.h): its
// difference to the disc is of order α² (α the sun's angular radius) except
// where the shadow boundary crosses a ray, where the disc softens the edge
// symmetrically to first order; the validation (tests, README) bounds it.
//
// Paths are independent samples of all wavelengths together (the standard
// error of each wavelength is its own; they are correlated between
// wavelengths). Sample j of batch b draws from the PCG32 stream of
// (seed + b·φ64, 0, j) and the reduction is fixed (parallel_estimator.h), so
// results are bit-identical for any thread count.
#include <cstddef>
#include <cstdint>
#include <functional>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/reference/single_scattering.h"
#include "atmosphere/reference/sun_disc.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

/// L1 quadrature at the path vertices: relative tolerance 1e-3 (default 1e-7),
/// optical depths 1e-5: twice as fast as 1e-4 / 1e-7, and the same estimate to
/// 4 digits at sun −12° (3 000 paths); far below the Monte Carlo error.
SingleScatteringOptions lit_air_vertex_quadrature();
/// Transmittance of each flight at every wavelength: relative tolerance 1e-5.
OpticalDepthOptions lit_air_flight_quadrature();

struct LitAirOptions {
  std::size_t samples = 4096;  ///< paths (each estimates every wavelength)
  std::size_t batches = 1;     ///< the paths run in this many equal batches, `progress` called after each
  std::uint64_t seed = 1;
  unsigned thread_count = 0;               ///< 0: std::thread::hardware_concurrency()
  int min_scattering_order = 1;            ///< ≥ 1
  int max_scattering_order = 1000;         ///< ≥ min_scattering_order
  int russian_roulette_start_order = 3;    ///< first path vertex after which roulette may end a path
  std::size_t majorant_shell_count = 128;  ///< sub-shells of the delta-tracking majorant
  /// Probability that a flight is delta-tracked; otherwise its vertex is uniform
  /// on the ray's segment in the atmosphere (the high air, which sees the lit air best).
  double tracked_flight_fraction = 0.5;
  /// The proposal of the lit-air direction: probability of the twilight lobe at
  /// a vertex in the planet's shadow (point sun) and at a sunlit one, its centre in μ = cos(zenith angle) above the
  /// horizon's dip at the vertex (μ₀ = μ_h + Δμ: seen from a vertex, the lit air lies in a band a few hundredths above
  /// the limb), its width w in μ, and the scale γ [rad] of its wrapped Cauchy in azimuth about the sun's.
  double lobe_fraction = 0.7;
  double lobe_fraction_sunlit = 0.1;
  /// At a sunlit vertex, the probability of a direction from HG(g) about the sun
  /// (its aureole: Mie's forward peak, which the phase proposal about the path's
  /// direction misses), and g.
  double aureole_fraction = 0.2;
  double aureole_asymmetry = 0.8;
  double lobe_mu_above_horizon = 0.04;
  double lobe_mu_width = 0.04;
  double lobe_azimuth_scale_rad = 0.5;
  SingleScatteringOptions vertex_single_scattering = lit_air_vertex_quadrature();
  OpticalDepthOptions flight_optical_depth = lit_air_flight_quadrature();
  /// Called after each batch with the paths done and the total (may be empty).
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct LitAirEstimate {
  Spectrum mean;                        ///< sky radiance of the counted orders [sr^-1 per unit solar irradiance]
  Spectrum standard_error;              ///< of the mean, per wavelength (order 1 adds none)
  Spectrum order_one;                   ///< the quadrature's order 1 (L1 + L_ground), included in `mean` when counted
  std::size_t samples = 0;              ///< paths
  std::size_t majorant_violations = 0;  ///< tentative collisions where β_ext > majorant (0 = unbiased)
  std::size_t single_scattering_quadratures = 0;  ///< lit-air estimates made (the cost)
};

/// Sky radiance seen from `observer_m` (planet-centred, at or above the ground;
/// outside the atmosphere the path starts where the view ray enters it) along
/// `view_direction`. A view ray that misses the atmosphere gives 0. Throws
/// std::invalid_argument for inconsistent options or an observer below the ground.
LitAirEstimate lit_air_radiance(const AtmosphereModel& model, const Vec3& observer_m, const Vec3& view_direction,
                                const SunDisc& sun, const LitAirOptions& options = {});

}  // namespace zenith::atmosphere::reference
