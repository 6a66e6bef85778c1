#include "astro/refraction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "atmosphere/rayleigh.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

constexpr std::size_t kTableSize = 512;
constexpr int kIntervals = 2048;
constexpr double kAirDepolarization = 0.0279;  // paper Table 1, as earth-advanced

/// The gas's (n² − 1) per molecule P(λ) = (n_ref² − 1)/N_ref (the loader scales
/// n² − 1 with N: atmosphere/rayleigh.h) and its depolarization, from the parameter set.
struct GasOptics {
  double refractivity_per_molecule_m3 = 0.0;  ///< P = (n_ref² − 1) / N_ref [m³]
  double depolarization = kAirDepolarization;
  bool at_ground_density = false;    ///< the index was given at the gas's own ground density
  double ground_refractivity = 0.0;  ///< then its n − 1
};

GasOptics gas_optics(const atmosphere::LoadedAtmosphere& loaded, double wavelength_nm) {
  GasOptics g;
  const auto& p = loaded.parameters;
  const bool advanced = loaded.mode == "advanced" && p.contains("gas") && p["gas"].is_object();
  auto standard_air = [&] {
    const double n = atmosphere::standard_air_refractive_index(wavelength_nm);
    g.refractivity_per_molecule_m3 = (n * n - 1.0) / atmosphere::kStandardAirNumberDensity_m3;
  };
  if (!advanced) {
    standard_air();
    return g;
  }
  const auto& gas = p["gas"];
  if (gas.contains("depolarization") && gas["depolarization"].is_number()) g.depolarization = gas["depolarization"];
  const auto index = gas.value("refractive_index", nlohmann::json("standard_air"));
  if (index.is_string()) {
    standard_air();
    return g;
  }
  // A number, or {"680": n, ...}: linear in wavelength between samples, nearest outside (as the loader reads it).
  double n = 0.0;
  if (index.is_number()) {
    n = index.get<double>();
  } else {
    std::vector<std::pair<double, double>> samples;
    for (auto it = index.begin(); it != index.end(); ++it)
      samples.emplace_back(std::stod(it.key()), it.value().get<double>());
    n = atmosphere::SpectralTable(samples)(wavelength_nm);
  }
  // The density the index was measured at, when given: K = (n − 1)/N_ref.
  // Without it the index is the gas's own at its ground: n₀ − 1 directly,
  // which the callers below tell by `at_ground_density`.
  if (gas.contains("refractive_index_number_density_m3")) {
    g.refractivity_per_molecule_m3 = (n * n - 1.0) / gas["refractive_index_number_density_m3"].get<double>();
  } else {
    g.at_ground_density = true;
    g.ground_refractivity = n - 1.0;
    g.refractivity_per_molecule_m3 = n * n - 1.0;  // per the (unknown) ground density: see ground_number_density_m3
  }
  return g;
}

std::size_t nearest_to_550(const std::vector<double>& wavelengths_nm) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < wavelengths_nm.size(); ++i)
    if (std::abs(wavelengths_nm[i] - 550.0) < std::abs(wavelengths_nm[best] - 550.0)) best = i;
  return best;
}

}  // namespace

double ground_number_density_m3(const atmosphere::LoadedAtmosphere& loaded) {
  const auto& m = loaded.model;
  if (m.wavelength_count() == 0 || m.rayleigh_scattering_m1.size() != m.wavelength_count())
    throw std::invalid_argument(loaded.model.name + ": no Rayleigh scattering to derive the air's density from");
  const std::size_t i = nearest_to_550(m.wavelengths_nm);
  const double beta = m.rayleigh_scattering_m1[i];
  if (!(beta > 0.0))
    throw std::invalid_argument(m.name + ": Rayleigh scattering is zero: no refraction can be derived");
  const double lambda_m = m.wavelengths_nm[i] * 1e-9;
  const GasOptics g = gas_optics(loaded, m.wavelengths_nm[i]);
  const double f = atmosphere::king_factor(g.depolarization);
  const double pi3 = core::kPi * core::kPi * core::kPi;
  if (g.at_ground_density) {
    // n given at the gas's own density: β = 8π³ (n² − 1)² f / (3 λ⁴ N) ⇒ N = 8π³ (n² − 1)² f / (3 λ⁴ β).
    const double n2m1 = g.refractivity_per_molecule_m3;
    return 8.0 * pi3 * n2m1 * n2m1 * f / (3.0 * std::pow(lambda_m, 4) * beta);
  }
  // β = 8π³ (P N)² f / (3 λ⁴ N) = 8π³ P² N f / (3 λ⁴) ⇒ N = 3 λ⁴ β / (8π³ P² f).
  const double p = g.refractivity_per_molecule_m3;
  return 3.0 * std::pow(lambda_m, 4) * beta / (8.0 * pi3 * p * p * f);
}

