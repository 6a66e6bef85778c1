#pragma once
// Artificial sky glow in physical units (docs/night-sky.md, "Light pollution").
//
// Given: the artificial part of the zenith's luminance [mcd m⁻²] (what a
// luminance meter at the site measures minus the natural sky), or a Bortle
// class mapped to a total zenith V surface brightness (the Bortle scale's
// sky-quality-meter ranges, e.g. Wikipedia "Bortle scale" after Bortle 2001,
// Sky & Telescope 101(2), 126; the midpoint of each class's range:
//   1: 21.99  2: 21.94  3: 21.79  4: 21.09  5: 20.0  6: 19.22  7: 18.66
//   8: 18.0   9: 17.5 (classes 8 and 9 share "< 18.38"; our split)),
// from which the natural floor's zenith luminance is subtracted.
// Spectrum: the lamps' light (a blackbody at the correlated colour temperature,
// default 3000 K, between high-pressure sodium's ~2000 K and white LEDs'
// 4000 K) times the air's scattering coefficient relative to 550 nm (the glow
// is lamp light scattered once by the model's molecules and aerosols, so it is
// bluer than the lamps: Rayleigh's λ⁻⁴).
// Gradient: the glow of a site surrounded by lights is the source function S of
// a scattering layer seen through it, L(z) = S (1 − e^(−τ X(z))) (radiative
// transfer in a homogeneous slab), X Pickering's air mass, τ the model's zenith
// scattering optical depth at each wavelength; normalized to the zenith:
//   L(z) = L_zenith (1 − e^(−τ X(z))) / (1 − e^(−τ)),
// 5.5× the zenith at the horizon for τ = 0.2 (1.9 mag brighter). That ratio
// is the slab model's: measured gradients depend on where the lights are, and
// a city to one side makes the glow depend on azimuth too; not modelled.
#include <optional>
#include <span>
#include <vector>

#include "atmosphere/atmosphere_model.h"

namespace zenith::astro {

struct LightPollutionOptions {
  double zenith_mcd_m2 = 0.0;            ///< artificial zenith luminance, [0, 1e5] mcd m⁻² (0: none)
  double colour_temperature_K = 3000.0;  ///< lamps' correlated colour temperature, [1500, 10000] K
};

/// Total zenith V surface brightness of a Bortle class 1–9 (above). Throws
/// std::invalid_argument outside 1–9.
double bortle_zenith_v_mag_arcsec2(int bortle_class);

class LightPollution {
 public:
  LightPollution(const atmosphere::AtmosphereModel& model, const LightPollutionOptions& options);

  /// Observed radiance at zenith angle z (clamped to 90°) [W m⁻² sr⁻¹ nm⁻¹]
  /// at the model's wavelengths (already through the air: no further attenuation).
  std::vector<double> radiance(double zenith_angle_rad) const;
  /// Ratio L(z) / L(0) at `wavelength_index`.
  double gradient(double zenith_angle_rad, std::size_t wavelength_index) const;
  double zenith_mcd_m2() const { return zenith_mcd_m2_; }

 private:
  std::vector<double> wavelengths_nm_, zenith_radiance_, scattering_depth_;
  double zenith_mcd_m2_ = 0.0;
};

/// The artificial zenith luminance [mcd m⁻²] that brings a sky whose natural
/// zenith luminance is `natural_cd_m2` to a Bortle class's total brightness,
/// both in V; the glow's spectrum (blackbody × scattering) converts V to luminance.
double bortle_artificial_mcd_m2(int bortle_class, const atmosphere::AtmosphereModel& model, double natural_cd_m2,
                                double colour_temperature_K = 3000.0);

}  // namespace zenith::astro
