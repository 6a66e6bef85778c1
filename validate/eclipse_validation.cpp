#include "validate/eclipse_validation.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "astro/solar_eclipse.h"
#include "astro/v_band.h"
#include "atmosphere/parameters.h"
#include "atmosphere/photometry.h"
#include "atmosphere/reference/path_tracer.h"
#include "atmosphere/sky_sampling.h"
#include "core/strings.h"
#include "core/units.h"
#include "scene/sun_disc.h"
#include "validate/gnuplot.h"

namespace zenith::validate {
namespace {

namespace fs = std::filesystem;
using astro::AstroTime;
using astro::EclipseKind;

/// NASA's point of greatest eclipse, 2017-08-21 (Espenak, Five Millennium Canon of Solar Eclipses).
const astro::Site kSite{36.9667, -87.6667, 150.0};
constexpr double kObserverAltitude_m = 2.0;

/// One instant of the eclipse at the site: the discs and the zenith with and without the Moon.
struct Moment {
  std::string label;
  double seconds_from_c2 = 0.0;
  astro::SolarEclipseView view;
  std::vector<double> uncovered_light;                 ///< per wavelength: 1 − the limb-darkened covered share
  std::vector<double> eclipsed, daylight;              ///< zenith radiance per unit solar irradiance
  std::vector<double> eclipsed_error, daylight_error;  ///< their standard errors
  double ratio(std::size_t i) const { return eclipsed[i] / daylight[i]; }
  /// The relative standard error of ratio(i).
  double ratio_error(std::size_t i) const {
    return std::hypot(eclipsed_error[i] / eclipsed[i], daylight_error[i] / daylight[i]);
  }
};

struct EclipseCheck {
  std::string what, source;
  bool pass = false;
  std::string detail;
};

AstroTime at(const AstroTime& start, double seconds) { return start.plus_seconds(seconds); }

EclipseKind kind_at(const AstroTime& t) { return astro::solar_eclipse_view(astro::SkyPositions(t, kSite)).kind; }

/// The instant in [a, b] (seconds from `start`) where the eclipse's kind stops being what it is at a, to 0.05 s.
double contact(const AstroTime& start, double a, double b) {
  const EclipseKind before = kind_at(at(start, a));
  while (b - a > 0.05) {
    const double m = 0.5 * (a + b);
    (kind_at(at(start, m)) == before ? a : b) = m;
  }
  return 0.5 * (a + b);
}

/// The site's observer and the sun of instant `t` for the path tracer: the limb-darkened disc with the
/// Moon in front of it (sun.occulter; clear it for the same sky without the Moon).
struct EclipsedSky {
  atmosphere::Vec3 observer_m;
  atmosphere::reference::SunDisc sun;
};

EclipsedSky eclipsed_sky(const atmosphere::AtmosphereModel& model, const astro::SkyPositions& sky) {
  const astro::SunAndMoon s = astro::sun_and_moon(sky, model.ground_radius_m + kObserverAltitude_m);
  atmosphere::SkyGeometry g;
  g.altitude_m = kObserverAltitude_m;
  g.sun_zenith_deg = s.sun_zenith_deg;
  g.sun_azimuth_deg = s.sun_azimuth_deg;
  EclipsedSky e;
  e.observer_m = g.observer_m(model);
  e.sun.direction = g.sun_direction();
  e.sun.angular_radius_rad = s.sun_angular_radius_rad;
  for (double nm : model.wavelengths_nm) e.sun.limb_exponents.push_back(scene::limb_darkening_exponent(nm));
  e.sun.occulter = {s.moon_centre_m, s.moon_radius_m};
  return e;
}

atmosphere::reference::PathTracerOptions paths(std::size_t samples) {
  atmosphere::reference::PathTracerOptions o;
  o.samples_per_wavelength = samples;
  return o;
}

Moment moment(const atmosphere::AtmosphereModel& model, const AstroTime& start, double seconds_from_start,
              double c2_seconds, std::string label, std::size_t samples) {
  const astro::SkyPositions sky(at(start, seconds_from_start), kSite);
  Moment m;
  m.label = std::move(label);
  m.seconds_from_c2 = seconds_from_start - c2_seconds;
  m.view = astro::solar_eclipse_view(sky);
  EclipsedSky e = eclipsed_sky(model, sky);
  for (double a : e.sun.limb_exponents)
    m.uncovered_light.push_back(1.0 - astro::limb_darkened_obscuration(m.view.separation_rad, m.view.sun_radius_rad,
                                                                       m.view.moon_radius_rad, a));
  const atmosphere::Vec3 zenith{0.0, 0.0, 1.0};
  const auto dark = atmosphere::reference::path_traced_radiance(model, e.observer_m, zenith, e.sun, paths(samples));
  e.sun.occulter = {};
  const auto day = atmosphere::reference::path_traced_radiance(model, e.observer_m, zenith, e.sun, paths(samples));
  m.daylight.assign(day.mean.begin(), day.mean.end());
  m.eclipsed.assign(dark.mean.begin(), dark.mean.end());
  m.eclipsed_error.assign(dark.standard_error.begin(), dark.standard_error.end());
  m.daylight_error.assign(day.standard_error.begin(), day.standard_error.end());
  return m;
}

/// The sky 10° above the horizon at eight azimuths (every 45° from north), eclipsed, per unit solar
/// irradiance: at mid-totality the ring of sunlit air beyond the umbra.
std::vector<std::vector<double>> horizon_ring(const atmosphere::AtmosphereModel& model, const AstroTime& t,
                                              std::size_t samples) {
  const EclipsedSky e = eclipsed_sky(model, astro::SkyPositions(t, kSite));
  std::vector<std::vector<double>> ring;
  for (int k = 0; k < 8; ++k) {
    const auto l = atmosphere::reference::path_traced_radiance(
        model, e.observer_m, atmosphere::view_vector({80.0, 45.0 * k}), e.sun, paths(samples));
    ring.emplace_back(l.mean.begin(), l.mean.end());
  }
  return ring;
}

void write_outputs(const fs::path& dir, const atmosphere::AtmosphereModel& model, const std::vector<Moment>& moments,
                   bool plots) {
  fs::create_directories(dir);
  std::ofstream csv(dir / "eclipse_zenith.csv");
  csv << "moment,seconds_from_second_contact,kind,magnitude,obscuration";
  for (double nm : model.wavelengths_nm)
    csv << fmt::format(",uncovered_light_{0:.0f}nm,zenith_ratio_{0:.0f}nm,zenith_ratio_error_{0:.0f}nm", nm);
  csv << '\n';
  for (const Moment& m : moments) {
    csv << fmt::format("{},{:.1f},{},{:.5f},{:.5f}", m.label, m.seconds_from_c2, astro::to_string(m.view.kind),
                       m.view.magnitude, m.view.obscuration);
    for (std::size_t i = 0; i < model.wavelengths_nm.size(); ++i)
      csv << fmt::format(",{:.6g},{:.6g},{:.3g}", m.uncovered_light[i], m.ratio(i),
                         m.eclipsed_error[i] / m.daylight[i]);
    csv << '\n';
  }
  csv.close();  // gnuplot reads it next
  if (!csv) throw std::runtime_error(core::cat("cannot write ", (dir / "eclipse_zenith.csv").string()));
  if (!plots) return;
  std::ofstream gp(dir / "eclipse.gp");
  gp << "# zenith validate eclipse (docs/validation.md, \"Eclipses\"); rerun: cd " << dir.string()
     << " && gnuplot eclipse.gp\n"
     << "set datafile separator ','\nset terminal pngcairo size 1000,560 font ',10'\nset grid\nset key outside\n"
     << "set output 'eclipse_zenith.png'\nset logscale y\nset format y '10^{%L}'\n"
     << "set title 'The zenith through the total eclipse of 2017-08-21 at 36.97N 87.67W (reference solver)'\n"
     << "set xlabel 'seconds from second contact'\nset ylabel 'zenith / the same zenith without the Moon'\n"
     << "plot";
  const char* colours[] = {"'#c0392b'", "'#27ae60'", "'#2e86c1'"};
  for (std::size_t i = 0; i < model.wavelengths_nm.size(); ++i) {
    const std::size_t column = 6 + 3 * i;
    gp << (i ? ", \\\n    " : "")
       << fmt::format(
              " 'eclipse_zenith.csv' skip 1 using 2:{} with linespoints pt 7 lc rgb "
              "{} title '{:.0f} nm'",
              column + 1, colours[i % 3], model.wavelengths_nm[i])
       << fmt::format(", '' skip 1 using 2:{} with lines dt 2 lc rgb {} title 'uncovered light, {:.0f} nm'", column,
                      colours[i % 3], model.wavelengths_nm[i]);
  }
  gp << ", 1e-4 with lines dt 3 lw 2 lc rgb 'black' title 'Dandekar and Turtle 1971, totality'\n";
  gp.close();
  if (!run_gnuplot(dir / "eclipse.gp"))
    spdlog::warn("gnuplot not found or failed: eclipse.gp and eclipse_zenith.csv are in {}", dir.string());
}

}  // namespace

void validate_eclipse(const EclipseValidationOptions& o) {
  const atmosphere::AtmosphereModel model = atmosphere::load_preset("earth-advanced").model;
  // The contacts, from a scan every 20 s and bisection.
  const AstroTime start = AstroTime::from_utc(astro::UtcTime{2017, 8, 21, 16, 50, 0.0});
  std::vector<double> contacts;
  EclipseKind kind = kind_at(start);
  for (double s = 20.0; s <= 3.2 * 3600.0 && contacts.size() < 4; s += 20.0) {
    const EclipseKind k = kind_at(at(start, s));
    if (k != kind) contacts.push_back(contact(start, s - 20.0, s));
    kind = k;
  }
  if (contacts.size() != 4)
    throw std::runtime_error(core::cat("validate eclipse: found ", contacts.size(), " contacts, expected 4"));
  const double c1 = contacts[0], c2 = contacts[1], c3 = contacts[2], c4 = contacts[3];
  fmt::print("zenith validate eclipse: 2017-08-21 at {:.4f}, {:.4f} (NASA's greatest eclipse), earth-advanced\n",
             kSite.latitude_deg, kSite.longitude_deg);
  for (auto [name, s] : {std::pair{"C1", c1}, {"C2", c2}, {"C3", c3}, {"C4", c4}})
    fmt::print("  {} {}\n", name, astro::format_utc_time(at(start, s).calendar_utc()));
  fmt::print("  totality {:.1f} s (NASA: 160 s)\n\n", c3 - c2);

  const std::size_t outside = std::max<std::size_t>(1000, o.samples / 10);
  const struct {
    const char* label;
    double seconds;
    std::size_t samples;
  } plan[] = {
      {"C1 + 25 %", c1 + 0.25 * (c2 - c1), outside},
      {"C1 + 50 %", c1 + 0.5 * (c2 - c1), outside},
      {"C1 + 75 %", c1 + 0.75 * (c2 - c1), outside},
      {"C1 + 95 %", c1 + 0.95 * (c2 - c1), outside},
      {"C2 - 30 s", c2 - 30.0, outside},
      {"C2 - 5 s", c2 - 5.0, outside},
      {"C2 + 5 s", c2 + 5.0, o.samples},
      {"mid-totality", 0.5 * (c2 + c3), o.samples},
      {"C3 - 5 s", c3 - 5.0, o.samples},
      {"C3 + 5 s", c3 + 5.0, outside},
      {"C3 + 30 s", c3 + 30.0, outside},
      {"C3 + 25 %", c3 + 0.25 * (c4 - c3), outside},
      {"C3 + 75 %", c3 + 0.75 * (c4 - c3), outside},
  };
  std::vector<Moment> moments;
  for (const auto& p : plan) {
    spdlog::info("reference solver: {} ({} paths per wavelength)", p.label, p.samples);
    moments.push_back(moment(model, start, p.seconds, c2, p.label, p.samples));
  }

  const std::size_t red = 0, green = 1, blue = 2;  // the preset's 680, 550, 440 nm
  fmt::print("{:>13} {:>9} {:>8} {:>12}   zenith / daylight (uncovered light) at 680, 550, 440 nm\n", "moment",
             "s from C2", "kind", "obscuration");
  for (const Moment& m : moments) {
    fmt::print("{:>13} {:>9.1f} {:>8} {:>12.4f}  ", m.label, m.seconds_from_c2, astro::to_string(m.view.kind),
               m.view.obscuration);
    for (std::size_t i = 0; i < 3; ++i) fmt::print(" {:>9.3g} ({:.3g})", m.ratio(i), m.uncovered_light[i]);
    fmt::print("\n");
  }

  std::vector<EclipseCheck> checks;
  const Moment& mid = moments[7];
  spdlog::info("reference solver: the horizon ring at mid-totality");
  const auto ring = horizon_ring(model, at(start, 0.5 * (c2 + c3)), std::max<std::size_t>(1000, o.samples / 4));
  const double zenith_colour = mid.eclipsed[red] / mid.eclipsed[blue];
  double dimmest_over_zenith = 1e300, least_red = 1e300;
  for (const std::vector<double>& l : ring) {
    dimmest_over_zenith = std::min(dimmest_over_zenith, l[green] / mid.eclipsed[green]);
    least_red = std::min(least_red, (l[red] / l[blue]) / zenith_colour);
  }
  checks.push_back({"mid-totality zenith / daylight at 550 nm within a factor 3 of 1e-4",
                    "Dandekar & Turtle 1971, Appl. Opt. 10(6)", mid.ratio(green) > 1e-4 / 3 && mid.ratio(green) < 3e-4,
                    fmt::format("{:.3g}", mid.ratio(green))});
  checks.push_back({"mid-totality zenith bluer than the daylit zenith (440 nm keeps more than 680 nm)",
                    "SQM and spectra at totality, 2017-08-21: ~11 000 K against ~9 000 K",
                    mid.ratio(blue) > mid.ratio(red),
                    fmt::format("{:.3g} against {:.3g}", mid.ratio(blue), mid.ratio(red))});
  // The zenith's V surface brightness at mid-totality: the tables' unit (radiance per unit solar irradiance)
  // times the Kurucz sun (atmosphere/photometry.h), V-band mean (astro/v_band.h).
  std::vector<double> zenith_W_m2_sr_nm;
  for (std::size_t i = 0; i < model.wavelengths_nm.size(); ++i)
    zenith_W_m2_sr_nm.push_back(mid.eclipsed[i] * atmosphere::solar_irradiance_W_m2_nm(model.wavelengths_nm[i]));
  const double zenith_v = astro::v_surface_brightness(astro::v_band_mean(model.wavelengths_nm, zenith_W_m2_sr_nm));
  checks.push_back({"mid-totality zenith, V mag/arcsec², within 1 mag of the SQM readings 12.4–13.3",
                    "SQM readings in totality, 2017-08-21, sun ~46° up (SQM's band is not V: up to ~0.3 mag)",
                    zenith_v > 12.4 - 1.0 && zenith_v < 13.3 + 1.0, fmt::format("{:.2f}", zenith_v)});
  checks.push_back({"mid-totality: the horizon (10° up) brighter than the zenith and redder, at every azimuth",
                    "the 360° sunset of totality (photographs and spectra of every total eclipse)",
                    dimmest_over_zenith > 1.0 && least_red > 1.0,
                    fmt::format("dimmest of 8 azimuths {:.1f}x the zenith at 550 nm; 680/440 nm at least {:.1f}x the "
                                "zenith's",
                                dimmest_over_zenith, least_red)});
  // The air above the site sees nearly the site's disc until the umbra comes close: within 5 % (the sky at
  // 69 % obscuration is 3 % off, redder light a little darker, bluer a little brighter) plus three standard
  // errors of the two estimates.
  double worst = 0.0, worst_allowed = 0.0;
  bool follows = true;
  for (const Moment& m : moments)
    if (m.view.kind == EclipseKind::partial && m.view.obscuration <= 0.9)
      for (std::size_t i = 0; i < 3; ++i) {
        const double difference = std::abs(m.ratio(i) / m.uncovered_light[i] - 1.0);
        const double allowed = 0.05 + 3.0 * m.ratio_error(i);
        follows = follows && difference <= allowed;
        if (difference > worst) worst = difference, worst_allowed = allowed;
      }
  checks.push_back(
      {"partial phases up to 90 % obscuration: the zenith follows the uncovered limb-darkened light",
       "the air above the site sees the site's disc", follows,
       fmt::format("largest difference {:.2f} % (allowed {:.2f} %)", 100.0 * worst, 100.0 * worst_allowed)});
  // Through the ingress (C1 + 25 % … C2 + 5 s) and the egress (C3 − 5 s … C3 + 75 %); inside totality the sky is
  // nearly flat and its differences are the path tracer's noise.
  // A step against the trend counts only beyond three standard errors of the difference.
  const auto rises = [&](const Moment& from, const Moment& to) {
    const double noise =
        std::hypot(from.ratio(green) * from.ratio_error(green), to.ratio(green) * to.ratio_error(green));
    return to.ratio(green) - from.ratio(green) > 3.0 * noise;
  };
  bool monotone = true;
  for (std::size_t k = 1; k <= 6; ++k) monotone = monotone && !rises(moments[k - 1], moments[k]);
  for (std::size_t k = 9; k < moments.size(); ++k) monotone = monotone && !rises(moments[k], moments[k - 1]);
  checks.push_back({"550 nm darkens from C1 into totality and brightens from it to C4, no jump at C2 or C3",
                    "continuity", monotone, monotone ? "monotone" : "not monotone"});

  fmt::print("\n");
  std::size_t failures = 0;
  for (const EclipseCheck& c : checks) {
    fmt::print("  {:<96} {}  {}  [{}]\n", c.what, c.pass ? "ok  " : "FAIL", c.detail, c.source);
    failures += c.pass ? 0 : 1;
  }
  fmt::print("{} checks, {} outside their tolerance\n", checks.size(), failures);
  write_outputs(o.out_dir, model, moments, !o.no_plots);
  spdlog::info("wrote {}/eclipse_zenith.csv{}", o.out_dir, o.no_plots ? "" : " and eclipse_zenith.png");
  if (failures > 0)
    throw std::runtime_error(core::cat("validate eclipse: ", failures, " checks outside their tolerance"));
}

}  // namespace zenith::validate
