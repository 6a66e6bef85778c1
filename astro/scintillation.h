#pragma once
// Scintillation: stars twinkle, most near the horizon (docs/night-sky.md,
// "Scintillation"). The relative variance of a star's intensity seen through
// an aperture D over an integration time t at zenith angle γ from an
// altitude h_obs, in the form of Young's approximation that Osborn et al.
// (2015, MNRAS 452, 1707) fitted to four observatories:
//   σ_I² = 10⁻⁵ C_Y² D^(−4/3) t⁻¹ (cos γ)⁻³ exp(−2 h_obs / H),   D [m], t [s], H = 8000 m,
// C_Y ≈ 1.5 their median (Young 1967: σ = 0.09 D_cm^(−2/3) X^1.75 e^(−h/8000) (2t)^(−1/2), C_Y ≈ 0.93).
// Departures, each for a reason:
//  * (cos γ)⁻³ is taken as X³ with Pickering's air mass X (paper eq. 21), which
//    stays finite at the horizon where 1/cos γ does not.
//  * The law assumes an aperture wider than the Fresnel scale r_F = √(λ z) of
//    the turbulence at height z (≈ 7 cm for 550 nm and 10 km); for a smaller one
//    (the eye's pupil) the variance stops growing as D^(−4/3) and tends to the
//    point-aperture value (Dravins et al. 1997, PASP 109, 173; Roddier 1981):
//    D is taken as max(D, r_F).
//  * Strong scintillation saturates: σ_I² is capped at 1 (Dravins et al. 1997:
//    the normalised variance approaches unity near the horizon).
//  * Other atmospheres: refractive-index fluctuations scale with the
//    refractivity n − 1, so σ_I² is scaled by ((n₀ − 1)/(n₀ − 1)_Earth)², the
//    same turbulence assumed (Mars's thin CO₂: ~1e-4 of Earth's twinkling).
// The intensity factor of one star over one integration time is log-normal
// with mean 1 and variance σ_I² (the weak-turbulence statistics): exp(s g − s²/2)
// with s² = ln(1 + σ_I²) and g a standard normal drawn from a hash of the star
// and the integration interval, so every node of a cluster and every rerun of an
// offline show draws the same value.
#include <cstdint>

namespace zenith::astro {

struct ScintillationOptions {
  double c_y = 1.5;                      ///< Young's coefficient C_Y (Osborn et al. 2015 median)
  double pupil_mm = 7.0;                 ///< the aperture: a dark-adapted eye's pupil
  double integration_s = 0.1;            ///< the eye's integration time; also how long one draw lasts
  double turbulence_height_m = 10000.0;  ///< z of the Fresnel scale √(λ z)
};

/// Earth's ground refractivity at 550 nm for standard air (Edlén 1953 / Penndorf 1957).
inline constexpr double kEarthGroundRefractivity550 = 2.7784e-4;

/// σ_I² above for a star at Pickering air mass `air_mass` ≥ 1, seen from
/// `observer_altitude_m`, through air of ground refractivity `ground_refractivity`
/// (n₀ − 1; Earth's scales by 1), at `wavelength_nm`. In [0, 1].
double scintillation_variance(const ScintillationOptions& options, double air_mass, double observer_altitude_m,
                              double ground_refractivity, double wavelength_nm = 550.0);
/// Everything of σ_I² but the air mass, before the cap: σ_I² = min(1, this · X³)
/// (scintillation_variance computes it so). The same for every star of a frame:
/// the star pass takes it once per frame and X³ per star.
double scintillation_variance_per_cubed_air_mass(const ScintillationOptions& options, double observer_altitude_m,
                                                 double ground_refractivity, double wavelength_nm = 550.0);
/// min(1, `per_cubed_air_mass` · X³) for Pickering air mass X ≥ 1.
double scintillation_variance_at(double per_cubed_air_mass, double air_mass);

/// The largest |g| scintillation_normal can return: √(−2 ln 2⁻⁵³) (its uniforms have 53 bits).
inline constexpr double kLargestScintillationNormal = 8.572;

/// A standard normal deviate from (star, interval): a fixed function of its
/// arguments (splitmix64, Box–Muller), the same on every machine.
double scintillation_normal(std::uint64_t star, std::int64_t interval);

/// The log-normal intensity factor with mean 1 and variance `variance` for
/// the standard normal `g`: exp(s g − s²/2), s² = ln(1 + variance).
double scintillation_factor(double variance, double g);
/// s = √ln(1 + variance): the standard deviation of ln f.
double scintillation_log_sigma(double variance);
/// exp(s g − s²/2): scintillation_factor from s.
double scintillation_factor_of_log_sigma(double s, double g);

}  // namespace zenith::astro
