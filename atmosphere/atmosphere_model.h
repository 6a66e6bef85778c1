#pragma once
// The resolved atmosphere: per-wavelength coefficients at reference density,
// density profiles and phase functions. This is what the lookup-table
// precomputation, the reference solver and the shaders consume; how it was
// obtained (standard or advanced parameters, see parameters.h) is forgotten here.
//
// Extinction at altitude h and wavelength λ_i (paper eq. 1):
//   β^ext(h) = β_R^scat ρ_R(h) + β_M^ext ρ_M(h) + Σ_absorbers β_a^abs ρ_a(h)
// Scattering: β_R^scat ρ_R(h) with the Rayleigh phase, β_M^scat ρ_M(h) with the Mie phase.
#include <memory>
#include <string>
#include <vector>

#include "atmosphere/air_mass.h"
#include "atmosphere/density_profile.h"
#include "atmosphere/spectrum.h"
#include "atmosphere/tabulated_phase.h"

namespace zenith::atmosphere {

enum class RayleighPhaseModel {
  Classic,      ///< eq. (9)
  Penndorf,     ///< eq. (10)
  Depolarized,  ///< Chandrasekhar's phase with the gas's depolarization δ (exactly normalized)
};

/// "classic", "penndorf" or "depolarized", as in parameter files.
const char* rayleigh_phase_name(RayleighPhaseModel model);

/// Mie phase function, per wavelength. Henyey–Greenstein is the double HG with α = 1.
struct MiePhase {
  enum class Model { HenyeyGreenstein, DoubleHenyeyGreenstein, CornetteShanks, Tabulated };
  Model model = Model::HenyeyGreenstein;
  Spectrum g1;     ///< forward-lobe asymmetry per wavelength, (−1, 1); a table's own asymmetry
  Spectrum g2;     ///< second-lobe asymmetry (DHG only), (−1, 1)
  Spectrum alpha;  ///< weight of the g1 lobe (DHG only), [0, 1]
  /// The table (Tabulated only), resampled at the model's wavelengths; shared,
  /// never changed once built.
  std::shared_ptr<const TabulatedPhase> table;

  /// P_M(cos θ) at wavelength index i [sr^-1].
  double operator()(std::size_t i, double cos_theta) const;
};

/// A purely absorbing constituent (ozone, O2, molecular absorption of eq. 12,
/// or any user-defined absorber).
struct Absorber {
  std::string name;
  Spectrum absorption_m1;  ///< β^abs at reference density [m^-1]
  DensityProfile profile;  ///< relative density
};

struct AtmosphereModel {
  std::string name;                    ///< for messages only; not part of the identity
  std::vector<double> wavelengths_nm;  ///< the working wavelengths
  double ground_radius_m = 0.0;
  double top_radius_m = 0.0;
  Spectrum ground_albedo;  ///< Lambertian reflectance of the ground, [0, 1]

  // Molecules (Rayleigh–Cabannes scattering).
  Spectrum rayleigh_scattering_m1;
  DensityProfile rayleigh_density = DensityProfile::exponential(8000.0);
  RayleighPhaseModel rayleigh_phase = RayleighPhaseModel::Penndorf;
  double rayleigh_depolarization = 0.0;  ///< δ, used by RayleighPhaseModel::Depolarized

  // Aerosols (Mie). Absorption is β^ext − β^scat.
  Spectrum mie_scattering_m1;
  Spectrum mie_extinction_m1;
  DensityProfile mie_density = DensityProfile::exponential(1200.0);
  MiePhase mie_phase;

  std::vector<Absorber> absorbers;

  /// Optical-depth stretch from Pickering's air mass (identity when disabled).
  AirMassStretch air_mass;

  std::size_t wavelength_count() const { return wavelengths_nm.size(); }
  double atmosphere_height_m() const { return top_radius_m - ground_radius_m; }
  bool has_mie() const { return !mie_extinction_m1.all_zero(); }

  /// Rayleigh phase function of the model [sr^-1].
  double rayleigh_phase_function(double cos_theta) const;
  /// Total extinction coefficient at altitude h [m^-1], without the air-mass stretch.
  Spectrum extinction_m1(double altitude_m) const;
  /// Same, written into out[0..wavelength_count()) without allocating (hot loops).
  void extinction_m1(double altitude_m, double* out) const;
  /// Vertical optical depth from the ground to the top, per constituent and total.
  struct ZenithOpticalDepth {
    Spectrum rayleigh, mie_scattering, mie_absorption, total;
    std::vector<std::pair<std::string, Spectrum>> absorbers;
  };
  ZenithOpticalDepth zenith_optical_depth() const;

  /// Throws std::invalid_argument describing the first physical inconsistency
  /// (negative or non-finite coefficient, scattering above extinction, top below
  /// the ground, spectra of the wrong length, ...). Config loading reports the
  /// same conditions with file and key; this guards models built in code.
  void check() const;
};

}  // namespace zenith::atmosphere
