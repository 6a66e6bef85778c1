#pragma once
// `zenith sample` queries, as CSV text: sky radiance, transmittance along the
// view direction, ground irradiance — from the lookup tables or the reference.
#include <array>
#include <string>
#include <vector>

#include "astro/moon_shadow.h"
#include "astro/sky_positions.h"
#include "atmosphere/reference/sun_disc.h"
#include "atmosphere/sky_sampling.h"
#include "render/lut/table_provider.h"

namespace zenith::app {

enum class SamplingMethod { Tables, Reference };

struct SamplingRequest {
  atmosphere::SkyGeometry geometry;
  std::vector<atmosphere::ViewDirection> directions;
  SamplingMethod method = SamplingMethod::Tables;
  double sun_angular_radius_deg = 0.2666;  ///< the sun seen from Earth
  /// Reference method: a limb-darkened disc (one law per wavelength; empty: uniform) and the Moon in
  /// front of it (a solar eclipse), in the frame of `geometry`.
  std::vector<atmosphere::LimbDarkening> limb_darkening;
  atmosphere::reference::Occulter occulter;
  std::size_t reference_samples = 4096;  ///< Monte Carlo paths per wavelength and direction
  bool polarized = false;                ///< reference method: vector radiative transfer instead of scalar
  /// Reference method with `polarized`: also each direction's linear polarization — Stokes Q and U against
  /// the vertical (e₁ up across the view, e₂ toward increasing azimuth; at the zenith "up" is away from the
  /// row's azimuth), the degree P with its standard error and the E-vector's angle from the vertical.
  bool stokes = false;
  /// Reference method with `polarized`: the aerosols send their light on unpolarized (the other bound of their
  /// scattering matrix; atmosphere/reference/polarization.h).
  bool aerosol_depolarizes = false;
  /// Reference method: only the light scattered this many times, first to last (1: single scattering and the
  /// direct sun the ground reflects), to split a sky by order (atmosphere/reference/path_tracer.h).
  std::array<int, 2> reference_orders = {1, 1000};
  /// Tables with the Moon in front of the sun: how its shadow is made (passes, polarization).
  astro::MoonShadowOptions shadow;
  /// Radiance: also each direction's colour — CIE 1931 x, y of the spectral radiance, its correlated colour
  /// temperature and Duv, and its effective blackbody temperature over `colour_band_nm` (image/colour.h);
  /// needs wavelengths that span the visible (colour_spectrum_problem).
  bool colour = false;
  std::array<double, 2> colour_band_nm = {410.0, 800.0};  ///< first, last wavelength of the effective temperature
  std::uint64_t seed = 1;
  unsigned threads = 0;
  render::TableRequest tables;
};

/// The Sun and the Moon of `sky` (its time and site) put into `r` for the reference method: the sun's place
/// and true size, its limb darkening (scene/sun_disc.h) and the Moon as the occulter. The frame of
/// sky_sampling.h with +x north and +y east, so azimuths count from north through east as an almanac's.
void place_sun_and_moon(const astro::SkyPositions& sky, const atmosphere::AtmosphereModel& model, SamplingRequest& r);

std::string sample_radiance_csv(const atmosphere::AtmosphereModel& model, const SamplingRequest& request);
std::string sample_transmittance_csv(const atmosphere::AtmosphereModel& model, const SamplingRequest& request);
std::string sample_irradiance_csv(const atmosphere::AtmosphereModel& model, const SamplingRequest& request);

}  // namespace zenith::app
