#pragma once
// Monte Carlo path tracer of the full radiative transfer problem: the
// stochastic half of the reference solver.
//
// Scene: spherical planet (radius R_ground) with a Lambertian ground of the
// model's albedo; spherical-shell atmosphere up to R_top with the model's
// density profiles, Rayleigh and Mie scattering with the model's phase functions
// (Rayleigh phase per model, Mie phase per wavelength) and every absorber; the
// sun a uniform disc (sun_disc.h) of irradiance 1 per wavelength.
//
// Quantity: the sky radiance arriving at the observer along the view direction
// [sr^-1 per unit solar irradiance] = all light scattered at least once by the
// atmosphere or the ground. The directly transmitted sun disc (L0) is excluded;
// a view ray that hits the ground includes the ground's reflected light (direct
// sun and skylight on the ground) attenuated to the observer.
//
// Spectral strategy: every working wavelength is traced independently, with
// its own paths and random streams (unbiased, and the standard error of each
// wavelength is independent of the others).
//
// Estimator (backward from the observer, path direction d):
//  * Free flight by delta tracking (delta_tracking.h) with the attenuation s·β_ext
//    of the ray's air-mass stretch s. The real collision at y then has density
//    p(y) = s β_ext(y) T_s(x, y). The radiative transfer equation with the
//    stretch convention of optical_depth.h is
//      L(x) = ∫ T_s(x, y) β_scat(y) L_in(y) dy + T_s(x, end) L_end,
//    i.e. attenuation stretched, source not. The path weight is therefore
//    multiplied at each collision by
//      w(y) = β_scat(y) / (s β_ext(y))     (≤ 1, single-scattering albedo over s),
//    so E[w L_in] = ∫ T_s β_scat L_in dy exactly. Ground hits happen with the
//    probability T_s(x, ground), as they should.
//  * Next-event estimation toward the sun at every scattering vertex and ground
//    hit: a direction ω_s uniform in solid angle on the sun's disc, weight
//    L_sun Ω = 2/(1 + cos α) (sun_disc.h) times the phase mixture
//    P(ν) = (β_R P_R(ν) + β_M P_M(ν))/β_scat at ν = ω_s·d (or the BRDF a/π times
//    n·ω_s on the ground) times the transmittance to the sun along ω_s, estimated
//    by residual ratio tracking (0 if that ray hits the planet; unbiased, and its
//    variance only adds to the estimate's). Escaping paths contribute
//    nothing: the sun is reached only by next-event estimation, which is why L0
//    is excluded.
//  * New directions: in the medium, Rayleigh or Mie is chosen with probability
//    β_R/β_scat, ν is drawn from that constituent's proposal (phase_sampling.h)
//    and the weight is P(ν)/q(ν), q = (β_R q_R + β_M q_M)/β_scat; on the ground,
//    cosine-weighted, weight a.
//  * Scattering order = number of scattering events (atmosphere or ground) of
//    the path; only next-event contributions of order in
//    [min_scattering_order, max_scattering_order] are counted and the path stops
//    at the maximum. Order 1 is single scattering plus the direct sun reflected by
//    the ground: it converges to L1 + L_ground of single_scattering.h for a point
//    sun. From russian_roulette_start_order on, a path survives each event with
//    probability q = min(1, weight) and its weight is divided by q (unbiased).
//  * Each sample (wavelength i, index j) draws from its own PCG32 stream derived
//    from (seed, i, j); chunks of samples run on std::threads and are reduced in
//    a fixed order, so the result does not depend on the thread count.
//  * Polarization (optional, PathTracerOptions::polarized): the path also carries
//    the importance tensor of polarization.h, which replaces the phase P(ν) of
//    each next-event estimate by ⟨M, L(Π/2)⟩ and is updated at each scattering;
//    directions are drawn as above, so the scalar and the vector estimates of one
//    seed share their paths and differ only by the polarization.
// One path is PathIntegrator::radiance (path_integrator.h).
//
// Majorants: per wavelength, a piecewise-constant bound of β_ext over 128 (by
// default) concentric sub-shells (majorant_grid.h), times the ray's own stretch s
// (exact, since s is constant along a ray) instead of a global maximum times the
// largest stretch: as safe, and far fewer wasted steps high in the atmosphere.
// Tentative collisions where β_ext exceeded the bound are counted and reported
// (majorant_violations; the tests require 0).
//
// Known weakness: deep twilight (sun several degrees below the horizon) is
// noisy, because most collisions on the view ray fall in the planet's shadow;
// Earth with the sun at 96° needs ~1e6 paths per wavelength for 2–4% standard error
// of order 1.
#include <cstddef>
#include <cstdint>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/reference/sun_disc.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

