#pragma once
// The Sun's limb darkening: the specific intensity leaving the photosphere at
// an angle arccos μ to the local vertical, relative to the disc's centre,
//   I(μ, λ) / I(1, λ) = Σ_{k=0..5} a_k(λ) μ^k,
// the fifth-degree polynomials Neckel & Labs (1994, Solar Physics 153, 91–114)
// fitted to the centre-to-limb curves they observed from 1986 to 1990 at 30
// continuum wavelengths from 303 to 1099 nm
// (atmosphere/data/solar_limb_darkening_neckel_labs_1994.csv). Between those
// wavelengths the coefficients are interpolated linearly; beyond them the
// nearest row's are kept (the law changes slowly there, and the presets'
// wavelengths lie inside).
//
// Why this law and not a one-parameter one such as the power law μ^α(λ) of
// Hestroffer & Magnan (1998), which zenith drew before: a power law goes to 0
// at the limb, where the measured Sun keeps a_0 = 8–51 % of its centre's
// intensity (303–1099 nm). The limb is all that is left in the last minutes
// before a total eclipse: at 97 % of the disc's area covered the power law
// leaves 6–9 % less light than Neckel & Labs at 430–590 nm, at 98.5 % 10–13 %
// (docs/validation.md, "The Sun's limb"). Bernhard & Petkov (ACP 19, 4703,
// 2019) found the spectral irradiance measured through the 2017 eclipse within
// 4 % of limb darkening observed with the McMath–Pierce telescope above
// 400 nm, up to 97.8 % of the disc covered; Neckel & Labs's coefficients
// "agree basically" with Pierce & Slaughter's (1977), observed there.
//
// The disc's mean radiance over its centre's — what sets the centre radiance
// of a disc of given irradiance (scene/sun_disc.h) — is, with ρ dρ = −r² μ dμ,
//   m = 2 ∫_0^1 I(μ)/I(1) μ dμ = 2 Σ a_k / (k + 2)      (1 for a uniform disc).
#include <array>
#include <string_view>
#include <vector>

namespace zenith::atmosphere {

/// I(μ)/I(1) = Σ a_k μ^k of one wavelength. The default is a uniform disc.
struct LimbDarkening {
  std::array<double, 6> coefficients{1.0, 0.0, 0.0, 0.0, 0.0, 0.0};  ///< a_0 … a_5, Σ a_k = 1

  /// I(μ)/I(1) for μ clamped to [0, 1] (a_0 at the limb, 1 at the centre).
  double intensity(double mu) const;
  /// m = 2 Σ a_k / (k + 2): the disc's mean radiance over its centre's.
  double mean_over_centre() const;

  bool operator==(const LimbDarkening&) const = default;
};

/// Neckel & Labs's law at `wavelength_nm`. Throws std::invalid_argument unless
/// the wavelength is finite and in [100, 10000] nm.
LimbDarkening solar_limb_darkening(double wavelength_nm);
/// The law at each of `wavelengths_nm` (a model's or a scene's), in order.
std::vector<LimbDarkening> solar_limb_darkening(const std::vector<double>& wavelengths_nm);

/// Throws std::invalid_argument, naming `who`, unless the coefficients are
/// finite, sum to 1 within 1e-3, and I(μ) ≥ 0 at μ = 0, 0.1, …, 1.
void check_limb_darkening(const LimbDarkening& law, std::string_view who);

}  // namespace zenith::atmosphere
