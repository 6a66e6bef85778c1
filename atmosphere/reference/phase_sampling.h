#pragma once
// Importance sampling of scattering directions.
//
// The path tracer never assumes that a proposal equals the model's phase
// function: a direction drawn from the proposal pdf q carries the weight
// P(ν)/q(ν), so any phase function of the model (Penndorf's fit, which
// integrates to 0.99991, depolarized Rayleigh, double Henyey–Greenstein,
// Cornette–Shanks) is honoured exactly. Proposals:
//  * molecules: the classic Rayleigh phase 3/(16π)(1 + ν²), inverted in closed form;
//  * aerosols: Henyey–Greenstein lobes — the model's own HG or double HG, and HG(g1)
//    for Cornette–Shanks (the ratio CS/HG = 3(1 + ν²)/(2(2 + g²)) ≤ 3/(2 + g²) is bounded);
//    a tabulated phase's own piecewise-uniform proposal (TabulatedPhase::sample_cosine).
// ν is the cosine of the scattering angle (ν = 1 forward).
#include <cstddef>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/reference/medium.h"

namespace zenith::atmosphere::reference {

/// ν distributed as the classic Rayleigh phase, from u ∈ [0, 1): the CDF
/// (ν³ + 3ν + 4)/8 = u is solved by ν = A − 1/A, A = ∛(z + √(z² + 1)), z = 4u − 2.
double sample_rayleigh_classic_cosine(double u);

/// ν distributed as HG(ν; g) from u ∈ [0, 1):
///   ν = (1 + g² − ((1 − g²)/(1 − g + 2 g u))²) / (2g),
/// or 2u − 1 (isotropic) for |g| < 1e-6, where henyey_greenstein_proposal_pdf is 1/4π.
double sample_henyey_greenstein_cosine(double g, double u);
/// The pdf [sr^-1] of sample_henyey_greenstein_cosine (HG, or 1/4π for |g| < 1e-6).
double henyey_greenstein_proposal_pdf(double g, double cos_scattering);

/// ν from the aerosol proposal of `phase` at wavelength i: HG(g1), or the DHG
/// mixture α HG(g1) + (1 − α) HG(g2) (lobe chosen with u_lobe), or a table's
/// segment chosen with u_lobe.
double sample_mie_proposal_cosine(const MiePhase& phase, std::size_t wavelength, double u_lobe, double u);
/// Its pdf [sr^-1].
double mie_proposal_pdf(const MiePhase& phase, std::size_t wavelength, double cos_scattering);

/// A scattering cosine drawn for the medium at one point, with its weight.
struct PhaseSample {
  double cos_scattering = 1.0;  ///< ν
  double weight = 0.0;          ///< P(ν)/q(ν), P the medium's mixture phase, q the proposal pdf
};

/// Draws ν for the mixture phase P = (β_R P_R + β_M P_M)/β_scat at a point with
/// coefficients `c`: Rayleigh is chosen with probability β_R/β_scat (u_component),
/// then ν from that constituent's proposal (u_lobe, u_cos). The pdf of ν is the
/// one-sample mixture q = (β_R q_R + β_M q_M)/β_scat, and E_q[weight · f(ν)] = ∫_{4π} P f dω
/// for any f. Requires β_scat > 0.
PhaseSample sample_scattering_cosine(const AtmosphereMedium& medium, const LocalCoefficients& c, std::size_t wavelength,
                                     double u_component, double u_lobe, double u_cos);

/// The pdf [sr^-1] of sample_scattering_cosine's ν at a point with coefficients `c`:
///   q(ν) = (β_R q_R(ν) + β_M q_M(ν)) / β_scat,  q_R the classic Rayleigh phase 3(1 + ν²)/(16π),
/// q_M the aerosol proposal (mie_proposal_pdf). Requires β_scat > 0.
double scattering_proposal_pdf(const AtmosphereMedium& medium, const LocalCoefficients& c, std::size_t wavelength,
                               double cos_scattering);

}  // namespace zenith::atmosphere::reference
