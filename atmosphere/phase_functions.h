#pragma once
// Scattering phase functions P(cos θ) [sr^-1], each normalized so that
// ∫_{4π} P dω = 1 (Penndorf's fit integrates to 0.99991, see below).
// θ is the scattering angle: θ = 0 is forward scattering.
#include "core/units.h"

namespace zenith::atmosphere {

/// 1/4π [sr^-1], the factor of every phase function below (INV_4PI in the shaders).
inline constexpr double kInv4Pi = 1.0 / (4.0 * core::kPi);
/// Penndorf's fit (rayleigh_phase_penndorf): P_R = kPenndorfA (1 + kPenndorfB cos²θ) / 4π
/// (PENNDORF_A, PENNDORF_B in the shaders).
inline constexpr double kPenndorfA = 0.7629;
inline constexpr double kPenndorfB = 0.932;

/// Classic Rayleigh phase function, paper eq. (9):
///   P_R(θ) = 3/4 (1 + cos²θ) / 4π.
double rayleigh_phase_classic(double cos_theta);

/// Penndorf's Rayleigh phase function for air, paper eq. (10):
///   P_R(θ) = 0.7629 (1 + 0.932 cos²θ) / 4π.
/// The constants are Penndorf's (1957) fit; as printed they integrate to
/// 0.7629·(4π)(1 + 0.932/3)/4π = 0.99991 over the sphere, not exactly 1. We keep
/// them verbatim (the 9e-5 deficit is below the model's accuracy).
double rayleigh_phase_penndorf(double cos_theta);

/// Rayleigh phase with depolarization δ (Chandrasekhar; Hansen & Travis 1974):
///   P(θ) = 3/(4(1+2γ)) ((1+3γ) + (1−γ) cos²θ) / 4π,   γ = δ/(2−δ).
/// Normalized exactly; used where a molecule other than air has no fitted phase.
double rayleigh_phase_depolarized(double cos_theta, double depolarization);

/// Henyey–Greenstein lobe with asymmetry g ∈ (−1, 1):
///   HG(θ; g) = (1 − g²) / (1 + g² − 2 g cos θ)^{3/2} / 4π.
double henyey_greenstein(double cos_theta, double g);

/// Double Henyey–Greenstein phase function, paper eq. (16), corrected:
///   P_M(θ) = α HG(θ; g1) + (1 − α) HG(θ; g2).
/// The printed eq. (16) has (1 + g1²) in both numerators; each lobe must be a
/// normalized HG lobe with (1 − g_i²), otherwise P does not integrate to 1 and the
/// second lobe depends on g1. g1 > 0 gives the forward lobe, g2 < 0 a backward one;
/// α ∈ [0, 1] weights them.
double double_henyey_greenstein(double cos_theta, double g1, double g2, double alpha);

/// Cornette–Shanks (1992) phase function, a physically better-behaved HG variant:
///   P(θ) = 3(1 − g²)(1 + cos²θ) / (2(2 + g²)(1 + g² − 2g cos θ)^{3/2}) / 4π.
double cornette_shanks(double cos_theta, double g);

}  // namespace zenith::atmosphere
