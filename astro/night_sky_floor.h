#pragma once
// The natural night sky: airglow, zodiacal light and integrated starlight, as
// a spectrum with van Rhijn's brightening toward the horizon (docs/night-sky.md,
// "The night sky is not black").
//
// Components (typical at the zenith of a dark site, high ecliptic and galactic
// latitude: Leinert et al. 1998, A&A Suppl. 127, 1, "The 1997 reference of
// diffuse night sky brightness", §1 and Table 2; Roach & Gordon 1973):
//  * airglow lines, in rayleighs (1 R = 10¹⁰/4π photons s⁻¹ m⁻² sr⁻¹):
//    [O I] 557.7 nm 250 R, Na D 589.3 nm 50 R, [O I] 630.0 nm 60 R (Leinert
//    Table 2's typical values); at the working wavelengths a line adds its
//    radiance divided by the width of the wavelength's bin (as luminance
//    weights take bins: atmosphere/photometry.h), so the sampled spectrum
//    carries the line's energy;
//  * airglow continuum, f_λ ∝ λ (rising to the red, Benn & Ellison 1998, La
//    Palma Tech. Note 115, Fig. 1);
//  * zodiacal light and integrated starlight: the solar spectrum (Kurucz, as
//    the Sun), 45 % of the zenith's V (Leinert 1998: ZL ~ 60 S10(V) at the
//    ecliptic poles, ISL ~ 30–40 S10 at high galactic latitude, of ~ 200–250
//    S10 in all).
// The continuum of the airglow is what is left for the zenith to show
// `zenith_v_mag_arcsec2` (default 22.0, the dark-site value: Benn & Ellison
// 1998 measured 21.9 at La Palma at solar minimum; Patat 2003, A&A 400, 1183:
// 21.6–21.9 at Paranal) after the zenith's extinction.
// Van Rhijn (1921): an emitting layer at height h_L (90 km, the O I and Na
// layers) seen at zenith angle z is brighter by
//   V(z) = 1 / √(1 − (R/(R + h_L))² sin² z)   (6.0 at the horizon);
// zodiacal light and starlight lie outside the atmosphere and are taken
// uniform over the sky (their real distribution follows the ecliptic and the
// Milky Way: a limit of this model).
// The renderer attenuates top_of_atmosphere radiance by the line of sight's
// transmittance (the layer at 90 km is above all but 1e-5 of the air).
#include <span>
#include <vector>

#include "atmosphere/atmosphere_model.h"

namespace zenith::astro {

struct NightSkyFloorOptions {
  double zenith_v_mag_arcsec2 = 22.0;  ///< observed V surface brightness at the zenith, [16, 23]
  double airglow_height_m = 90000.0;   ///< the emitting layer of van Rhijn's function
};

class NightSkyFloor {
 public:
  /// Calibrated so the zenith, seen through `model`'s zenith transmittance,
  /// shows options.zenith_v_mag_arcsec2. Throws std::invalid_argument for an
  /// option out of range.
  NightSkyFloor(const atmosphere::AtmosphereModel& model, const NightSkyFloorOptions& options = {});

  /// Radiance above the atmosphere toward zenith angle z [rad] (beyond 90° the
  /// horizon's value), at the model's wavelengths [W m⁻² sr⁻¹ nm⁻¹].
  std::vector<double> top_of_atmosphere_radiance(double zenith_angle_rad) const;
  /// The same attenuated by `transmittance` (per wavelength) of the line of sight.
  std::vector<double> observed_radiance(double zenith_angle_rad, std::span<const double> transmittance) const;
  /// Van Rhijn's factor at zenith angle z.
  double van_rhijn(double zenith_angle_rad) const;
  /// Observed V surface brightness at the zenith [mag/arcsec²] (equals the option: a check).
  double zenith_v_mag_arcsec2() const;
  /// Observed luminance at the zenith [cd m⁻²].
  double zenith_luminance_cd_m2() const;

 private:
  double continuous_radiance(double wavelength_nm, bool airglow) const;  // top of atmosphere, at the zenith
  atmosphere::SpectralTable zenith_transmittance_table() const;          // linear in wavelength
  std::vector<double> wavelengths_nm_, bin_width_nm_, zenith_transmittance_;
  std::vector<double> airglow_zenith_, outside_zenith_;  // per working wavelength, lines included in airglow
  double airglow_continuum_scale_ = 0.0, outside_scale_ = 0.0, lines_scale_ = 1.0;
  double layer_ratio_ = 0.0;  // R / (R + h_L)
  double ground_radius_m_ = 0.0;
};

/// The width of each working wavelength's bin (half the distance to each
/// neighbour; 100 nm for a single wavelength), as atmosphere/photometry.h uses.
std::vector<double> wavelength_bin_widths_nm(std::span<const double> wavelengths_nm);

}  // namespace zenith::astro
