#include "astro/lunar_eclipse.h"

#include <erfa.h>
#include <erfam.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "astro/refraction.h"
#include "astro/sky_positions.h"
#include "atmosphere/reference/geometry.h"
#include "atmosphere/reference/optical_depth.h"
#include "core/strings.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

using core::kPi;

/// The point-source pattern's radial bins, filled ring by ring.
class RadialBins {
 public:
  RadialBins(std::size_t count, double width_m) : irradiance_(count, 0.0), width_m_(width_m) {}

  /// A ring of light of power `power` (per unit irradiance: m²) spread evenly over the annulus [y1, y2].
  void deposit(double power, double y1, double y2) {
    if (y2 < y1) std::swap(y1, y2);
    const double w = width_m_;
    if (y2 - y1 < 1e-3 * w) {
      // A caustic's fold: the ring lands on one radius; the bin holds its light.
      const std::size_t k = std::min(std::size_t(y1 / w), irradiance_.size() - 1);
      irradiance_[k] += power / (kPi * w * w * double(2 * k + 1));
      return;
    }
    const double per_area = power / (kPi * (y2 * y2 - y1 * y1));
    const std::size_t first = std::size_t(y1 / w), last = std::min(std::size_t(y2 / w), irradiance_.size() - 1);
    for (std::size_t k = first; k <= last && k < irradiance_.size(); ++k) {
      const double a = std::max(y1, double(k) * w), b = std::min(y2, double(k + 1) * w);
      if (b > a) irradiance_[k] += per_area * (b * b - a * a) / (w * w * double(2 * k + 1));
    }
  }
  /// E at radius y, linear between bin centres; 1 beyond the bins (no air, no planet: the Sun itself).
  double at(double y) const {
    const double f = y / width_m_ - 0.5;
    if (f <= 0.0) return irradiance_.front();
    const std::size_t k = std::size_t(f);
    if (k + 1 >= irradiance_.size()) return 1.0;
    const double t = f - double(k);
    return (1.0 - t) * irradiance_[k] + t * irradiance_[k + 1];
  }
  std::vector<double>& values() { return irradiance_; }

 private:
  std::vector<double> irradiance_;
  double width_m_;
};

}  // namespace

