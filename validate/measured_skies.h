#pragma once
// Measured clear skies: spectral sky radiance at fixed directions, capture by
// capture, with the sun of each capture — Kider et al. 2014's measurements at
// Cornell on 2013-05-27 as Bruneton 2017's evaluation of eight clear-sky
// models reads them (validate/data/, their README lines; docs/validation.md,
// "Measured skies") — and the extraterrestrial sun that evaluation uses.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"

namespace zenith::validate {

struct MeasuredDirection {
  int sample_index = 0;
  double azimuth_deg = 0.0;                 ///< clockwise from north
  double elevation_deg = 0.0;               ///< above the horizon
  std::vector<double> radiance_W_m2_sr_nm;  ///< at MeasuredSkies::wavelengths_nm
};

struct MeasuredCapture {
  std::string time;  ///< local time of the capture, as the files name it ("09:30")
  double sun_zenith_deg = 0.0;
  double sun_azimuth_deg = 0.0;  ///< clockwise from north, as the evaluation uses it
  std::vector<MeasuredDirection> directions;
  /// The Sun's distance from the site at the capture [au]. Extraterrestrial
  /// spectra are given at 1 au; the sky that day had them × (1 au / distance)².
  /// 1 where the files do not say on which day the capture was taken.
  double sun_distance_au = 1.0;
};

struct MeasuredSkies {
  std::string source;  ///< the radiance file, for reports
  std::vector<double> wavelengths_nm;
  std::vector<MeasuredCapture> captures;
};

/// Parses the radiance table (columns capture_time_EDT, sample_index,
/// azimuth_deg, elevation_deg, then L<wavelength> per wavelength in
/// W m^-2 sr^-1 nm^-1) and the sun table (capture_time_EDT, sun_zenith_deg,
/// sun_azimuth_used_deg). Throws std::invalid_argument naming the file, line
/// and column of a missing column, a value out of range (radiance ≥ 0,
/// azimuth [0, 360], elevation [0, 90], sun zenith [0, 90]), a capture
/// without a sun line or a sun line twice.
MeasuredSkies parse_measured_skies(std::string_view radiance_csv, const std::string& radiance_name,
                                   std::string_view sun_csv, const std::string& sun_name);
/// The same from files; a file that cannot be read is named in the error.
MeasuredSkies load_measured_skies(const std::filesystem::path& radiance_csv, const std::filesystem::path& sun_csv);
/// Kider et al. 2014, Cornell, 2013-05-27: the 15 public captures, compiled in,
/// with the Sun's distance at each (set_sun_distances: the site of the sun
/// table's header, EDT = UTC − 4 h).
MeasuredSkies kider2014_cornell_skies();

/// Sets every capture's sun_distance_au from the ephemeris (astro/sky_positions.h,
/// EPV00): the captures' times ("hh:mm", local) on `day` (its hour and minute
/// ignored), `utc_offset_h` ahead of UTC, seen from `site`. Throws
/// std::invalid_argument naming a capture whose time is not hh:mm.
void set_sun_distances(MeasuredSkies& skies, const astro::UtcTime& day, double utc_offset_h, const astro::Site& site);

/// The extraterrestrial sun of Bruneton 2017's evaluation: ASTM G173-03's
/// ETR column averaged over 11.75 nm bins starting at 360 nm (compiled in).
struct SolarSpectrum {
  std::vector<double> wavelengths_nm;
  std::vector<double> irradiance_W_m2_nm;
  /// The irradiance at one of the sampled wavelengths (within 1e-6 nm); throws
  /// std::invalid_argument naming the wavelength and the sampled range otherwise.
  double at(double wavelength_nm) const;
};
SolarSpectrum astm_g173_extraterrestrial_sun();
/// The same sun as the measurements' spectroradiometer sees it: ASTM G173's
/// ETR column through a Gaussian slit of 3 nm FWHM (an ASD FieldSpec's in
/// 350–1000 nm), at the 31 measured wavelengths (compiled in).
SolarSpectrum astm_g173_extraterrestrial_sun_through_3nm_slit();
/// Parses such a table (columns lambda_nm, irradiance_W_m2_nm); errors as above.
SolarSpectrum parse_solar_spectrum(std::string_view csv, const std::string& name);

}  // namespace zenith::validate