struct PathTracerOptions {
  std::size_t samples_per_wavelength = 4096;  ///< paths per wavelength
  std::uint64_t seed = 1;
  unsigned thread_count = 0;               ///< 0: std::thread::hardware_concurrency()
  int min_scattering_order = 1;            ///< ≥ 1
  int max_scattering_order = 1000;         ///< ≥ min_scattering_order
  int russian_roulette_start_order = 4;    ///< first order after which roulette may end a path
  std::size_t majorant_shell_count = 128;  ///< sub-shells of the delta-tracking majorant
  bool polarized = false;                  ///< vector radiative transfer (polarization.h) instead of scalar
  /// With polarized: the aerosols send their light on unpolarized — the other bound of an aerosol's scattering
  /// matrix from the default, which carries the polarization through unchanged (polarization.h).
  bool aerosol_depolarizes = false;
};

struct RadianceEstimate {
  Spectrum mean;                        ///< sky radiance [sr^-1 per unit solar irradiance]
  Spectrum standard_error;              ///< standard error of the mean, per wavelength
  std::size_t samples = 0;              ///< paths per wavelength
  std::size_t majorant_violations = 0;  ///< tentative collisions where β_ext > majorant (0 = unbiased)
};

/// Sky radiance seen from `observer_m` (planet-centred [m], at or above the
/// ground; anywhere outside the atmosphere, e.g. 40 AU away, starts the path
/// where the view ray enters it) along `view_direction` (need not be unit). A
/// view ray that misses the atmosphere gives 0 with zero error.
RadianceEstimate path_traced_radiance(const AtmosphereModel& model, const Vec3& observer_m, const Vec3& view_direction,
                                      const SunDisc& sun, const PathTracerOptions& options = {});

/// The light's linear polarization arriving at the observer, as Stokes parameters in a frame across the
/// view ray: e₁ = `reference_axis` made unit and across it, e₂ = e₁ × v̂; Q = I₁ − I₂, U = I₊₄₅ − I₋₄₅, the
/// E-vector leaning from e₁ toward e₂ where U > 0 (polarization.h). Circular polarization is never made.
struct StokesEstimate {
  Spectrum i, q, u;  ///< [sr^-1 per unit solar irradiance]; i is path_traced_radiance's mean, path for path
  Spectrum i_standard_error, q_standard_error, u_standard_error;
  std::size_t samples = 0;
  std::size_t majorant_violations = 0;
};

/// I, Q and U of the sky seen from `observer_m` along `view_direction` (path_traced_radiance's arguments),
/// each from the same paths (the analyser changes a path's importance, not its draws). Needs
/// options.polarized; throws std::invalid_argument otherwise or where `reference_axis` lies along the view.
StokesEstimate path_traced_stokes(const AtmosphereModel& model, const Vec3& observer_m, const Vec3& view_direction,
                                  const Vec3& reference_axis, const SunDisc& sun, const PathTracerOptions& options);

/// √(Q² + U²) / I, the degree of linear polarization (0 where I is 0).
double degree_of_linear_polarization(double i, double q, double u);

/// ½ atan2(U, Q): the E-vector's angle from e₁ toward e₂ [rad], in (−π/2, π/2].
double polarization_angle_rad(double q, double u);

/// Irradiance on a horizontal ground element [per unit solar irradiance]:
///   E_direct  = ∫_disc L_sun T(g, ω) max(0, n·ω) dω   (attenuated sun disc),
///   E_diffuse = ∫_hemisphere L_sky(g, ω) (n·ω) dω      (all orders, including light
///               reflected by the ground and scattered back).
/// Each sample draws one sun direction (ratio-tracked transmittance) and one
/// cosine-weighted sky direction whose radiance is path traced (E = π·L).
/// The scattering-order options apply to L_sky.
struct GroundIrradianceEstimate {
  Spectrum direct_mean, direct_standard_error;
  Spectrum diffuse_mean, diffuse_standard_error;
  Spectrum total_mean, total_standard_error;
  std::size_t samples = 0;
  std::size_t majorant_violations = 0;
};

/// `ground_point_m` is projected radially onto the ground sphere.
GroundIrradianceEstimate ground_irradiance(const AtmosphereModel& model, const Vec3& ground_point_m, const SunDisc& sun,
                                           const PathTracerOptions& options = {});

}  // namespace zenith::atmosphere::reference