EarthShadow::EarthShadow(const atmosphere::LoadedAtmosphere& loaded, double distance_m, double sun_angular_radius_rad,
                         const std::vector<atmosphere::LimbDarkening>& limb_darkening,
                         const EarthShadowOptions& options)
    : distance_m_(distance_m),
      sun_radius_rad_(sun_angular_radius_rad),
      ground_radius_m_(loaded.model.ground_radius_m),
      top_radius_m_(loaded.model.top_radius_m),
      bin_m_(options.bin_m),
      wavelengths_(loaded.model.wavelengths_nm.size()) {
  const atmosphere::AtmosphereModel& model = loaded.model;
  if (!(distance_m > 10.0 * top_radius_m_))
    throw std::invalid_argument(core::cat("lunar eclipse: the distance ", distance_m,
                                          " m must be over ten times the top of the air, ", top_radius_m_, " m"));
  if (!(sun_angular_radius_rad > 0.0 && sun_angular_radius_rad < 0.1))
    throw std::invalid_argument(
        core::cat("lunar eclipse: the Sun's angular radius ", sun_angular_radius_rad, " rad must be in (0, 0.1)"));
  if (limb_darkening.size() != wavelengths_)
    throw std::invalid_argument(
        core::cat("lunar eclipse: ", limb_darkening.size(), " limb darkening laws for ", wavelengths_, " wavelengths"));
  for (const atmosphere::LimbDarkening& law : limb_darkening) atmosphere::check_limb_darkening(law, "lunar eclipse");
  if (options.heights < 16 || !(options.bin_m > 0.0) || options.sun_rings < 1 || options.sun_sectors < 4)
    throw std::invalid_argument("lunar eclipse: options out of range");

  // Impact parameters b = R + h, crowded toward the ground where δ and T change fastest.
  const double air_m = top_radius_m_ - ground_radius_m_;
  const std::size_t n = options.heights;
  for (std::size_t j = 0; j <= n; ++j) heights_m_.push_back(air_m * double(j * j) / double(n * n));

  // δ at 550 nm by the refraction integral, scaled by each wavelength's refractivity (δ ∝ n₀ − 1).
  const double n_550 = ground_refractivity(loaded, 550.0);
  std::vector<double> deflection_550;
  for (double h : heights_m_)
    deflection_550.push_back(h >= air_m - 1.0 ? 0.0
                                              : 2.0 * Refraction::horizon_rad(ground_radius_m_, top_radius_m_,
                                                                              model.rayleigh_density, n_550, h));
  // The refracted path's stretch f = (1 − k)^(−1/2), k = r |dn/dr| / n.
  std::vector<double> stretch;
  for (double h : heights_m_) {
    const double step = 10.0, r = ground_radius_m_ + h;
    const double dn_dr = n_550 * (model.rayleigh_density(std::max(0.0, h - step)) - model.rayleigh_density(h + step)) /
                         (h + step - std::max(0.0, h - step));
    const double k = r * dn_dr / (1.0 + n_550 * model.rayleigh_density(h));
    stretch.push_back(1.0 / std::sqrt(std::max(0.05, 1.0 - k)));
  }
  deflection_.assign(wavelengths_, {});
  transmittance_.assign(wavelengths_, {});
  for (std::size_t j = 0; j <= n; ++j) {
    // Half the grazing path, from its lowest point out to the top, by the reference solver's quadrature.
    const double r = std::min(ground_radius_m_ + heights_m_[j], top_radius_m_);
    const double half_m = std::sqrt(std::max(0.0, (top_radius_m_ - r) * (top_radius_m_ + r)));
    const atmosphere::Spectrum tau = atmosphere::reference::optical_depth_along_ray(
        model, atmosphere::reference::Ray({0.0, 0.0, r}, {1.0, 0.0, 0.0}), 0.0, half_m);
    for (std::size_t i = 0; i < wavelengths_; ++i) transmittance_[i].push_back(std::exp(-2.0 * stretch[j] * tau[i]));
  }
  for (std::size_t i = 0; i < wavelengths_; ++i) {
    const double ratio = ground_refractivity(loaded, model.wavelengths_nm[i]) / n_550;
    for (double d : deflection_550) deflection_[i].push_back(d * ratio);
  }

  // The Sun's disc: rings × sectors, limb-darkened weights summing to 1.
  struct SunPoint {
    double x_m, y_m, weight;
  };
  const double sun_image_m = distance_m_ * std::tan(sun_radius_rad_);
  const std::size_t bins = std::size_t((top_radius_m_ + 1.2 * sun_image_m) / bin_m_) + 2;
  illumination_.assign(wavelengths_, std::vector<double>(bins, 1.0));
  for (std::size_t i = 0; i < wavelengths_; ++i) {
    // The Sun a point: the rings of the air and the straight rays above it.
    RadialBins point(bins + std::size_t(sun_image_m / bin_m_) + 4, bin_m_);
    point.deposit(kPi * (std::pow(double(point.values().size()) * bin_m_, 2) - top_radius_m_ * top_radius_m_),
                  top_radius_m_, double(point.values().size()) * bin_m_);
    for (std::size_t j = 0; j < n; ++j) {
      const double b_a = ground_radius_m_ + heights_m_[j], b_b = ground_radius_m_ + heights_m_[j + 1];
      const double y_a = b_a - distance_m_ * deflection_[i][j], y_b = b_b - distance_m_ * deflection_[i][j + 1];
      const double t = 0.5 * (transmittance_[i][j] + transmittance_[i][j + 1]);
      if ((y_a >= 0.0) == (y_b >= 0.0)) {
        point.deposit(t * kPi * (b_b * b_b - b_a * b_a), std::abs(y_a), std::abs(y_b));
      } else {
        // The ring crosses the axis: its two parts land on either side.
        const double b_0 = b_a + (b_b - b_a) * y_a / (y_a - y_b);
        point.deposit(t * kPi * (b_0 * b_0 - b_a * b_a), 0.0, std::abs(y_a));
        point.deposit(t * kPi * (b_b * b_b - b_0 * b_0), 0.0, std::abs(y_b));
      }
    }
    std::vector<SunPoint> sun;
    double total = 0.0;
    for (std::size_t ring = 0; ring < options.sun_rings; ++ring) {
      const double rho = (double(ring) + 0.5) / double(options.sun_rings);
      const double mu = std::sqrt(std::max(0.0, 1.0 - rho * rho));
      const double weight = limb_darkening[i].intensity(mu) * rho;  // ring area ∝ ρ
      for (std::size_t s = 0; s < options.sun_sectors; ++s) {
        const double phi = 2.0 * kPi * (double(s) + 0.5) / double(options.sun_sectors);
        sun.push_back({sun_image_m * rho * std::cos(phi), sun_image_m * rho * std::sin(phi), weight});
        total += weight;
      }
    }
    for (std::size_t k = 0; k < bins; ++k) {
      const double y = (double(k) + 0.5) * bin_m_;
      double e = 0.0;
      for (const SunPoint& p : sun) e += p.weight * point.at(std::hypot(y - p.x_m, p.y_m));
      illumination_[i][k] = e / total;
    }
  }
}

