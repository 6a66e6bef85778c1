#include "apps/sampling.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "astro/eclipsed_sky.h"
#include "astro/moon_shadow.h"
#include "astro/solar_eclipse.h"
#include "atmosphere/constants.h"
#include "atmosphere/photometry.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/optical_depth.h"
#include "atmosphere/reference/path_tracer.h"
#include "atmosphere/solar_limb_darkening.h"
#include "core/progress_bar.h"
#include "core/units.h"
#include "image/colour.h"

namespace zenith::app {
namespace {

using namespace atmosphere;

reference::SunDisc sun_disc(const SamplingRequest& r) {
  reference::SunDisc disc;
  disc.direction = r.geometry.sun_direction();
  disc.angular_radius_rad = r.sun_angular_radius_deg * kPi / 180.0;
  disc.limb_darkening = r.limb_darkening;
  disc.occulter = r.occulter;
  return disc;
}

reference::PathTracerOptions tracer_options(const SamplingRequest& r) {
  reference::PathTracerOptions o;
  o.samples_per_wavelength = r.reference_samples;
  o.seed = r.seed;
  o.thread_count = r.threads;
  o.polarized = r.polarized;
  o.aerosol_depolarizes = r.aerosol_depolarizes;
  o.min_scattering_order = r.reference_orders[0];
  o.max_scattering_order = r.reference_orders[1];
  return o;
}

/// The vertical across the view d: e₁ = −∂v/∂z, "up" on the sky — at the zenith, away from d's azimuth.
Vec3 vertical_across(const ViewDirection& d) {
  const double z = d.zenith_deg * kPi / 180.0, a = d.azimuth_deg * kPi / 180.0;
  return {-std::cos(z) * std::cos(a), -std::cos(z) * std::sin(a), std::sin(z)};
}

/// Q and U per wavelength, then the degree P, its standard error to first order (the three estimates'
/// correlation neglected) and the E-vector's angle from the vertical [deg].
std::vector<double> polarization_row(const reference::StokesEstimate& e) {
  std::vector<double> row(e.q.begin(), e.q.end());
  row.insert(row.end(), e.u.begin(), e.u.end());
  const std::size_t n = e.i.size();
  std::vector<double> degree(n), error(n), angle(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double p = reference::degree_of_linear_polarization(e.i[k], e.q[k], e.u[k]);
    const double linear = std::hypot(e.q[k], e.u[k]);
    double se = 0.0;
    if (e.i[k] > 0.0) {
      const double from_qu =
          linear > 0.0 ? std::hypot(e.q[k] * e.q_standard_error[k], e.u[k] * e.u_standard_error[k]) / (linear * e.i[k])
                       : std::hypot(e.q_standard_error[k], e.u_standard_error[k]) / e.i[k];
      se = std::hypot(from_qu, p * e.i_standard_error[k] / e.i[k]);
    }
    degree[k] = p;
    error[k] = se;
    angle[k] = reference::polarization_angle_rad(e.q[k], e.u[k]) * 180.0 / kPi;
  }
  for (const auto* column : {&degree, &error, &angle}) row.insert(row.end(), column->begin(), column->end());
  return row;
}

std::string spectrum_header(const AtmosphereModel& m, const std::string& prefix) {
  std::string h;
  for (double w : m.wavelengths_nm) h += "," + prefix + std::to_string(int(std::lround(w))) + "nm";
  return h;
}

}  // namespace

void place_sun_and_moon(const astro::SkyPositions& sky, const AtmosphereModel& model, SamplingRequest& r) {
  const astro::SunAndMoon s = astro::sun_and_moon(sky, r.geometry.observer_m(model).z);
  r.geometry.sun_zenith_deg = s.sun_zenith_deg;
  r.geometry.sun_azimuth_deg = s.sun_azimuth_deg;
  r.sun_angular_radius_deg = s.sun_angular_radius_rad / core::kDeg;
  r.limb_darkening = solar_limb_darkening(model.wavelengths_nm);
  r.occulter.centre_m = s.moon_centre_m;
  r.occulter.radius_m = s.moon_radius_m;
}

std::string sample_radiance_csv(const AtmosphereModel& model, const SamplingRequest& r) {
  if (r.stokes && !(r.method == SamplingMethod::Reference && r.polarized))
    throw std::invalid_argument("the sky's polarization is the reference solver's in vector transfer (--polarized)");
  std::vector<RadianceSample> samples;
  std::vector<std::vector<double>> polarization;  // per direction: polarization_row
  if (r.method == SamplingMethod::Tables) {
    const render::ObtainedTables t = render::obtain_tables(model, r.tables);
    const lut::TableQueries queries(model, t.tables);
    if (r.occulter.radius_m > 0.0) {
      // A solar eclipse: the tables with the Moon's shadow over them (astro/eclipsed_sky.h).
      const Vec3 observer = r.geometry.observer_m(model);
      const astro::EclipseGeometry g{r.occulter.centre_m, r.occulter.radius_m, r.geometry.sun_direction(),
                                     r.sun_angular_radius_deg * core::kDeg, r.limb_darkening};
      astro::MoonShadowOptions options = r.shadow;
      options.threads = r.threads;
      const astro::MoonShadow shadow(g, queries, model, observer, options);
      for (const ViewDirection& d : r.directions)
        samples.push_back({d, astro::eclipsed_sky_radiance(queries, model, shadow, observer, view_vector(d)), {}});
    } else {
      samples = sample_radiance(queries, r.geometry, r.directions);
    }
  } else {
    core::ProgressBar bar("reference");
    const Vec3 observer = r.geometry.observer_m(model);
    for (std::size_t i = 0; i < r.directions.size(); ++i) {
      bar.update("direction " + std::to_string(i + 1) + "/" + std::to_string(r.directions.size()),
                 double(i) / double(r.directions.size()));
      const ViewDirection& d = r.directions[i];
      if (r.stokes) {
        const auto e = reference::path_traced_stokes(model, observer, view_vector(d), vertical_across(d), sun_disc(r),
                                                     tracer_options(r));
        samples.push_back({d, e.i, e.i_standard_error});
        polarization.push_back(polarization_row(e));
      } else {
        const auto e = reference::path_traced_radiance(model, observer, view_vector(d), sun_disc(r), tracer_options(r));
        samples.push_back({d, e.mean, e.standard_error});
      }
    }
  }
  atmosphere::ExtraColumns extra;  // the colour, then the polarization
  if (r.colour) {
    // The colour the sky has under the Kurucz sun (the CSV's spectral radiance columns).
    extra.names = {"x", "y", "CCT_K", "Duv", "T_eff_K"};
    for (const RadianceSample& s : samples) {
      std::vector<double> spectral;
      for (std::size_t i = 0; i < model.wavelengths_nm.size(); ++i)
        spectral.push_back(std::max(0.0, s.radiance[i]) * solar_irradiance_W_m2_nm(model.wavelengths_nm[i]));
      const image::Chromaticity c = image::spectrum_chromaticity(model.wavelengths_nm, spectral);
      const image::ColourTemperature t = image::correlated_colour_temperature(c);
      // And the effective blackbody temperature, as eclipse photometry gives the sky's colour.
      const double effective = image::effective_blackbody_temperature_K(model.wavelengths_nm, spectral,
                                                                        r.colour_band_nm[0], r.colour_band_nm[1]);
      extra.rows.push_back({c.x, c.y, t.kelvin, t.duv, effective});
    }
  }
  if (r.stokes) {
    const auto add_columns = [&](const std::string& prefix, const std::string& unit) {
      for (double w : model.wavelengths_nm) extra.names.push_back(prefix + std::to_string(int(std::lround(w))) + unit);
    };
    add_columns("Q_rel_", "nm_per_sr");
    add_columns("U_rel_", "nm_per_sr");
    add_columns("P_", "nm");
    add_columns("se_P_", "nm");
    add_columns("chi_", "nm_deg");
    extra.rows.resize(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k)
      extra.rows[k].insert(extra.rows[k].end(), polarization[k].begin(), polarization[k].end());
  }
  return radiance_csv(model, samples, extra);
}

std::string sample_transmittance_csv(const AtmosphereModel& model, const SamplingRequest& r) {
  std::ostringstream csv;
  csv.precision(9);
  csv << "zenith_deg,azimuth_deg,path_length_m,ends_on_ground" << spectrum_header(model, "T_") << '\n';
  const Vec3 observer = r.geometry.observer_m(model);
  std::optional<render::ObtainedTables> tables;
  if (r.method == SamplingMethod::Tables) tables = render::obtain_tables(model, r.tables);
  for (const ViewDirection& d : r.directions) {
    const reference::Ray ray(observer, view_vector(d));
    const auto interval = reference::atmosphere_interval(ray, model.ground_radius_m, model.top_radius_m);
    Spectrum t(model.wavelength_count(), 1.0);
    if (interval.intersects) {
      if (tables) {
        const lut::TableQueries q(model, tables->tables);
        const Vec3 start = observer + view_vector(d) * interval.begin_t_m;
        const double rr = length(start), mu = dot(start, view_vector(d)) / rr;
        double out[lut::kMaxChannels];
        q.transmittance(rr, mu, interval.end_t_m - interval.begin_t_m, interval.ends_on_ground, out);
        for (std::size_t c = 0; c < t.size(); ++c) t[c] = out[c];
      } else {
        t = reference::transmittance(model, observer + view_vector(d) * interval.begin_t_m,
                                     observer + view_vector(d) * interval.end_t_m);
      }
    }
    csv << d.zenith_deg << ',' << d.azimuth_deg << ','
        << (interval.intersects ? interval.end_t_m - interval.begin_t_m : 0.0) << ','
        << (interval.ends_on_ground ? 1 : 0);
    for (double v : t) csv << ',' << v;
    csv << '\n';
  }
  return csv.str();
}

std::string sample_irradiance_csv(const AtmosphereModel& model, const SamplingRequest& r) {
  std::ostringstream csv;
  csv.precision(9);
  csv << "altitude_m,sun_zenith_deg" << spectrum_header(model, "E_direct_") << spectrum_header(model, "E_sky_")
      << spectrum_header(model, "E_total_");
  if (r.method == SamplingMethod::Reference) csv << spectrum_header(model, "se_total_");
  csv << '\n';
  Spectrum direct(model.wavelength_count()), sky(model.wavelength_count()), total, se;
  if (r.method == SamplingMethod::Tables) {
    const render::ObtainedTables t = render::obtain_tables(model, r.tables);
    const lut::TableQueries q(model, t.tables);
    const double rr = model.ground_radius_m + r.geometry.altitude_m;
    const double mu_s = std::cos(r.geometry.sun_zenith_deg * kPi / 180.0);
    double with[lut::kMaxChannels], without[lut::kMaxChannels];
    q.irradiance(rr, mu_s, true, with);
    q.irradiance(rr, mu_s, false, without);
    for (std::size_t c = 0; c < direct.size(); ++c) {
      sky[c] = without[c];
      direct[c] = with[c] - without[c];
    }
    total = direct + sky;
  } else {
    const auto e = reference::ground_irradiance(model, r.geometry.observer_m(model), sun_disc(r), tracer_options(r));
    direct = e.direct_mean;
    sky = e.diffuse_mean;
    total = e.total_mean;
    se = e.total_standard_error;
  }
  csv << r.geometry.altitude_m << ',' << r.geometry.sun_zenith_deg;
  for (const Spectrum* s : {&direct, &sky, &total})
    for (double v : *s) csv << ',' << v;
  for (double v : se) csv << ',' << v;
  csv << '\n';
  return csv.str();
}

}  // namespace zenith::app