double ground_refractivity(const atmosphere::LoadedAtmosphere& loaded, double wavelength_nm) {
  const double n0 = ground_number_density_m3(loaded);
  const GasOptics g = gas_optics(loaded, wavelength_nm);
  if (g.at_ground_density) return g.ground_refractivity;
  return std::sqrt(1.0 + g.refractivity_per_molecule_m3 * n0) - 1.0;  // n₀² − 1 = P N₀
}

std::optional<double> ducting_altitude_m(double ground_radius_m, double top_radius_m,
                                         const atmosphere::DensityProfile& density, double ground_refractivity,
                                         double observer_altitude_m) {
  // n r with n = 1 + (n₀ − 1) ρ(r − R), differenced over the metre above (the air ends at the ground).
  const auto n_r = [&](double r) { return (1.0 + ground_refractivity * density(r - ground_radius_m)) * r; };
  for (double h = observer_altitude_m; h < top_radius_m - ground_radius_m; h += 50.0) {
    const double r = ground_radius_m + h;
    if (!(n_r(r + 1.0) - n_r(r) > 0.0)) return h;
  }
  return std::nullopt;
}

Refraction::Refraction(double ground_radius_m, double top_radius_m, const atmosphere::DensityProfile& density,
                       double ground_refractivity, double observer_altitude_m)
    : Refraction(ground_radius_m, top_radius_m, density, ground_refractivity, observer_altitude_m, true) {}

double Refraction::horizon_rad(double ground_radius_m, double top_radius_m, const atmosphere::DensityProfile& density,
                               double ground_refractivity, double observer_altitude_m) {
  return Refraction(ground_radius_m, top_radius_m, density, ground_refractivity, observer_altitude_m, false)
      .integral_rad(0.0);
}

Refraction::Refraction(double ground_radius_m, double top_radius_m, const atmosphere::DensityProfile& density,
                       double ground_refractivity, double observer_altitude_m, bool tabulate)
    : ground_radius_m_(ground_radius_m),
      top_radius_m_(top_radius_m),
      observer_radius_m_(ground_radius_m + observer_altitude_m),
      refractivity_(ground_refractivity),
      density_(density) {
  if (!(ground_refractivity >= 0.0 && ground_refractivity < 0.1))
    throw std::invalid_argument("refraction: ground refractivity n - 1 = " + std::to_string(ground_refractivity) +
                                ": must be in [0, 0.1)");
  if (!(observer_altitude_m >= 0.0 && observer_radius_m_ < top_radius_m_))
    throw std::invalid_argument("refraction: observer altitude " + std::to_string(observer_altitude_m) +
                                " m: must be in [0, the atmosphere's height)");
  // No ducting: n r must grow with r, or horizontal rays are trapped and the integral diverges.
  if (const auto duct_m =
          ducting_altitude_m(ground_radius_m, top_radius_m, density, ground_refractivity, observer_altitude_m))
    throw std::invalid_argument(
        fmt::format("refraction: the gas is so dense that horizontal rays are trapped {:.2f} km up (d(nr)/dr <= 0)",
                    *duct_m / 1000.0));
  if (!tabulate) return;
  table_rad_.resize(kTableSize);
  for (std::size_t i = 0; i < kTableSize; ++i) {
    const double t = double(i) / double(kTableSize - 1);
    table_rad_[i] = integral_rad(0.5 * core::kPi * t * t);
  }
  node_h_minus_r_.resize(kTableSize);
  for (std::size_t i = 0; i < kTableSize; ++i) {
    const double t = double(i) / double(kTableSize - 1);
    node_h_minus_r_[i] = 0.5 * core::kPi * t * t - table_rad_[i];
  }
}

Refraction Refraction::for_atmosphere(const atmosphere::LoadedAtmosphere& loaded, double wavelength_nm,
                                      double observer_altitude_m) {
  return Refraction(loaded.model.ground_radius_m, loaded.model.top_radius_m, loaded.model.rayleigh_density,
                    astro::ground_refractivity(loaded, wavelength_nm), observer_altitude_m);
}

double Refraction::refractivity_at(double r_m) const {
  return refractivity_ * density_(std::max(0.0, r_m - ground_radius_m_));
}