double EarthShadow::illumination(double axis_distance_m, std::size_t i) const {
  const std::vector<double>& e = illumination_.at(i);
  const double f = std::abs(axis_distance_m) / bin_m_ - 0.5;
  if (f <= 0.0) return e.front();
  const std::size_t k = std::size_t(f);
  if (k + 1 >= e.size()) return 1.0;
  const double t = f - double(k);
  return (1.0 - t) * e[k] + t * e[k + 1];
}

double EarthShadow::disc_illumination(double axis_distance_m, double radius_m, std::size_t i) const {
  // Equal-area rings × sectors over the disc.
  constexpr int kRings = 24, kSectors = 48;
  double sum = 0.0;
  for (int ring = 0; ring < kRings; ++ring) {
    const double r = radius_m * std::sqrt((ring + 0.5) / kRings);
    for (int s = 0; s < kSectors; ++s) {
      const double phi = 2.0 * kPi * (s + 0.5) / kSectors;
      sum += illumination(std::hypot(axis_distance_m + r * std::cos(phi), r * std::sin(phi)), i);
    }
  }
  return sum / (kRings * kSectors);
}

double EarthShadow::geometric_umbra_radius_m() const {
  return ground_radius_m_ - distance_m_ * std::tan(sun_radius_rad_);
}

double EarthShadow::apparent_umbra_radius_m(std::size_t i) const {
  // The steepest fall of ln E between the geometric umbra's radius − 10 % and the penumbra's edge.
  const double from = 0.9 * geometric_umbra_radius_m(), to = ground_radius_m_ + distance_m_ * std::tan(sun_radius_rad_);
  double best = from, steepest = 0.0;
  for (double y = from; y < to; y += bin_m_) {
    const double slope =
        std::log(std::max(illumination(y + bin_m_, i), 1e-300)) - std::log(std::max(illumination(y, i), 1e-300));
    if (slope > steepest) {
      steepest = slope;
      best = y + 0.5 * bin_m_;
    }
  }
  return best;
}

double EarthShadow::over_heights(const std::vector<double>& values, double height_m, double above_the_air) const {
  const auto it = std::upper_bound(heights_m_.begin(), heights_m_.end(), height_m);
  if (it == heights_m_.begin()) return values.front();
  if (it == heights_m_.end()) return above_the_air;
  const std::size_t j = std::size_t(it - heights_m_.begin()) - 1;
  const double t = (height_m - heights_m_[j]) / (heights_m_[j + 1] - heights_m_[j]);
  return (1.0 - t) * values[j] + t * values[j + 1];
}

double EarthShadow::deflection_rad(double height_m, std::size_t i) const {
  return over_heights(deflection_.at(i), height_m, 0.0);
}

