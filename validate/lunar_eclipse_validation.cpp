#include "validate/lunar_eclipse_validation.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "astro/civil_time.h"
#include "astro/danjon_scale.h"
#include "astro/lunar_eclipse.h"
#include "astro/moon_photometry.h"
#include "astro/sky_positions.h"
#include "astro/v_band.h"
#include "atmosphere/parameters.h"
#include "atmosphere/photometry.h"
#include "atmosphere/solar_limb_darkening.h"
#include "core/strings.h"
#include "validate/gnuplot.h"

namespace zenith::validate {
namespace {

namespace fs = std::filesystem;
using astro::AstroTime;

/// The earth-advanced preset at 31 wavelengths, 380 to 780 nm: the V band and the umbra's colours.
atmosphere::LoadedAtmosphere spectral_earth() {
  atmosphere::LoadOptions options;
  options.wavelengths_nm = std::vector<double>{};
  for (int k = 0; k <= 30; ++k) options.wavelengths_nm->push_back(380.0 + 400.0 * k / 30.0);
  return atmosphere::load_preset("earth-advanced", options);
}

/// The Moon's face in the shadow at `time`: its V magnitude below the uneclipsed Moon's (the Kurucz
/// sun times the Moon's reflectance, astro/moon_photometry.h, over the face's mean illumination).
class MoonInShadow {
 public:
  MoonInShadow(const atmosphere::LoadedAtmosphere& air, const AstroTime& around)
      : air_(air), geometry_(astro::lunar_eclipse_geometry(around)), shadow_(make_shadow(air, geometry_)) {}

  double drop_v_mag(const AstroTime& time) const {
    const astro::LunarEclipseGeometry g = astro::lunar_eclipse_geometry(time);
    const std::vector<double>& nm = air_.model.wavelengths_nm;
    std::vector<double> lit, full;
    for (std::size_t i = 0; i < nm.size(); ++i) {
      const double light = atmosphere::solar_irradiance_W_m2_nm(nm[i]) * astro::lunar_geometric_albedo(nm[i]);
      full.push_back(light);
      lit.push_back(light * shadow_.disc_illumination(g.axis_distance_m, astro::kMoonRadius_km * 1e3, i));
    }
    return -2.5 * std::log10(astro::v_band_mean(nm, lit) / astro::v_band_mean(nm, full));
  }
  const astro::EarthShadow& shadow() const { return shadow_; }

