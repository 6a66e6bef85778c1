#pragma once
// The Moon's light (docs/night-sky.md, "The Moon").
//
// Disc: the Lommel–Seeliger law, the single-scattering limit of a dark
// particulate surface (Hapke 1993, "Theory of Reflectance and Emittance
// Spectroscopy", §8.E): the radiance of a point of the disc lit at incidence
// cosine μ₀ and seen at emission cosine μ is
//   L = (2/π) E_sun(λ) p(λ) f(α) μ₀ / (μ₀ + μ),
// with no limb darkening at full Moon (the real Moon's look). Integrated over
// the disc it gives Φ_LS(α) = 1 − sin(α/2) tan(α/2) ln cot(α/4) (normalized to
// 1 at α = 0). That alone makes the quarter Moon 1.1 mag fainter than full,
// against 2.2 mag observed: the opposition surge and the shadows of the rough
// surface, which Hapke's full model adds with fitted parameters. We take the
// brightness by phase from the Moon's measured integral phase curve instead
// (Allen 1973, as Krisciunas & Schaefer 1991, PASP 103, 1033, eq. 20 use it):
//   V(α) = −12.73 + 0.026 |α| + 4·10⁻⁹ α⁴   (α in degrees, mean distance 384 400 km),
// and let f(α) = 10^(−0.4 (0.026|α| + 4e-9 α⁴)) / Φ_LS(α) carry it: the disc has
// Lommel–Seeliger's distribution of brightness and the measured total.
// Colour: the Moon is redder than the Sun (B−V 0.92 against 0.65: Allen's
// Astrophysical Quantities, 4th ed., §12.6 and §14.7); reflectance linear in λ,
// A(λ) ∝ 1 + 0.0020 (λ − 550 nm) (−0.27 mag in B−V between 440 and 550 nm).
// Irradiance at the top of the atmosphere (what scales the precomputed sky,
// linear in its source, for moonlight):
//   E_moon(λ) = E_sun(λ) (1 AU/d_sun)² · p(λ) Φ(α) (R_moon / d)²,
// p(550) the geometric albedo that makes the full Moon at 384 400 km V = −12.73
// with the Kurucz Sun (0.12, as published: 0.12, Allen).
#include <span>
#include <vector>

#include "astro/sky_positions.h"

namespace zenith::astro {

/// Φ_LS(α): the Lommel–Seeliger disc integral, 1 at α = 0, 0 at α = π.
double lommel_seeliger_phase(double phase_angle_rad);
/// The Moon's measured integral phase law, 10^(−0.4 ΔV(α)), 1 at full.
double lunar_phase_law(double phase_angle_rad);
/// Geometric albedo p(λ) (p(550 nm) fitted as above).
double lunar_geometric_albedo(double wavelength_nm);
/// V magnitude of the Moon at phase angle α and distance d [km] from the
/// observer, Sun at `sun_distance_au`.
double moon_v_magnitude(double phase_angle_rad, double distance_km, double sun_distance_au = 1.0);

/// Spectral irradiance of the whole Moon at the top of the atmosphere [W m⁻² nm⁻¹].
std::vector<double> moon_irradiance_W_m2_nm(const MoonPlace& moon, std::span<const double> wavelengths_nm);

/// Radiance of a point of the disc [W m⁻² sr⁻¹ nm⁻¹] with incidence and
/// emission cosines μ₀, μ (μ₀ ≤ 0: night side, 0) at phase angle α.
double moon_disc_radiance(double mu0, double mu, double phase_angle_rad, double wavelength_nm,
                          double sun_distance_au = 1.0);

}  // namespace zenith::astro
