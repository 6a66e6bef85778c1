#pragma once
// Linear polarization for the path tracer: vector radiative transfer without
// Stokes frames.
//
// A beam travelling along the unit vector k is described by its coherency
// tensor T = ⟨E Eᵀ⟩ (circular polarization, V, is never made from the
// unpolarized sun by these scatterers and is dropped), and Rayleigh scattering
// is the dipole's eq. (1) of atmosphere/rayleigh_polarization.h, with the
// gas's depolarization: no rotation of reference planes. The path tracer keeps its scalar
// phase functions — the model's Rayleigh phase (Penndorf's fit, say) and the
// aerosol's — as the trace of each map, so unpolarized light is scattered
// exactly as by the scalar solver and only the light's state of polarization
// is added:
//
//   molecules  eq. (1) divided by its own trace for unpolarized light, times P_R(ν);
//   aerosols   the polarization carried through unchanged in the frame of the
//              scattering plane (the unit matrix of a Stokes scattering matrix:
//              T_out = R T_in Rᵀ, R the rotation taking k_in to k_out about
//              k_in × k_out), times P_M(ν) — what a large particle's forward
//              peak, which carries nearly all its scattering, does; the model
//              has no aerosol scattering matrix to do better. The other bound,
//              PolarizedScatterers::aerosol_depolarizes, sends the aerosols'
//              light on unpolarized, tr(T_in) Π_out/2 times P_M(ν), as the
//              ground does: a real haze lies between the two;
//   the ground Lambertian, so unpolarized: tr(T_in) Π_out/2 times the BRDF.
//
// A backward path (from the camera toward the sun) carries the adjoint: an
// importance tensor M, the camera's 1 (it measures I = tr T = ⟨1, T⟩), and at
// each event M ← L*(M)/P(ν), L* the adjoint of the event's map under
// ⟨A, B⟩ = Σ A_ij B_ij (for eq. 1: Δ(3/2) Π_out M Π_out + (1 − Δ)·⟨M, Π_out⟩/2·1;
// for the rotation: Rᵀ M R). Divided by the scalar phase P(ν), M is the
// vector correction of the scalar path's weight; the next-event estimate
// toward the sun (unpolarized, T = Π_in/2) is then ⟨M, L(Π_in/2)⟩ in place of
// P(ν), and the two are equal while M is 1: the first order is the scalar
// solver's, exactly. Every map keeps tensors positive semidefinite, so no
// radiance estimate is ever negative.
//
// A camera behind a linear analyser starts the path with the analyser's tensor
// A instead of 1 and measures ⟨A, T⟩: in a frame (e₁, e₂) across the view ray,
// e₁e₁ᵀ − e₂e₂ᵀ gives Stokes Q = I₁ − I₂ and e₁e₂ᵀ + e₂e₁ᵀ gives U = I₊₄₅ − I₋₄₅.
// These A are indefinite, so their estimates take either sign; the maps are
// linear, so each is unbiased (path_tracer.h's path_traced_stokes).
#include "atmosphere/rayleigh_polarization.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere::reference {

using atmosphere::contract;
using atmosphere::Mat3;
using atmosphere::transverse_projector;

/// The rotation about k_in × k_out taking the unit vector k_in to k_out (the
/// unit matrix for ν = 1; for ν = −1 a half turn about an axis across k_in).
Mat3 rotation_between(const Vec3& k_in, const Vec3& k_out);

/// What scatters at one point, for the light turned from k_in to k_out: the
/// scalar parts of β_scat P(ν), and the gas's depolarization.
struct PolarizedScatterers {
  double rayleigh_m1_sr1 = 0.0;      ///< β_R P_R(ν) [m^-1 sr^-1]
  double aerosol_m1_sr1 = 0.0;       ///< β_M P_M(ν) [m^-1 sr^-1]
  double depolarization = 0.0;       ///< ρ of the gas, in [0, 1)
  bool aerosol_depolarizes = false;  ///< the aerosols' light leaves unpolarized instead of as it came
};

/// The coherency tensor scattered toward k_out by unit volume of the medium,
/// per unit solid angle, from a beam of coherency tensor `t_in` travelling
/// along k_in [m^-1 sr^-1 times t_in's units]: the maps of the header. Its
/// trace for unpolarized light (t_in = Π(k_in)/2) is β_R P_R + β_M P_M.
Mat3 scattered_coherency(const PolarizedScatterers& s, const Vec3& k_in, const Vec3& k_out, const Mat3& t_in);

/// The adjoint of scattered_coherency in its tensor argument:
/// ⟨scattered_importance(s, k_in, k_out, M), T⟩ = ⟨M, scattered_coherency(s, k_in, k_out, T)⟩
/// for every T across k_in.
Mat3 scattered_importance(const PolarizedScatterers& s, const Vec3& k_in, const Vec3& k_out, const Mat3& m_out);

}  // namespace zenith::atmosphere::reference
