#pragma once
// Physical constants (CODATA 2018 exact or recommended values), SI units.
#include "core/units.h"

namespace zenith::atmosphere {

inline constexpr double kPi = core::kPi;
inline constexpr double kAvogadro_per_mol = 6.02214076e23;                                  ///< N_A [mol^-1]
inline constexpr double kBoltzmann_J_per_K = 1.380649e-23;                                  ///< k_B [J K^-1]
inline constexpr double kGasConstant_J_per_mol_K = kAvogadro_per_mol * kBoltzmann_J_per_K;  ///< R [J mol^-1 K^-1]
/// One Dobson unit: 2.6867e20 molecules per m^2 of column (0.01 mm of pure gas at STP).
inline constexpr double kDobsonUnit_per_m2 = 2.6867e20;
inline constexpr double kStandardGravity_m_s2 = 9.80665;

}  // namespace zenith::atmosphere
