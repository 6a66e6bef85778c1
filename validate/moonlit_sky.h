#pragma once
// The published model of the moonlit sky's brightness that the renderer's
// moonlight (the precomputed tables lit by the Moon, render/night/moon_light.h)
// is checked against (docs/night-sky.md, "Moonlight").
//
// Krisciunas & Schaefer (1991, PASP 103, 1033), fitted to V-band sky
// brightness measured on Mauna Kea under the Moon at many phases, altitudes
// and separations: the sky's brightness at zenith distance Z, ρ degrees from a
// Moon at zenith distance Z_m and phase angle α (degrees), with the extinction
// coefficient k (mag per air mass, V), is
//   B_moon = f(ρ) I* 10^(−0.4 k X(Z_m)) [1 − 10^(−0.4 k X(Z))]   [nanolamberts]
//   I*     = 10^(−0.4 (3.84 + 0.026 |α| + 4·10⁻⁹ α⁴))   the Moon's illuminance (eq. 20)
//   f(ρ)   = 10^5.36 (1.06 + cos² ρ) + 10^(6.15 − ρ/40)  Rayleigh and aerosol scattering (eq. 21, ρ > 10°)
//   X(Z)   = (1 − 0.96 sin² Z)^(−1/2)                    their air mass
// The authors give the model's agreement with their measurements as 8–23 %.
namespace zenith::validate {

/// K&S 1991's moonlit sky brightness [nL] for a Moon at phase angle
/// `phase_angle_deg`, zenith distance `moon_zenith_deg` (< 90°), `separation_deg`
/// (> 10°) from the sky point at `sky_zenith_deg`, extinction `k_v` [mag/air mass].
double krisciunas_schaefer_moon_nL(double phase_angle_deg, double separation_deg, double moon_zenith_deg,
                                   double sky_zenith_deg, double k_v);

/// A surface brightness in nanolamberts as V mag/arcsec² (the inverse of
/// Garstang's conversion, validate/visibility.h: μ = (20.7233 − ln(B/34.08)) / 0.92104).
double v_mag_arcsec2_from_nanolamberts(double nanolamberts);

}  // namespace zenith::validate
