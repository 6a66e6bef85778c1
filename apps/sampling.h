#pragma once
// `zenith sample` queries, as CSV text: sky radiance, transmittance along the
// view direction, ground irradiance — from the lookup tables or the reference.
#include <string>
#include <vector>

#include "atmosphere/sky_sampling.h"
#include "render/lut/table_provider.h"

namespace zenith::app {

enum class SamplingMethod { Tables, Reference };

struct SamplingRequest {
  atmosphere::SkyGeometry geometry;
  std::vector<atmosphere::ViewDirection> directions;
  SamplingMethod method = SamplingMethod::Tables;
  double sun_angular_radius_deg = 0.2666;  ///< the sun seen from Earth
  std::size_t reference_samples = 4096;    ///< Monte Carlo paths per wavelength and direction
  std::uint64_t seed = 1;
  unsigned threads = 0;
  render::TableRequest tables;
};

std::string sample_radiance_csv(const atmosphere::AtmosphereModel& model, const SamplingRequest& request);
std::string sample_transmittance_csv(const atmosphere::AtmosphereModel& model, const SamplingRequest& request);
std::string sample_irradiance_csv(const atmosphere::AtmosphereModel& model, const SamplingRequest& request);

}  // namespace zenith::app
