#pragma once
// Sky radiance for a list of view directions seen from a point above the
// ground, from the lookup tables or from the reference solver. Used by
// `zenith sample` and by the accuracy tests, so both query the same way.
//
// Frame: the observer stands on the +z axis at altitude h; zenith angles are
// measured from +z, azimuths from +x toward +y. The sun is given the same way.
#include <string>
#include <vector>

#include "atmosphere/atmosphere_model.h"
#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/vec3.h"

namespace zenith::atmosphere {

struct ViewDirection {
  double zenith_deg;
  double azimuth_deg;
};

struct SkyGeometry {
  double altitude_m = 0.0;
  double sun_zenith_deg = 30.0;
  double sun_azimuth_deg = 0.0;
  Vec3 observer_m(const AtmosphereModel& m) const { return {0.0, 0.0, m.ground_radius_m + altitude_m}; }
  Vec3 sun_direction() const;
};

Vec3 view_vector(const ViewDirection& d);

struct RadianceSample {
  ViewDirection direction;
  Spectrum radiance;        ///< per unit solar irradiance [sr^-1]
  Spectrum standard_error;  ///< reference method only (else empty)
};

std::vector<RadianceSample> sample_radiance(const lut::TableQueries& tables, const SkyGeometry& geometry,
                                            const std::vector<ViewDirection>& directions);

/// Columns a caller adds after the radiance_csv's own: one name each, and per
/// sample one value each (rows: as many as samples, or none).
struct ExtraColumns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
};

/// CSV: zenith_deg, azimuth_deg, radiance per unit solar irradiance per
/// wavelength, spectral radiance for the Kurucz sun at 1 AU per wavelength,
/// luminance Y [cd m^-2] (docs/physics.md, "Photometry"), `extra`'s columns,
/// and for the reference method the standard errors. Throws
/// std::invalid_argument when `extra` has rows but not one per sample, or a
/// row not one value per name.
std::string radiance_csv(const AtmosphereModel& model, const std::vector<RadianceSample>& samples,
                         const ExtraColumns& extra = {});

}  // namespace zenith::atmosphere
