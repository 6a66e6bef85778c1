#pragma once
// The solar disc as the camera sees it: a limb-darkened sphere, so that the
// renderer can draw the sun (the paper's model stops at the sky).
//
// Limb darkening: I(μ, λ)/I(1, λ) = Σ a_k(λ) μ^k, Neckel & Labs (1994)
// (atmosphere/solar_limb_darkening.h), μ the cosine at the photosphere.
//
// Geometry (exact, not small-angle): the sun is a sphere of radius R at distance
// D, seen under the angular radius θ_s with sin θ_s = R / D. The line of sight at
// an angle θ from the disc centre passes the sun's centre at the impact
// parameter b = D sin θ, meets the photosphere where sin(angle to the normal) =
// b / R, so
//   μ(θ) = sqrt(1 − sin²θ / sin²θ_s),   0 ≤ θ ≤ θ_s.
// For small discs this is the familiar sqrt(1 − (θ/θ_s)²); the exact form keeps
// the normalization below exact for any disc size (scenes allow up to 30°).
//
// Normalization: the irradiance E [W m^-2 nm^-1] is the flux through a plane
// facing the sun's centre (the convention of the Kurucz spectrum and of the
// reference solver), E = ∫_disc L(θ) cos θ dΩ with dΩ = sin θ dθ dφ. With
// L = L_0 I(μ)/I(1), s = sin θ (ds = cos θ dθ) and u = s² / sin²θ_s = 1 − μ²:
//   E = 2π L_0 ∫_0^{sin θ_s} I(μ(s))/I(1) s ds
//     = π L_0 sin²θ_s ∫_0^1 I(μ)/I(1) 2μ dμ = π L_0 sin²θ_s m,
// m the disc's mean radiance over its centre's (2 Σ a_k/(k + 2)), hence the
// centre radiance L_0 = E / (π sin²θ_s m). A uniform disc (m = 1) is the
// reference solver's, E / (π sin²θ_s). Radiance is conserved along rays in
// vacuum, so L is the same at any distance; the atmosphere then attenuates it.
#include "atmosphere/solar_limb_darkening.h"

namespace zenith::scene {

/// The astronomical unit [m] (IAU 2012 Resolution B2, exact).
inline constexpr double kAstronomicalUnit_m = 1.495978707e11;
/// The nominal solar radius [m] (IAU 2015 Resolution B3): 2 asin(R/1 AU) = 0.533°.
inline constexpr double kSolarRadius_m = 6.957e8;

/// μ at the photosphere for a line of sight at `angle_from_centre_rad` from the
/// disc centre, on a disc of angular radius θ_s: sqrt(1 − sin²θ / sin²θ_s);
/// 0 on and outside the limb. Throws std::invalid_argument unless 0 < θ_s < π/2.
double disc_mu(double angle_from_centre_rad, double angular_radius_rad);

/// Radiance at the disc centre L_0 [W m^-2 sr^-1 nm^-1] such that the
/// limb-darkened disc delivers exactly `irradiance_W_m2_nm` on a plane facing
/// it: L_0 = E / (π sin²θ_s m), m of the Sun's law at the wavelength. Throws
/// std::invalid_argument unless E ≥ 0 and finite, 0 < θ_s < π/2 and the
/// wavelength is in [100, 10000] nm.
double disc_centre_radiance(double irradiance_W_m2_nm, double angular_radius_rad, double wavelength_nm);

/// Radiance of a uniform disc (no limb darkening) delivering the same
/// irradiance: E / (π sin²θs) = L_0 m. For drawing the sun with limb
/// darkening turned off.
double uniform_disc_radiance(double irradiance_W_m2_nm, double angular_radius_rad);

/// Radiance of the disc along a line of sight at `angle_from_centre_rad` from
/// its centre: L_0 I(μ)/I(1) (0 outside the disc).
double disc_radiance(double irradiance_W_m2_nm, double angular_radius_rad, double wavelength_nm,
                     double angle_from_centre_rad);

}  // namespace zenith::scene