double EarthShadow::grazing_transmittance(double height_m, std::size_t i) const {
  return over_heights(transmittance_.at(i), height_m, 1.0);
}

LunarEclipseGeometry lunar_eclipse_geometry(const AstroTime& time) {
  const JulianDate& tt = time.tt();  // TDB − TT < 2 ms
  double pvh[2][3], pvb[2][3], moon[2][3];
  eraEpv00(tt.day1, tt.day2, pvh, pvb);
  eraMoon98(tt.day1, tt.day2, moon);
  const double au_m = kAstronomicalUnit_km * 1e3;
  double sun[3], axis[3];
  for (int k = 0; k < 3; ++k) sun[k] = -pvh[0][k];
  const double sun_distance = eraPm(sun);
  // The shadow lies along the light's path in the Earth's frame: the Sun's direction moved by the Earth's
  // velocity over c (annual aberration, 20.5″: the shadow's axis trails the geometric antisolar point, and
  // the Moon reaches it ~35 s later).
  const double c_au_per_day = 86400.0 / ERFA_AULT;
  double apparent[3];
  for (int k = 0; k < 3; ++k) apparent[k] = sun[k] / sun_distance + pvh[1][k] / c_au_per_day;
  const double apparent_norm = eraPm(apparent);
  for (int k = 0; k < 3; ++k) axis[k] = -apparent[k] / apparent_norm;  // the shadow's axis, away from the Sun
  LunarEclipseGeometry g;
  const double along = eraPdp(moon[0], axis);
  double across[3];
  for (int k = 0; k < 3; ++k) across[k] = moon[0][k] - along * axis[k];
  g.moon_distance_m = along * au_m;
  g.axis_distance_m = eraPm(across) * au_m;
  g.sun_angular_radius_rad = std::asin(kSunRadius_km / (sun_distance * kAstronomicalUnit_km));
  return g;
}

EarthShadowRadii earth_shadow_radii(const AstroTime& time) {
  constexpr double kEarthRadius_m = 6378.137e3, kDanjon = 1.0 + 1.0 / 85.0;
  const LunarEclipseGeometry g = lunar_eclipse_geometry(time);
  const double sun_distance_m = kSunRadius_km * 1e3 / std::sin(g.sun_angular_radius_rad);
  const double parallax = std::asin(kEarthRadius_m / sun_distance_m);
  return {kEarthRadius_m * kDanjon - g.moon_distance_m * (g.sun_angular_radius_rad - parallax),
          kEarthRadius_m * kDanjon + g.moon_distance_m * (g.sun_angular_radius_rad + parallax)};
}

const char* to_string(LunarEclipseKind kind) {
  switch (kind) {
    case LunarEclipseKind::penumbral: return "penumbral";
    case LunarEclipseKind::partial: return "partial";
    case LunarEclipseKind::total: return "total";
  }
  return "?";
}

namespace {

/// How far inside the shadow the Moon's disc reaches at `seconds` after `base`, in units of its diameter,
/// against the umbra (umbra = true) or the penumbra: the eclipse's magnitude then.
double magnitude_at(const AstroTime& base, double seconds, bool umbra) {
  const AstroTime t = base.plus_seconds(seconds);
  const LunarEclipseGeometry g = lunar_eclipse_geometry(t);
  const EarthShadowRadii r = earth_shadow_radii(t);
  const double moon = kMoonRadius_km * 1e3;
  return ((umbra ? r.umbra_m : r.penumbra_m) - (g.axis_distance_m - moon)) / (2.0 * moon);
}

/// The time in [a, b] (seconds after `base`) where f crosses `level`, f(a) and f(b) on either side.
template <class F>
double crossing(F f, double a, double b, double level) {
  const bool rising = f(a) < level;
  while (b - a > 0.5) {
    const double m = 0.5 * (a + b);
    ((f(m) < level) == rising ? a : b) = m;
  }
  return 0.5 * (a + b);
}

double moon_altitude_deg(const Site& site, const AstroTime& t) {
  return SkyPositions(t, site).moon().horizontal.altitude_rad / core::kDeg;
}

}  // namespace