double Refraction::integral_rad(double apparent_altitude_rad) const {
  const double z0 = 0.5 * core::kPi - std::clamp(apparent_altitude_rad, 0.0, 0.5 * core::kPi);
  const double r0 = observer_radius_m_;
  const double c = (1.0 + refractivity_at(r0)) * r0 * std::sin(z0);
  const double u_top = std::sqrt(top_radius_m_ - r0);
  const double du = u_top / kIntervals;
  double sum = 0.0;
  for (int k = 0; k < kIntervals; ++k) {
    const double u = (k + 0.5) * du;
    const double r = r0 + u * u;
    const double n = 1.0 + refractivity_at(r);
    const double step = std::max(1.0, 1e-3 * u * u);  // central difference of n
    const double dn_dr =
        (refractivity_at(r + step) - refractivity_at(std::max(r0, r - step))) / (r + step - std::max(r0, r - step));
    const double nr = n * r;
    const double root = std::sqrt(std::max(nr * nr - c * c, 1e-300));
    sum += (-dn_dr / n) * (c / root) * 2.0 * u;
  }
  return sum * du;
}

double Refraction::at_apparent_rad(double apparent_altitude_rad) const {
  const double h = std::clamp(apparent_altitude_rad, 0.0, 0.5 * core::kPi);
  const double x = std::sqrt(h / (0.5 * core::kPi)) * double(kTableSize - 1);
  const std::size_t i = std::min<std::size_t>(std::size_t(x), kTableSize - 2);
  const double f = x - double(i);
  return table_rad_[i] * (1.0 - f) + table_rad_[i + 1] * f;
}

double Refraction::apparent_from_true_rad(double true_altitude_rad) const {
  if (true_altitude_rad <= -table_rad_[0]) return true_altitude_rad + table_rad_[0];
  // f(h) = h − R(h) − h_true is increasing, negative at max(0, h_true) and
  // positive at h_true + R(0). R is linear in t = √(h / (π/2)) between the
  // table's nodes t_i = i/M (M = kTableSize − 1, at_apparent_rad), so on the
  // segment [t_i, t_i+1] with t = (i + s)/M, h = k (i + s)², k = π/(2M²):
  //   f = k s² + (2 k i − ΔR) s + (g_i − h_true),  ΔR = R_i+1 − R_i ≤ 0,
  // g_i = k i² − R_i the node's h − R. Its root in s ∈ [0, 1] is closed form,
  // s = 2 (h_true − g_i) / (b + √(b² + 4 k (h_true − g_i))), b = 2 k i − ΔR > 0
  // (no cancellation), on the segment whose g_i ≤ h_true < g_i+1 (binary
  // search: g grows with i). The star pass solves this for every star in view,
  // every frame: one search and one square root where the regula falsi this
  // replaced took 5–10 table reads (docs/night-sky.md, "Cost").
  // Where f(lo) ≥ 0 or f(hi) ≤ 0 (no refraction there, or h_true above the
  // last node's h − R) the segment's root clamps to lo or hi, the bracket's ends.
  const double lo = std::max(0.0, true_altitude_rad), hi = std::min(0.5 * core::kPi, true_altitude_rad + table_rad_[0]);
  if (lo >= hi) return true_altitude_rad;
  // The root's t lies between those of lo and hi (h ≥ h_true, R ≤ R(0)): search there.
  const double m = double(kTableSize - 1);
  const auto node = [&](double h) { return static_cast<std::ptrdiff_t>(std::sqrt(h / (0.5 * core::kPi)) * m); };
  const auto begin = node_h_minus_r_.begin();
  const auto first = std::upper_bound(begin + std::clamp<std::ptrdiff_t>(node(lo) - 1, 0, kTableSize - 1),
                                      begin + std::min<std::ptrdiff_t>(node(hi) + 2, kTableSize), true_altitude_rad);
  const std::size_t i =
      std::min<std::size_t>(static_cast<std::size_t>(std::max<std::ptrdiff_t>(first - begin - 1, 0)), kTableSize - 2);
  const double k = 0.5 * core::kPi / (double(kTableSize - 1) * double(kTableSize - 1));
  const double above = true_altitude_rad - node_h_minus_r_[i];  // ≥ 0
  const double delta_r = table_rad_[i + 1] - table_rad_[i];
  const double b = 2.0 * k * double(i) - delta_r;
  const double s = std::clamp(2.0 * above / (b + std::sqrt(b * b + 4.0 * k * above)), 0.0, 1.0);
  // h = h_true + R(h): the small R added to the exact h_true keeps h's digits.
  return std::clamp(true_altitude_rad + table_rad_[i] + delta_r * s, lo, hi);
}

double bennett_refraction_deg(double h) {
  const double arg_deg = h + 7.31 / (h + 4.4);
  return 1.0 / std::tan(arg_deg * core::kDeg) / 60.0;
}

double saemundsson_refraction_deg(double h) {
  const double arg_deg = h + 10.3 / (h + 5.11);
  return 1.02 / std::tan(arg_deg * core::kDeg) / 60.0;
}

}  // namespace zenith::astro
