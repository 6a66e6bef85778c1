#pragma once
// Random atmosphere parameter sets within the valid ranges of
// docs/atmosphere-config.md (standard mode), for the numerical-stability
// stress. Deterministic: set `index` of seed S is always the same file. No GL.
//
// Drawn (log-uniform where a range spans decades):
//  * planet radius 1e4…1e9 m, atmosphere height 10 m…1e7 m, ground albedo 0…1
//    (one number, or per wavelength);
//  * Rayleigh scattering 1e-9…1e-2 m^-1 per wavelength, scale height 1 m…1e6 m,
//    phase penndorf / classic / depolarized (depolarization 0…0.5);
//  * Mie (70%): extinction 1e-9…1e-2 m^-1, scattering = extinction × 0…1,
//    scale height 1 m…1e6 m, phase Henyey–Greenstein / Cornette–Shanks
//    (g −0.999…0.999) or double Henyey–Greenstein (g1 0…0.999, g2 −0.999…0, α 0…1);
//  * one exponential absorber (30%): 1e-9…1e-3 m^-1, scale height 1 m…1e6 m;
//  * geometric air mass, the paper's wavelengths 680/550/440 nm.
// The advanced mode's derivations are exercised by the presets that use it.
#include <cstdint>

#include <nlohmann/json.hpp>

namespace zenith::validate {

/// Parameter set `index` of `seed` (zenith_atmosphere 1, standard mode), named "random-<seed>-<index>".
nlohmann::json random_atmosphere_parameters(std::uint64_t seed, std::uint64_t index);

}  // namespace zenith::validate