std::optional<LocalLunarEclipse> next_lunar_eclipse(const Site& site, const AstroTime& from, double years) {
  if (!(years > 0.0 && years <= 30.0))
    throw std::invalid_argument(core::cat("lunar eclipse search: ", years, " years must be in (0, 30]"));
  const double day = 86400.0, span = years * 365.25 * day;
  // The Moon's angle from the antisolar point seen from the Earth's centre: least at full moon, π at new moon.
  const auto from_antisolar = [&](double s) {
    const LunarEclipseGeometry g = lunar_eclipse_geometry(from.plus_seconds(s));
    return std::atan2(g.axis_distance_m, g.moon_distance_m);
  };
  // Full moons: local minima of the daily samples (the Moon gains ~12° a day on the antisolar point).
  // Start two days early so an eclipse in progress at `from` is found.
  double before = from_antisolar(-3.0 * day), now = from_antisolar(-2.0 * day);
  for (double s = -2.0 * day; s < span; s += day) {
    const double next = from_antisolar(s + day);
    const bool minimum = now <= before && now <= next;
    before = now;
    now = next;
    if (!minimum) continue;
    // The least distance on a 20-minute grid over the two days around it, then golden section to a second.
    double best = s - day, least = from_antisolar(best);
    for (double t = s - day; t <= s + day; t += 1200.0)
      if (const double d = from_antisolar(t); d < least) least = d, best = t;
    double a = best - 1200.0, b = best + 1200.0;
    const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
    while (b - a > 1.0) {
      const double c = b - phi * (b - a), d = a + phi * (b - a);
      if (from_antisolar(c) < from_antisolar(d))
        b = d;
      else
        a = c;
    }
    const double max_s = 0.5 * (a + b);
    if (magnitude_at(from, max_s, false) <= 0.0) continue;  // the Moon misses the penumbra
    LocalLunarEclipse e;
    e.maximum = from.plus_seconds(max_s);
    e.umbral_magnitude = magnitude_at(from, max_s, true);
    e.penumbral_magnitude = magnitude_at(from, max_s, false);
    e.kind = e.umbral_magnitude >= 1.0  ? LunarEclipseKind::total
             : e.umbral_magnitude > 0.0 ? LunarEclipseKind::partial
                                        : LunarEclipseKind::penumbral;
    // Contacts: the magnitude against the penumbra crosses 0 (P1, P4), against the umbra 0 (U1, U4) and 1 (U2, U3).
    const double reach = 4.0 * 3600.0;
    const auto penumbral = [&](double t) { return magnitude_at(from, t, false); };
    const auto umbral = [&](double t) { return magnitude_at(from, t, true); };
    const double p1 = crossing(penumbral, max_s - reach, max_s, 0.0),
                 p4 = crossing(penumbral, max_s, max_s + reach, 0.0);
    e.penumbra_begins = from.plus_seconds(p1);
    e.penumbra_ends = from.plus_seconds(p4);
    if (e.kind != LunarEclipseKind::penumbral) {
      e.umbra_begins = from.plus_seconds(crossing(umbral, p1, max_s, 0.0));
      e.umbra_ends = from.plus_seconds(crossing(umbral, max_s, p4, 0.0));
    }
    if (e.kind == LunarEclipseKind::total) {
      e.totality_begins = from.plus_seconds(crossing(umbral, p1, max_s, 1.0));
      e.totality_ends = from.plus_seconds(crossing(umbral, max_s, p4, 1.0));
    }
    if (p4 < 0.0) continue;  // over before `from`
    e.moon_altitude_deg = moon_altitude_deg(site, e.maximum);
    bool seen = e.moon_altitude_deg > 0.0;
    for (double t = p1; t <= p4 && !seen; t += 300.0) seen = moon_altitude_deg(site, from.plus_seconds(t)) > 0.0;
    if (seen) return e;
  }
  return std::nullopt;
}

}  // namespace zenith::astro
