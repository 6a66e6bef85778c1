#pragma once
// Spherical harmonics for the scattering-density integral of the precomputation.
//
// The density of order n at a point is a spherical convolution of the incoming
// radiance of order n−1 with the phase functions (paper eq. 8):
//
//   J(v) = Σ_species β_s ρ_s(h) ∫_4π P_s(v·ω) L(ω) dω.
//
// By the Funk–Hecke theorem a rotation-invariant kernel is diagonal in the
// spherical harmonics: ∫ P(v·ω) Y_lm(ω) dω = p_l Y_lm(v), with the Legendre
// moments p_l = 2π ∫₋₁¹ P(x) P_l(x) dx (p_0 = 1 for a normalised phase;
// Henyey–Greenstein: p_l = g^l; the classic Rayleigh phase: p_0 = 1, p_2 = 1/10,
// nothing else). So with the incoming radiance projected once,
// a_lm = ∫ L Y_lm dω, the density in every direction is
//
//   J(v) = Σ_lm q_l a_lm Y_lm(v),   q_l = Σ_s β_s ρ_s(h) p_l^s,
//
// exact up to the degree L where the series is cut: the Rayleigh part exactly
// (p_l = 0 for l > 2), the aerosol part to O(g^L) of its forward peak. Since the
// sun, the zenith and the view are all that matter, the incoming radiance at
// (r, μs) is symmetric about the plane of the zenith and the sun, and only the
// cos(mφ) harmonics appear (φ the azimuth from the sun's vertical):
//
//   Y_lm(θ, φ) = c_m P̄_l^m(cos θ) cos(mφ),   c_0 = 1, c_m = √2 (m > 0),
//
// with P̄ the associated Legendre functions normalised so that the Y_lm are
// orthonormal on the sphere (2π ∫ P̄_l^m² dx = 1).
//
// docs/lookup-tables.md ("Scattering density") derives the method and gives
// its accuracy and cost against the direct quadrature it replaces.
#include <cstddef>
#include <functional>
#include <vector>

namespace zenith::atmosphere::lut {

/// Number of harmonics (l, m) with 0 ≤ m ≤ l ≤ degree.
constexpr std::size_t harmonic_count(int degree) {
  return static_cast<std::size_t>(degree + 1) * static_cast<std::size_t>(degree + 2) / 2;
}

/// Position of (l, m) in the m-major packing used throughout: all l ≥ 0 for
/// m = 0, then all l ≥ 1 for m = 1, ... (the recurrence in l runs along memory).
constexpr std::size_t harmonic_index(int degree, int l, int m) {
  const std::size_t mm = static_cast<std::size_t>(m);
  return mm * static_cast<std::size_t>(degree + 1) - mm * (mm - 1) / 2 + static_cast<std::size_t>(l - m);
}

/// The normalisation c_m of the cos(mφ) harmonics: 1 for m = 0, √2 otherwise.
double azimuth_normalisation(int m);

/// P̄_l^m(x) for 0 ≤ m ≤ l ≤ degree, m-major (harmonic_index), by the stable
/// recurrences of the fully normalised functions (Holmes & Featherstone 2002):
///   P̄_0^0 = 1/√(4π),  P̄_m^m = √((2m+1)/2m) √(1−x²) P̄_{m−1}^{m−1},
///   P̄_{m+1}^m = √(2m+3) x P̄_m^m,
///   P̄_l^m = a_lm x P̄_{l−1}^m − b_lm P̄_{l−2}^m,
///   a_lm = √((4l²−1)/(l²−m²)),  b_lm = √((2l+1)(l+m−1)(l−m−1) / ((l−m)(l+m)(2l−3))).
/// (No Condon–Shortley sign: the projection and the evaluation use the same functions.)
void normalized_legendre(int degree, double x, double* out);

/// Legendre moments p_l = 2π ∫₋₁¹ P(x) P_l(x) dx, l = 0..degree, of a phase
/// function P [sr^-1] of the scattering-angle cosine, by a 1024-node
/// Gauss–Legendre rule (exact to rounding for Henyey–Greenstein up to g = 0.95).
std::vector<double> phase_legendre_moments(const std::function<double(double)>& phase, int degree);

/// Gauss–Legendre nodes in μ = cos θ over the sphere of directions at radius
/// r, split at the horizon μ_h = −√(1 − rb²/r²): `nodes_per_part` nodes on
/// [−1, μ_h] (rays that hit the ground) and as many on [μ_h, 1] (rays that reach
/// the top). The incoming radiance jumps at the horizon (sky above, the
/// reflecting ground below); a rule across the jump converges only as 1/n,
/// one per side as fast as the radiance is smooth. Ground nodes come first.
struct HorizonSplitRule {
  std::vector<double> mu;      ///< nodes, ascending within each part
  std::vector<double> weight;  ///< Σ = 2
  int ground_nodes = 0;        ///< mu[0 .. ground_nodes) hit the ground

  HorizonSplitRule(double bottom_radius_m, double r_m, int nodes_per_part);
};

}  // namespace zenith::atmosphere::lut
