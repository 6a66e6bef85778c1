#pragma once
// A lunar eclipse: the Sun's light inside a planet's shadow at the Moon's
// distance, refracted and extinguished through the planet's air
// (docs/validation.md, "Lunar eclipses").
//
// A ray of the Sun passing the planet's centre at impact parameter b = R + h
// (h the height of its lowest point, R the ground's radius) is bent toward
// the centre by twice the refraction at the horizon seen from height h,
//   δ(h) = 2 R_h(0)        (astro/refraction.h: the model's own air, Bouguer's invariant),
// and dimmed by the transmittance of the whole grazing path, twice the path
// from its lowest point to the top,
//   T(h) = exp(−2 f(h) τ(h)),   f = (1 − k)^(−1/2),   k = r |dn/dr| / n
// (τ the model's own extinction — Rayleigh, aerosols, ozone — from the
// lowest point horizontally out to the top, by the reference solver's
// quadrature, atmosphere/reference/optical_depth.h; f the refracted
// ray's longer path through the air — Chapman's grazing optical depth grows
// as √r, and a ray bent with curvature k/r keeps the height of a straight
// ray over a planet of radius r / (1 − k)). At the distance D behind the
// planet the ray lands at y = b − D δ(h) from the shadow's axis (y < 0: it
// crossed the axis). With the Sun a point, the ring [b, b + db] sends its
// light T · 2π b db onto the annulus between |y(b)| and |y(b + db)|; rays
// above the top of the air land at y = b unchanged, rays below the ground
// are stopped. The Sun's limb-darkened disc (atmosphere/solar_limb_darkening.h) then
// spreads this pattern: E(Y) = Σ_k w_k E_point(|Y − D σ_k|) over points σ_k
// of the disc. E is per unit of the Sun's irradiance: 1 outside the shadow,
// the penumbra's fall, and the umbra's red light.
#include <cstddef>
#include <optional>
#include <vector>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "atmosphere/parameters.h"
#include "atmosphere/solar_limb_darkening.h"

namespace zenith::astro {

struct EarthShadowOptions {
  std::size_t heights = 600;   ///< impact parameters across the air, crowded toward the ground
  double bin_m = 2e3;          ///< radial bins of the point-source pattern
  std::size_t sun_rings = 16;  ///< the Sun's disc: rings × sectors
  std::size_t sun_sectors = 32;
};

class EarthShadow {
 public:
  /// The shadow of `loaded`'s planet at `distance_m` behind its centre, lit by
  /// a Sun of angular radius `sun_angular_radius_rad` with a limb darkening
  /// law per wavelength (all uniform: a uniform disc). Throws
  /// std::invalid_argument for a distance under ten times the top of the air, a
  /// Sun radius outside (0, 0.1) rad or limb darkening not one valid law per wavelength.
  EarthShadow(const atmosphere::LoadedAtmosphere& loaded, double distance_m, double sun_angular_radius_rad,
              const std::vector<atmosphere::LimbDarkening>& limb_darkening, const EarthShadowOptions& options = {});

  /// E / E_sun at `axis_distance_m` from the shadow's axis, wavelength i.
  double illumination(double axis_distance_m, std::size_t wavelength) const;
  /// The mean of E / E_sun over a disc of radius `radius_m` whose centre lies
  /// `axis_distance_m` from the axis (the Moon's face, of uniform albedo).
  double disc_illumination(double axis_distance_m, double radius_m, std::size_t wavelength) const;

  /// The umbra of the solid planet alone, straight rays: R − D (r_s − R / D_sun), D_sun → ∞.
  double geometric_umbra_radius_m() const;
  /// The umbra's edge as the light shows it: where ln E falls fastest between
  /// the geometric umbra and penumbra's edges (what observers time crater
  /// contacts by), at wavelength i.
  double apparent_umbra_radius_m(std::size_t wavelength) const;
  /// δ(h) [rad] and T(h) of the grazing ray whose lowest point is `height_m` up.
  double deflection_rad(double height_m, std::size_t wavelength) const;
  double grazing_transmittance(double height_m, std::size_t wavelength) const;
  std::size_t wavelengths() const { return wavelengths_; }

 private:
  /// A per-height table at `height_m`, linear between the heights; `above_the_air` past the top.
  double over_heights(const std::vector<double>& values, double height_m, double above_the_air) const;

  double distance_m_, sun_radius_rad_, ground_radius_m_, top_radius_m_, bin_m_;
  std::size_t wavelengths_;
  std::vector<double> heights_m_;                   // the impact parameters' heights
  std::vector<std::vector<double>> deflection_;     // [wavelength][height]
  std::vector<std::vector<double>> transmittance_;  // [wavelength][height]
  std::vector<std::vector<double>> illumination_;   // [wavelength][bin]: E at (k + ½) bin
};

/// Where the Moon is in the Earth's shadow at `time` (geocentric: ERFA's
/// Moon98 and EPV00; the shadow's axis along the sunlight's path in the
/// Earth's frame, the Sun's direction moved by the annual aberration, 20.5″).
struct LunarEclipseGeometry {
  double moon_distance_m = 0.0;  ///< from the Earth's centre, along the shadow's axis
  double axis_distance_m = 0.0;  ///< of the Moon's centre from the axis
  double sun_angular_radius_rad = 0.0;
};
LunarEclipseGeometry lunar_eclipse_geometry(const AstroTime& time);

/// The Earth's shadow's radii at the Moon's distance by Danjon's rule (the
/// Earth's radius enlarged by 1/85, as the Five Millennium Canon takes it):
/// umbra R' − D (r_s − π_s), penumbra R' + D (r_s + π_s), π_s the Sun's
/// parallax; and the eclipse's magnitudes: (radius − (y − R_moon)) / 2 R_moon.
struct EarthShadowRadii {
  double umbra_m = 0.0, penumbra_m = 0.0;
};
EarthShadowRadii earth_shadow_radii(const AstroTime& time);

enum class LunarEclipseKind { penumbral, partial, total };
const char* to_string(LunarEclipseKind kind);

/// A lunar eclipse and how one site sees it.
struct LocalLunarEclipse {
  LunarEclipseKind kind = LunarEclipseKind::penumbral;
  AstroTime maximum;  ///< the Moon's centre nearest the shadow's axis
  double umbral_magnitude = 0.0, penumbral_magnitude = 0.0;
  AstroTime penumbra_begins, penumbra_ends;                 ///< P1, P4
  std::optional<AstroTime> umbra_begins, umbra_ends;        ///< U1, U4 (partial and total)
  std::optional<AstroTime> totality_begins, totality_ends;  ///< U2, U3 (total)
  double moon_altitude_deg = 0.0;                           ///< geometric, at the site, at the maximum
};

/// The first lunar eclipse with the Moon above `site`'s horizon at some time
/// between P1 and P4 that has not ended at `from`, within `years` (at most
/// 30), or none. Full moons bracketed by daily samples of the Moon's distance
/// from the shadow's axis, the least by golden section to a second, contacts
/// by bisection; penumbral eclipses included. Throws std::invalid_argument
/// for years outside (0, 30].
std::optional<LocalLunarEclipse> next_lunar_eclipse(const Site& site, const AstroTime& from, double years = 5.0);

}  // namespace zenith::astro
