#pragma once
// The Johnson V band: how a spectrum becomes a V magnitude or a V surface
// brightness (mag/arcsec²), and back.
//
// Response: a Gaussian in wavelength centred at 551 nm with 88 nm FWHM, the
// band's effective wavelength and width (Binney & Merrifield 1998, Galactic
// Astronomy, Table 2.1; Bessell 2005, ARA&A 43, 293, Table 1 gives 545–551 nm
// and 84–88 nm depending on the source spectrum). A V magnitude is the
// photon-weighted band mean of f_λ against the zero point
//   f_λ(V = 0) = 3.631e-11 W m⁻² nm⁻¹  (Bessell, Castelli & Plez 1998, A&A 333, 231, Table A2):
//   V = −2.5 log10( ∫ f_λ S λ dλ / ∫ S λ dλ / f₀ ).
// Check: the Kurucz solar spectrum of atmosphere/photometry.h gives the Sun
// V = −26.75 (published −26.76, Willmer 2018, ApJS 236, 47): tests/astro.
// A surface brightness μ_V [mag/arcsec²] is the same for radiance per arcsec²
// (1 arcsec² = 2.3504e-11 sr). Spectra known only at the working wavelengths
// are interpolated linearly between them (held flat outside) for the band mean.
#include <functional>
#include <span>

namespace zenith::astro {

inline constexpr double kVZeroPoint_W_m2_nm = 3.631e-11;
inline constexpr double kVCentre_nm = 551.0;
inline constexpr double kVFwhm_nm = 88.0;
inline constexpr double kSteradianPerArcsec2 = 2.350443e-11;  ///< (π/648000)²

/// The V response S(λ), 1 at the centre.
double v_response(double wavelength_nm);

/// Photon-weighted V-band mean of a spectral quantity given as a function of wavelength [nm].
double v_band_mean(const std::function<double(double)>& spectrum);
/// The same for values at `wavelengths_nm` (ascending or not), linear between them.
double v_band_mean(std::span<const double> wavelengths_nm, std::span<const double> values);

/// The V-band mean of a spectral line (an emission line of integrated radiance
/// or irradiance `line` at `wavelength_nm`, e.g. W m⁻² sr⁻¹): line · S λ / ∫ S λ dλ.
double v_band_mean_of_line(double wavelength_nm, double line);

/// V magnitude of a band-mean spectral irradiance [W m⁻² nm⁻¹] (≤ 0 gives +inf).
double v_magnitude(double band_mean_irradiance_W_m2_nm);
/// Band-mean spectral irradiance of a V magnitude.
double v_irradiance_W_m2_nm(double v_mag);
/// V surface brightness [mag/arcsec²] of a band-mean spectral radiance [W m⁻² sr⁻¹ nm⁻¹].
double v_surface_brightness(double band_mean_radiance_W_m2_sr_nm);
/// Band-mean spectral radiance [W m⁻² sr⁻¹ nm⁻¹] of a V surface brightness.
double v_radiance_W_m2_sr_nm(double mag_per_arcsec2);

/// Luminance [cd m⁻²] of a spectral radiance given as a function of wavelength:
/// 683 lm/W ∫ V(λ) L(λ) dλ over 380–780 nm (CIE 1924 V(λ), atmosphere/photometry.h).
double luminance_cd_m2(const std::function<double(double)>& radiance_W_m2_sr_nm);

}  // namespace zenith::astro
