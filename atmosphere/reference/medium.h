#pragma once
// Local optical properties of a model's atmosphere, evaluated without heap
// allocation for the inner loops of the reference solver. The values are the
// same as AtmosphereModel::extinction_m1 (paper eq. 1), split into the parts the
// radiative transfer needs.
#include <cstddef>
#include <span>

#include "atmosphere/atmosphere_model.h"

namespace zenith::atmosphere::reference {

/// Coefficients at one altitude and one wavelength [m^-1], without the air-mass stretch.
struct LocalCoefficients {
  double rayleigh_scattering_m1 = 0.0;  ///< β_R^scat ρ_R(h)
  double mie_scattering_m1 = 0.0;       ///< β_M^scat ρ_M(h)
  double extinction_m1 = 0.0;           ///< β_R^scat ρ_R + β_M^ext ρ_M + Σ_a β_a^abs ρ_a
  double scattering_m1() const { return rayleigh_scattering_m1 + mie_scattering_m1; }
};

/// A read-only view of an AtmosphereModel as a participating medium. Holds a
/// reference: the model must outlive it.
class AtmosphereMedium {
 public:
  explicit AtmosphereMedium(const AtmosphereModel& model) : model_(&model) {}
  const AtmosphereModel& model() const { return *model_; }
  std::size_t wavelength_count() const { return model_->wavelength_count(); }

  /// β_ext(h) at wavelength index i [m^-1].
  double extinction_m1(double altitude_m, std::size_t wavelength) const;
  /// β_ext(h) for every wavelength into `out` (size = wavelength count) [m^-1].
  void extinction_m1(double altitude_m, std::span<double> out) const;
  /// Scattering and extinction at wavelength index i.
  LocalCoefficients coefficients(double altitude_m, std::size_t wavelength) const;
  /// The same for every wavelength into `out`.
  void coefficients(double altitude_m, std::span<LocalCoefficients> out) const;

  /// Scattering phase function of the mixture at wavelength i [sr^-1]:
  ///   P(ν) = (β_R P_R(ν) + β_M P_M,i(ν)) / (β_R + β_M),
  /// with ν the cosine of the scattering angle; 0 where nothing scatters.
  double mixture_phase(const LocalCoefficients& c, std::size_t wavelength, double cos_scattering) const;

 private:
  const AtmosphereModel* model_;
};

}  // namespace zenith::atmosphere::reference
