#include "atmosphere/sky_sampling.h"

#include <sstream>
#include <stdexcept>

#include "atmosphere/constants.h"
#include "atmosphere/photometry.h"
#include "core/units.h"

namespace zenith::atmosphere {

namespace {
using core::kDeg;
}

Vec3 SkyGeometry::sun_direction() const { return direction_from_angles(sun_zenith_deg * kDeg, sun_azimuth_deg * kDeg); }

Vec3 view_vector(const ViewDirection& d) { return direction_from_angles(d.zenith_deg * kDeg, d.azimuth_deg * kDeg); }

std::vector<RadianceSample> sample_radiance(const lut::TableQueries& tables, const SkyGeometry& geometry,
                                            const std::vector<ViewDirection>& directions) {
  std::vector<RadianceSample> out;
  out.reserve(directions.size());
  // The queries need the model only for phases and albedo; the tables carry the geometry.
  const Vec3 observer{0.0, 0.0, tables.tables().geometry.bottom_radius_m + geometry.altitude_m};
  for (const ViewDirection& d : directions)
    out.push_back({d, tables.sky_radiance(observer, view_vector(d), geometry.sun_direction()), {}});
  return out;
}

std::string radiance_csv(const AtmosphereModel& model, const std::vector<RadianceSample>& samples,
                         const ExtraColumns& extra) {
  if (!extra.rows.empty() && extra.rows.size() != samples.size())
    throw std::invalid_argument("radiance CSV: " + std::to_string(extra.rows.size()) + " rows of extra columns for " +
                                std::to_string(samples.size()) + " samples");
  for (const std::vector<double>& row : extra.rows)
    if (row.size() != extra.names.size())
      throw std::invalid_argument("radiance CSV: an extra row of " + std::to_string(row.size()) + " values for " +
                                  std::to_string(extra.names.size()) + " columns");
  std::ostringstream csv;
  csv.precision(9);
  const auto& wl = model.wavelengths_nm;
  const std::vector<double> weights = luminance_weights(wl);
  const bool with_errors = !samples.empty() && samples.front().standard_error.size() == wl.size();
  csv << "zenith_deg,azimuth_deg";
  for (double w : wl) csv << ",L_rel_" << w << "nm_per_sr";
  for (double w : wl) csv << ",L_" << w << "nm_W_m2_sr_nm";
  csv << ",Y_cd_m2";
  for (const std::string& name : extra.names) csv << ',' << name;
  if (with_errors)
    for (double w : wl) csv << ",se_rel_" << w << "nm_per_sr";
  csv << '\n';
  for (std::size_t row = 0; row < samples.size(); ++row) {
    const RadianceSample& s = samples[row];
    csv << s.direction.zenith_deg << ',' << s.direction.azimuth_deg;
    for (double v : s.radiance) csv << ',' << v;
    double y = 0.0;
    for (std::size_t i = 0; i < wl.size(); ++i) {
      const double spectral = s.radiance[i] * solar_irradiance_W_m2_nm(wl[i]);
      csv << ',' << spectral;
      y += weights[i] * spectral;
    }
    csv << ',' << y;
    if (!extra.rows.empty())
      for (double v : extra.rows[row]) csv << ',' << v;
    if (with_errors)
      for (double v : s.standard_error) csv << ',' << v;
    csv << '\n';
  }
  return csv.str();
}

}  // namespace zenith::atmosphere