 private:
  static astro::EarthShadow make_shadow(const atmosphere::LoadedAtmosphere& air, const astro::LunarEclipseGeometry& g) {
    return astro::EarthShadow(air, g.moon_distance_m, g.sun_angular_radius_rad,
                              atmosphere::solar_limb_darkening(air.model.wavelengths_nm));
  }
  const atmosphere::LoadedAtmosphere& air_;
  astro::LunarEclipseGeometry geometry_;
  astro::EarthShadow shadow_;
};

/// The instant the Moon's centre passes nearest the shadow's axis within ±1 h of `guess` (golden section).
AstroTime mid_eclipse(const AstroTime& guess) {
  const auto distance = [&](double s) { return astro::lunar_eclipse_geometry(guess.plus_seconds(s)).axis_distance_m; };
  double a = -3600.0, b = 3600.0;
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  while (b - a > 1.0) {
    const double c = b - phi * (b - a), d = a + phi * (b - a);
    if (distance(c) < distance(d))
      b = d;  // the least distance lies in [a, d]
    else
      a = c;
  }
  return guess.plus_seconds(0.5 * (a + b));
}

AstroTime utc(int y, int mo, int d, int h, int mi, double s) { return AstroTime::from_utc({y, mo, d, h, mi, s}); }

}  // namespace

std::vector<ValidationCheck> lunar_eclipse_checks(const fs::path& out_dir, bool plots) {
  const atmosphere::LoadedAtmosphere air = spectral_earth();
  std::vector<ValidationCheck> checks;
  fmt::print("\nlunar eclipses: the Moon's V magnitude below the uneclipsed Moon, earth-advanced at 31 wavelengths\n");

  // The drop at mid-totality, measured by photometry against the same Moon outside the shadow. Eclipses of
  // like depth differ by 1–2 mag with the stratosphere's aerosol and the clouds along the limb (Keen 1983,
  // Science 222, 1011); the model has neither clouds nor volcanic aerosol, and all three were in quiet
  // years: within 1 mag. Beside each, the observers' Danjon class and the one the model implies
  // (astro/danjon_scale.h): theirs moved by the model's error in brightness.
  const struct {
    AstroTime guess;
    double measured, error;
    const char* source;
    double danjon, danjon_error;
    const char* danjon_source;
  } drops[] = {
      {utc(2003, 5, 16, 3, 40, 0.0), 10.73, 0.07, "Georgia Journal of Science 62(2), art. 9 (photoelectric)", 1.5, 0.5,
       "most reports to Sky & Telescope: between 1 and 2; \"The Dark of an Eclipsed Moon\", 2003"},
      {utc(2004, 10, 28, 3, 4, 0.0), 10.61, 0.15, "Georgia Journal of Science 62(2), art. 9 (photoelectric)", 2.4, 0.5,
       "P. Harrington at mid-eclipse, Oakdale NY; philharrington.net/ec04.htm"},
      {utc(2022, 11, 8, 10, 59, 0.0), 10.78, 0.03,
       "E. Schmidt, -13.09 to -2.31 mvis at air mass 1 (forum.meteoros.de, t=61057)", 2.4, 0.2,
       "H. C. Vital, from the Moon's magnitude in images; geocities.ws/lunissolar2003/Nov08.htm"},
  };
  for (const auto& d : drops) {
    const AstroTime mid = mid_eclipse(d.guess);
    const MoonInShadow moon(air, mid);
    const double model = moon.drop_v_mag(mid);
    const double implied = astro::implied_danjon_class(d.danjon, d.measured, model);
    const astro::UtcTime t = mid.calendar_utc();
    fmt::print(
        "  {:04d}-{:02d}-{:02d} mid-totality {:02d}:{:02d} UTC, the Moon's centre {:.0f} km from the axis: "
        "{:.2f} mag (measured {:.2f} ± {:.2f})\n    Danjon L observed {:.1f} ± {:.1f} ({}); the model implies "
        "L {:.1f} (nearest class {}: {})\n",
        t.year, t.month, t.day, t.hour, t.minute, astro::lunar_eclipse_geometry(mid).axis_distance_m / 1e3, model,
        d.measured, d.error, d.danjon, d.danjon_error, d.danjon_source, implied, astro::nearest_danjon_class(implied),
        astro::danjon_description(implied));
    checks.push_back(
        {fmt::format("lunar {:04d}-{:02d}-{:02d}: the drop at mid-totality within 1 mag", t.year, t.month, t.day),
         d.source, std::abs(model - d.measured) <= 1.0,
         fmt::format("{:.2f} mag against {:.2f} ± {:.2f} ({:+.2f}); Danjon L {:.1f} implied, {:.1f} ± {:.1f} observed",
                     model, d.measured, d.error, model - d.measured, implied, d.danjon, d.danjon_error)});
  }

  // 2019-01-21 through totality (SSP-3, Johnson V): −3.18 at 04:43, −2.04 at 05:13:30, −2.70 at 05:31 UTC.
  // The changes to the minimum, within half a magnitude: the model's face has one albedo (the maria are
  // darker), and at 04:43 the limb is at the umbra's edge, where the light changes fastest.
  const AstroTime mid_2019 = mid_eclipse(utc(2019, 1, 21, 5, 12, 0.0));
  const MoonInShadow moon_2019(air, mid_2019);
  const AstroTime minimum = utc(2019, 1, 21, 5, 13, 30.0);
  const double at_minimum = moon_2019.drop_v_mag(minimum);
  for (const auto& [time, measured] :
       {std::pair{utc(2019, 1, 21, 4, 43, 0.0), -3.18 + 2.04}, std::pair{utc(2019, 1, 21, 5, 31, 0.0), -2.70 + 2.04}}) {
    const double model = moon_2019.drop_v_mag(time) - at_minimum;
    const astro::UtcTime t = time.calendar_utc();
    checks.push_back(
        {fmt::format("lunar 2019-01-21: {:02d}:{:02d} UTC against 05:13:30 within 0.5 mag", t.hour, t.minute),
         "Georgia Journal of Science 80(1), art. 32 (V photometry)", std::abs(model - measured) <= 0.5,
         fmt::format("{:+.2f} mag against {:+.2f}", model, measured)});
  }
  fs::create_directories(out_dir);
  {
    std::ofstream csv(out_dir / "lunar_eclipse_2019.csv");
    csv << "utc,minutes_from_mid,axis_distance_km,model_v_drop_mag,measured_v_minus_minimum_mag\n";
    for (double minutes = -120.0; minutes <= 120.0; minutes += 2.0) {
      const AstroTime t = mid_2019.plus_seconds(60.0 * minutes);
      csv << fmt::format("{},{:.1f},{:.1f},{:.4f},\n", astro::format_utc_time(t.calendar_utc()), minutes,
                         astro::lunar_eclipse_geometry(t).axis_distance_m / 1e3, moon_2019.drop_v_mag(t));
    }
    for (const auto& [time, v] : {std::pair{utc(2019, 1, 21, 4, 43, 0.0), -3.18}, std::pair{minimum, -2.04},
                                  std::pair{utc(2019, 1, 21, 5, 31, 0.0), -2.70}})
      csv << fmt::format("{},{:.2f},{:.1f},,{:.2f}\n", astro::format_utc_time(time.calendar_utc()),
                         (time.utc().value() - mid_2019.utc().value()) * 1440.0,
                         astro::lunar_eclipse_geometry(time).axis_distance_m / 1e3, v + 2.04);
    csv.close();  // gnuplot reads it next
    if (!csv) throw std::runtime_error(core::cat("cannot write ", (out_dir / "lunar_eclipse_2019.csv").string()));
  }
  if (plots) {
    std::ofstream gp(out_dir / "lunar_eclipse.gp");
    gp << "# zenith validate eclipse (docs/validation.md, \"Lunar eclipses\"); rerun: gnuplot lunar_eclipse.gp\n"
       << "set datafile separator ','\nset terminal pngcairo size 900,520 font ',10'\nset grid\n"
       << "set output 'lunar_eclipse_2019.png'\nset yrange [*:*] reverse\n"
       << "set title 'The Moon through the total lunar eclipse of 2019-01-21, V'\n"
       << "set xlabel 'minutes from mid-eclipse'\nset ylabel 'magnitudes below the uneclipsed Moon'\n"
       << fmt::format(
              "plot 'lunar_eclipse_2019.csv' skip 1 using 2:4 with lines lw 2 title 'zenith (earth-advanced)', "
              "'' skip 1 using 2:($5 + {:.4f}) with points pt 7 ps 1.5 title 'measured (SSP-3 V), at the "
              "model minimum'\n",
              at_minimum);
    gp.close();
    if (!run_gnuplot(out_dir / "lunar_eclipse.gp"))
      spdlog::warn("gnuplot not found or failed: lunar_eclipse.gp and its CSV are in {}", out_dir.string());
  }

  // The umbra's edge as the light draws it, against crater timings: 1.7–2.1 % beyond the solid planet's
  // (2004-10-28: 1.69 ± 0.04 %, 2008-02-21: 1.89 ± 0.06 %; Chauvenet's rule 1/50). The model's edge is where
  // ln E falls fastest, an observer's eye's proxy: within half a percent of that range.
  const astro::EarthShadow& shadow = moon_2019.shadow();
  const std::size_t green = 13;  // 553 nm
  const double enlargement = shadow.apparent_umbra_radius_m(green) / shadow.geometric_umbra_radius_m() - 1.0;
  checks.push_back({"lunar: the umbra's edge beyond the solid planet's by 1.7-2.1 % (+-0.5)",
                    "crater timings: 2004-10-28 1.69 %, 2008-02-21 1.89 %; Chauvenet 1/50 (Espenak, eclipsewise.com)",
                    enlargement >= 0.012 && enlargement <= 0.026, fmt::format("{:.2f} %", 100.0 * enlargement)});
  // Red at the centre (the blue scattered out of the grazing rays); bluer at the rim, where the light has
  // crossed the ozone layer, whose Chappuis band takes the orange (the turquoise fringe of photographs).
  const std::size_t blue = 5, orange = 17, red = 23;  // 447, 607, 687 nm
  const double centre_red = shadow.illumination(0.0, red) / shadow.illumination(0.0, blue);
  const double rim_y = 0.97 * shadow.geometric_umbra_radius_m();
  const double centre_blue_orange = shadow.illumination(0.0, blue) / shadow.illumination(0.0, orange);
  const double rim_blue_orange = shadow.illumination(rim_y, blue) / shadow.illumination(rim_y, orange);
  checks.push_back({"lunar: the umbra's centre red (687 nm over 447 nm > 10), its rim bluer than its centre",
                    "photographs of every total lunar eclipse; Vollmer & Gedzelman 2008, Appl. Opt. 47(34) H52",
                    centre_red > 10.0 && rim_blue_orange > centre_blue_orange,
                    fmt::format("centre 687/447 nm {:.3g}; 447/607 nm {:.3g} at the rim against {:.3g} at the centre",
                                centre_red, rim_blue_orange, centre_blue_orange)});
  return checks;
}

}  // namespace zenith::validate
