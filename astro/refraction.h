#pragma once
// Atmospheric refraction from the model's own air (docs/night-sky.md, "Refraction").
//
// The gas's refractivity n − 1 is proportional to its number density
// (Gladstone–Dale, the dilute limit of Lorentz–Lorenz), so with the model's
// molecular density profile ρ(h) (relative, 1 at the ground):
//   n(r) = 1 + (n₀ − 1) ρ(r − R).
// At a wavelength, n₀² − 1 = P(λ)·N₀ (n² − 1 ∝ N, as the parameter loader
// scales it: atmosphere/rayleigh.h): P = (n_ref² − 1)/N_ref of the gas (air:
// Edlén 1953 as Penndorf 1957 tabulates it, at 2.547e25 m⁻³; other gases: the
// index and density their parameter file gives), N₀ the ground number density
// that reproduces the model's own Rayleigh coefficient (paper eq. 11):
//   β_R = 8π³ (P N)² f(δ) / (3 N λ⁴)  ⇒  N₀ = 3 λ⁴ β_R / (8 π³ P² f(δ)).
// earth-advanced gives back its 2.547e25 m⁻³ (to 1e-12), Mars its 2.19e23
// (636 Pa, 210 K); earth-standard's β_R (Bucholtz 1995) implies 2.72e25, 6.8 %
// more air than standard air, and so 6.8 % more refraction.
//
// In a spherically stratified atmosphere n r sin z is constant along a ray
// (Bouguer's invariant), and the refraction of a ray arriving at the observer
// (radius r₀) at apparent zenith angle z₀ is (e.g. Green 1985, "Spherical
// Astronomy", §4.3; Auer & Standish 2000, AJ 119, 2472)
//   R(z₀) = ∫_{r₀}^{r_top} −(1/n)(dn/dr) tan z dr,   tan z = C / √(n² r² − C²),  C = n₀ r₀ sin z₀.
// At the horizon tan z has an integrable 1/√(r − r₀) singularity; the
// substitution r = r₀ + u² removes it (dr = 2u du), and the midpoint rule in u
// (2048 intervals) converges to 1e-6 relative. R is tabulated once against the
// apparent altitude and inverted for the lift of an object at a true altitude.
#include <optional>
#include <vector>

#include "atmosphere/density_profile.h"
#include "atmosphere/parameters.h"

namespace zenith::astro {

/// n₀ − 1 of the model's gas at its ground at `wavelength_nm`, derived as above
/// from the parameter set (advanced mode: the gas's refractive index and the
/// density it was measured at; standard mode: air) and the model's β_R at the
/// working wavelength nearest 550 nm. Throws std::invalid_argument if the
/// model has no Rayleigh scattering.
double ground_refractivity(const atmosphere::LoadedAtmosphere& loaded, double wavelength_nm = 550.0);

/// The ground number density N₀ [m⁻³] the same derivation finds.
double ground_number_density_m3(const atmosphere::LoadedAtmosphere& loaded);

/// The lowest altitude [m] from `observer_altitude_m` up where n r stops growing
/// with r (d(nr)/dr ≤ 0, checked every 50 m): rays near the horizontal are
/// trapped there and R(0) diverges — a duct, as in Venus' dense lower air.
/// None for the Earth's presets (d(nr)/dr = 1 − (n₀ − 1)(R/H − 1) = 0.77 at the
/// ground) or Mars' (0.999).
std::optional<double> ducting_altitude_m(double ground_radius_m, double top_radius_m,
                                         const atmosphere::DensityProfile& density, double ground_refractivity,
                                         double observer_altitude_m);

class Refraction {
 public:
  /// `density`: the relative molecular profile (1 at the ground); `observer_altitude_m` ≥ 0.
  /// Throws std::invalid_argument for a negative refractivity, a top below the
  /// observer, or a gas so dense that rays are trapped (ducting, d(nr)/dr ≤ 0).
  Refraction(double ground_radius_m, double top_radius_m, const atmosphere::DensityProfile& density,
             double ground_refractivity, double observer_altitude_m = 0.0);
  /// The model's own air at `wavelength_nm` (ground_refractivity above).
  static Refraction for_atmosphere(const atmosphere::LoadedAtmosphere& loaded, double wavelength_nm = 550.0,
                                   double observer_altitude_m = 0.0);

  /// R [rad] at the horizon (apparent altitude 0) for an observer
  /// `observer_altitude_m` up, by the integral alone (no table): half the
  /// bending of a ray through the whole air whose lowest point is there.
  static double horizon_rad(double ground_radius_m, double top_radius_m, const atmosphere::DensityProfile& density,
                            double ground_refractivity, double observer_altitude_m);

  double ground_refractivity() const { return refractivity_; }
  /// R [rad] of a ray arriving at apparent altitude h ∈ [0, π/2], by the integral.
  double integral_rad(double apparent_altitude_rad) const;
  /// R [rad] at apparent altitude h from the table (h < 0 is taken as 0).
  double at_apparent_rad(double apparent_altitude_rad) const;
  /// Apparent altitude of an object at true (geometric) altitude h: h + R, solved
  /// on the table (the root of h' − at_apparent_rad(h') = h, in closed form on
  /// its segment); below −R(0) (under the apparent horizon) h + R(0).
  double apparent_from_true_rad(double true_altitude_rad) const;

 private:
  Refraction(double ground_radius_m, double top_radius_m, const atmosphere::DensityProfile& density,
             double ground_refractivity, double observer_altitude_m, bool tabulate);
  double refractivity_at(double r_m) const;
  double ground_radius_m_, top_radius_m_, observer_radius_m_, refractivity_;
  atmosphere::DensityProfile density_;
  std::vector<double> table_rad_;       // R at apparent altitude (π/2)·t², t = i/(n − 1)
  std::vector<double> node_h_minus_r_;  // h − R at those nodes (increasing): apparent_from_true_rad's segments
};

/// Bennett (1982, J. Navigation 35, 255): R = cot(h + 7.31/(h + 4.4)) arcmin, h
/// the apparent altitude in degrees; 1010 hPa, 10 °C; 0.07′ accuracy. [deg]
double bennett_refraction_deg(double apparent_altitude_deg);
/// Sæmundsson (1986, Sky & Telescope 72, 70): R = 1.02 cot(h + 10.3/(h + 5.11))
/// arcmin, h the true altitude in degrees; same conditions. [deg]
double saemundsson_refraction_deg(double true_altitude_deg);

}  // namespace zenith::astro
