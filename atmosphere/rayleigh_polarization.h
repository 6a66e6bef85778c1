#pragma once
// Rayleigh scattering of polarized light, without Stokes frames: what the
// path tracer's vector transfer (atmosphere/reference/polarization.h) and the
// Moon's shadow on the air (astro/moon_shadow.h) both need of the gas.
//
// A beam travelling along the unit vector k is described by its coherency
// tensor T = ⟨E Eᵀ⟩, a real symmetric 3×3 matrix with T k = 0; its radiance is
// I = tr T, and unpolarized light is (I/2) Π(k), Π(k) = 1 − k kᵀ the projector
// onto the plane across k. A dipole driven by E radiates Π(k_out) E toward
// k_out, so the gas, with its depolarization ρ and the dipole's share of its
// scattering Δ = (1 − ρ)/(1 + ρ/2) (Hansen & Travis, Space Sci. Rev. 16, 527,
// 1974, §2), scatters per unit β and solid angle, times 4π,
//
//   T_out = Δ·(3/2)·Π_out T_in Π_out + (1 − Δ)·tr(T_in)·Π_out/2,             (1)
//
// whose trace for unpolarized light is Δ·(3/4)(1 + ν²) + (1 − Δ), ν = k_in·k_out:
// the depolarized Rayleigh phase times 4π. The degree of polarization of
// once-scattered light is Δ·(3/4)(1 − ν²) over that: 94.6 % at 90° for air (ρ = 0.0279).
#include <glm/mat3x3.hpp>

#include "atmosphere/vec3.h"

namespace zenith::atmosphere {

using Mat3 = glm::dmat3;

/// Π(k) = 1 − k kᵀ, the projector onto the plane across the unit vector k.
Mat3 transverse_projector(const Vec3& k);

/// ⟨A, B⟩ = Σ_ij A_ij B_ij = tr(Aᵀ B).
double contract(const Mat3& a, const Mat3& b);

/// Δ = (1 − ρ)/(1 + ρ/2): the share of the gas's scattering a dipole radiates, ρ ∈ [0, 1).
double dipole_share(double depolarization);

/// The trace of eq. (1) for unpolarized light: Δ·(3/4)(1 + ν²) + (1 − Δ), 4π times the phase.
double depolarized_rayleigh_shape(double dipole_share, double cos_scattering);

/// Eq. (1): the coherency tensor the gas scatters toward the unit k_out from a
/// beam of coherency `t_in` (across k_in), per unit β and solid angle, times 4π.
Mat3 rayleigh_scattered_coherency(double dipole_share, const Vec3& k_out, const Mat3& t_in);

/// The adjoint of eq. (1) in its tensor argument under ⟨A, B⟩ = Σ A_ij B_ij:
/// Δ(3/2) Π_out M Π_out + (1 − Δ)·⟨M, Π_out⟩/2·1.
Mat3 rayleigh_scattered_importance(double dipole_share, const Vec3& k_out, const Mat3& m_out);

/// The coherency tensor of unit radiance the gas has scattered once, from an
/// unpolarized beam along k_in into k_out: eq. (1) for T_in = Π(k_in)/2,
/// divided by its trace (so tr = 1; Π(k_out)/2 where the light is unpolarized).
Mat3 once_scattered_rayleigh_coherency(double dipole_share, const Vec3& k_in, const Vec3& k_out);

}  // namespace zenith::atmosphere
