// Colour of spectral quantities at the working wavelengths (colour.h;
// docs/colour.md explains the choices).
#include "image/colour.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include "core/planck.h"

namespace zenith::image {
namespace {

// Colour triples (XYZ, RGB, cone responses) and their 3 × 3 transforms are
// GLM's, the project's one vector library: glm::dmat3 is column-major, m[c][r].
using glm::dmat3;
using glm::dvec3;

dmat3 diagonal(const dvec3& v) { return dmat3(v.x, 0, 0, 0, v.y, 0, 0, 0, v.z); }

/// XYZ of a white point given by its chromaticity (x, y), scaled to Y = 1.
dvec3 white_xyz(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

// ---------------------------------------------------------------- CIE 1931

/// One lobe of Wyman, Sloan & Shirley's fit: a Gaussian of peak 1 at μ whose
/// width is σ₁ below μ and σ₂ above it,
///   g(λ; μ, σ₁, σ₂) = exp(−½ ((λ − μ) / σ)²),  σ = σ₁ if λ < μ else σ₂.
double lobe(double wavelength_nm, double mu_nm, double sigma_below_nm, double sigma_above_nm) {
  const double t = (wavelength_nm - mu_nm) / (wavelength_nm < mu_nm ? sigma_below_nm : sigma_above_nm);
  return std::exp(-0.5 * t * t);
}

/// CIE 1931 2° colour matching functions x̄, ȳ, z̄ by the multi-lobe fit of
/// C. Wyman, P.-P. Sloan, P. Shirley, "Simple Analytic Approximations to the
/// CIE XYZ Color Matching Functions", JCGT 2(2), 2013, eq. 2–4 and table 1:
///   x̄ = 1.056 g(λ; 599.8, 37.9, 31.0) + 0.362 g(λ; 442.0, 16.0, 26.7) − 0.065 g(λ; 501.1, 20.4, 26.2)
///   ȳ = 0.821 g(λ; 568.8, 46.9, 40.5) + 0.286 g(λ; 530.9, 16.3, 31.1)
///   z̄ = 1.217 g(λ; 437.0, 11.8, 36.0) + 0.681 g(λ; 459.0, 26.0, 13.8)
/// (λ in nm). The paper reports it within the variability of the measured data;
/// ∫x̄, ∫ȳ, ∫z̄ come out 106.8, 106.9, 106.9 against the tables' 106.9 each.
dvec3 cie1931_xyz_bar(double nm) {
  return {
      1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) - 0.065 * lobe(nm, 501.1, 20.4, 26.2),
      0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
      1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8)};
}

/// Linear sRGB → XYZ from the primaries and white of IEC 61966-2-1 (ITU-R BT.709
/// primaries R (0.64, 0.33), G (0.30, 0.60), B (0.15, 0.06); white D65
/// (0.3127, 0.3290)): the columns are the primaries' XYZ, scaled so that
/// RGB (1, 1, 1) is the white. Its inverse (3.2410 −1.5374 −0.4986;
/// −0.9692 1.8760 0.0416; 0.0556 −0.2040 1.0570) differs from the standard's
/// printed one (3.2406 −1.5372 −0.4986; −0.9689 1.8758 0.0415; 0.0557 −0.2040
/// 1.0570) by at most 4e-4, because the standard rounded its forward matrix
/// before inverting; derived, D65 maps to exactly (1, 1, 1).
dmat3 srgb_to_xyz() {
  const dmat3 primaries(white_xyz(0.64, 0.33), white_xyz(0.30, 0.60), white_xyz(0.15, 0.06));  // columns R, G, B
  const dvec3 scale = glm::inverse(primaries) * white_xyz(0.3127, 0.3290);
  return primaries * diagonal(scale);
}

/// Bradford chromatic adaptation from the equal-energy white E (X = Y = Z) to
/// D65 (Lam 1985; as in ICC.1 annex E and CIECAM97s):
///   A = M⁻¹ · diag(M · W_D65 ⊘ M · W_E) · M,
///   M = (0.8951 0.2664 −0.1614; −0.7502 1.7135 0.0367; 0.0389 −0.0685 1.0296).
/// The working wavelengths carry radiance per unit solar irradiance — the sun
/// is spectrally flat in these units — so a flat spectrum is the scene's white,
/// as it is for the direct mapping; without adapting, it would come out pink
/// (linear sRGB ≈ 1.20, 0.95, 0.91).
dmat3 bradford_e_to_d65() {
  const dmat3 m = glm::transpose(dmat3(0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296));
  const dvec3 cone_d65 = m * white_xyz(0.3127, 0.3290), cone_e = m * dvec3(1.0);
  return glm::inverse(m) * diagonal(cone_d65 / cone_e) * m;
}

/// Bin widths by the midpoint rule, as atmosphere::luminance_weights: half the
/// distance to each neighbour; the outer bins extend by half their inner gap
/// (100 nm for a single wavelength).
std::vector<double> bin_widths_nm(std::span<const double> wavelengths_nm) {
  const std::size_t n = wavelengths_nm.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return wavelengths_nm[a] < wavelengths_nm[b]; });
  std::vector<double> widths(n, 100.0);
  if (n < 2) return widths;
  for (std::size_t k = 0; k < n; ++k) {
    const double here = wavelengths_nm[order[k]];
    const double below = k > 0 ? wavelengths_nm[order[k - 1]] : 2 * here - wavelengths_nm[order[k + 1]];
    const double above = k + 1 < n ? wavelengths_nm[order[k + 1]] : 2 * here - wavelengths_nm[order[k - 1]];
    widths[order[k]] = 0.5 * (above - below);
  }
  return widths;
}

// ---------------------------------------------------------------- direct

enum Channel { red = 0, green = 1, blue = 2 };

/// The direct mapping's bands: B [380, 500) nm, G [500, 600) nm, R [600, 750] nm.
std::optional<Channel> direct_band(double nm) {
  if (nm >= 380.0 && nm < 500.0) return blue;
  if (nm >= 500.0 && nm < 600.0) return green;
  if (nm >= 600.0 && nm <= 750.0) return red;
  return std::nullopt;
}

bool direct_applies(std::span<const double> wavelengths_nm) {
  if (wavelengths_nm.size() != 3) return false;
  std::array<int, 3> count{};
  for (double nm : wavelengths_nm)
    if (const auto band = direct_band(nm)) ++count[*band];
  return count == std::array<int, 3>{1, 1, 1};
}

std::string describe(std::span<const double> wavelengths_nm) {
  std::ostringstream s;
  s << '{';
  for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) s << (i ? ", " : "") << wavelengths_nm[i];
  s << "} nm";
  return s.str();
}

void check_wavelengths(std::span<const double> wavelengths_nm) {
  if (wavelengths_nm.empty()) throw std::invalid_argument("colour mapping: no wavelengths");
  for (double nm : wavelengths_nm)
    if (!std::isfinite(nm) || nm <= 0.0)
      throw std::invalid_argument("colour mapping: wavelengths " + describe(wavelengths_nm) +
                                  " must be finite and positive");
}

/// `automatic` resolved; throws when `direct` is asked for and does not apply.
ColourMapping resolve(std::span<const double> wavelengths_nm, ColourMapping mapping) {
  const bool direct_ok = direct_applies(wavelengths_nm);
  if (mapping == ColourMapping::direct && !direct_ok)
    throw std::invalid_argument(
        "direct colour mapping needs exactly 3 wavelengths, one in each band R [600, 750] nm, "
        "G [500, 600) nm, B [380, 500) nm; got " +
        describe(wavelengths_nm));
  if (mapping == ColourMapping::automatic) return direct_ok ? ColourMapping::direct : ColourMapping::cie1931;
  return mapping;
}

std::vector<std::array<double, 3>> direct_weights(std::span<const double> wavelengths_nm) {
  std::vector<std::array<double, 3>> weights(wavelengths_nm.size(), {0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) weights[i][*direct_band(wavelengths_nm[i])] = 1.0;
  return weights;
}

}  // namespace

const char* to_string(ColourMapping mapping) {
  switch (mapping) {
    case ColourMapping::automatic: return "auto";
    case ColourMapping::direct: return "direct";
    case ColourMapping::cie1931: return "cie1931";
  }
  return "?";
}

ColourMapping parse_colour_mapping(const std::string& text) {
  if (text == "auto") return ColourMapping::automatic;
  if (text == "direct") return ColourMapping::direct;
  if (text == "cie1931") return ColourMapping::cie1931;
  throw std::invalid_argument("unknown colour mapping '" + text + "': must be one of auto, direct, cie1931");
}

std::vector<std::array<double, 3>> spectral_to_rgb_weights(std::span<const double> wavelengths_nm,
                                                           ColourMapping mapping) {
  check_wavelengths(wavelengths_nm);
  {
    std::vector<double> sorted(wavelengths_nm.begin(), wavelengths_nm.end());
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw std::invalid_argument("colour mapping: wavelengths " + describe(wavelengths_nm) + " repeat a value");
  }
  if (resolve(wavelengths_nm, mapping) == ColourMapping::direct) return direct_weights(wavelengths_nm);

  // rgb = k · Σ_i L_i Δλ_i · T · (x̄, ȳ, z̄)(λ_i),  T = sRGB⁻¹ · Bradford(E → D65),
  // k such that a flat L_i = 1 gives luminance Y = 0.2126 R + 0.7152 G + 0.0722 B = 1.
  const dmat3 to_xyz = srgb_to_xyz();
  const dmat3 xyz_to_rgb = glm::inverse(to_xyz) * bradford_e_to_d65();
  const std::vector<double> widths = bin_widths_nm(wavelengths_nm);
  std::vector<std::array<double, 3>> weights(wavelengths_nm.size());
  double flat_luminance = 0.0;
  for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) {
    const dvec3 rgb = xyz_to_rgb * (cie1931_xyz_bar(wavelengths_nm[i]) * widths[i]);
    weights[i] = {rgb.r, rgb.g, rgb.b};
    flat_luminance += glm::dot(glm::row(to_xyz, 1), rgb);  // Y of the weights
  }
  // A flat spectrum over the whole visible range has Σ ȳ Δλ ≈ 107 nm; wavelengths
  // that together see less than 1e-3 nm of it (all far outside 380–780 nm) make no colour.
  if (!(flat_luminance > 1e-3))
    throw std::invalid_argument("cie1931 colour mapping: the wavelengths " + describe(wavelengths_nm) +
                                " lie outside the visible range (a flat spectrum there has Σ ȳ Δλ = " +
                                std::to_string(flat_luminance) + " nm)");
  for (auto& w : weights)
    for (double& c : w) c /= flat_luminance;
  return weights;
}

std::vector<std::array<double, 3>> rgb_to_spectral_weights(std::span<const double> wavelengths_nm,
                                                           ColourMapping mapping) {
  check_wavelengths(wavelengths_nm);
  if (resolve(wavelengths_nm, mapping) == ColourMapping::direct) return direct_weights(wavelengths_nm);
  // Piecewise linear in λ through (450 nm, B), (550 nm, G), (650 nm, R), constant
  // beyond: the weights at each λ sum to 1, so white stays 1 and grey stays grey.
  std::vector<std::array<double, 3>> weights(wavelengths_nm.size());
  for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) {
    const double nm = wavelengths_nm[i];
    if (nm <= 450.0)
      weights[i] = {0.0, 0.0, 1.0};
    else if (nm <= 550.0)
      weights[i] = {0.0, (nm - 450.0) / 100.0, (550.0 - nm) / 100.0};
    else if (nm <= 650.0)
      weights[i] = {(nm - 550.0) / 100.0, (650.0 - nm) / 100.0, 0.0};
    else
      weights[i] = {1.0, 0.0, 0.0};
  }
  return weights;
}

namespace {

/// CIE 1960 UCS (u, v) of a chromaticity.
std::array<double, 2> uv_1960(Chromaticity c) {
  const double d = -2.0 * c.x + 12.0 * c.y + 3.0;
  return {4.0 * c.x / d, 6.0 * c.y / d};
}

/// The chromaticity of a Planckian radiator at `kelvin` through the colour
/// matching functions above, 360–830 nm every nm.
Chromaticity planckian(double kelvin) {
  dvec3 xyz(0.0);
  for (int nm = 360; nm <= 830; ++nm) xyz += cie1931_xyz_bar(nm) * core::planck_W_m2_sr_nm(nm, kelvin);
  const double sum = xyz.x + xyz.y + xyz.z;
  return {xyz.x / sum, xyz.y / sum};
}

/// Where f is least over [lo, hi]: a scan of `nodes` + 1 evenly spaced points,
/// then golden section between the best one's neighbours (the functions here
/// are smooth and have one minimum, but a scan first costs little and keeps a
/// flat stretch from misleading the section). `at_upper_end`: the best scanned
/// point was `hi` itself — the minimum lies there or beyond.
struct Minimum {
  double x = 0.0;
  bool at_upper_end = false;
};
template <class F>
Minimum scan_then_golden_section(F f, double lo, double hi, int nodes) {
  int best = 0;
  double best_value = f(lo);
  for (int k = 1; k <= nodes; ++k) {
    const double value = f(lo + (hi - lo) * k / nodes);
    if (value < best_value) best_value = value, best = k;
  }
  if (best == nodes) return {hi, true};
  double a = lo + (hi - lo) * std::max(best - 1, 0) / nodes, b = lo + (hi - lo) * (best + 1) / nodes;
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  while (b - a > 1e-7) {
    const double m1 = b - phi * (b - a), m2 = a + phi * (b - a);
    if (f(m1) < f(m2))
      b = m2;
    else
      a = m1;
  }
  return {0.5 * (a + b), false};
}

}  // namespace

Chromaticity spectrum_chromaticity(std::span<const double> wavelengths_nm, std::span<const double> spectrum) {
  spectral_to_rgb_weights(wavelengths_nm, ColourMapping::cie1931);  // the same checks of the wavelengths
  if (spectrum.size() != wavelengths_nm.size())
    throw std::invalid_argument("chromaticity: " + std::to_string(spectrum.size()) + " values for " +
                                std::to_string(wavelengths_nm.size()) + " wavelengths " + describe(wavelengths_nm));
  const std::vector<double> widths = bin_widths_nm(wavelengths_nm);
  dvec3 xyz(0.0);
  for (std::size_t i = 0; i < spectrum.size(); ++i) {
    if (!std::isfinite(spectrum[i]) || spectrum[i] < 0.0)
      throw std::invalid_argument("chromaticity: the value at " + std::to_string(wavelengths_nm[i]) + " nm is " +
                                  std::to_string(spectrum[i]) + " (must be finite and not negative)");
    xyz += cie1931_xyz_bar(wavelengths_nm[i]) * (spectrum[i] * widths[i]);
  }
  const double sum = xyz.x + xyz.y + xyz.z;
  if (!(sum > 0.0)) throw std::invalid_argument("chromaticity: the spectrum holds no light");
  return {xyz.x / sum, xyz.y / sum};
}

std::string colour_spectrum_problem(std::span<const double> wavelengths_nm) {
  if (wavelengths_nm.empty()) return "no wavelengths";
  const auto [lo, hi] = std::minmax_element(wavelengths_nm.begin(), wavelengths_nm.end());
  if (wavelengths_nm.size() >= 16 && *lo <= 400.0 && *hi >= 700.0) return {};
  std::ostringstream why;
  why << "a spectrum's colour needs at least 16 wavelengths from 400 nm or below to 700 nm or above; these are "
      << wavelengths_nm.size() << ", " << *lo << "–" << *hi << " nm";
  return why.str();
}

ColourTemperature correlated_colour_temperature(Chromaticity c) {
  if (!(std::isfinite(c.x) && std::isfinite(c.y) && c.x > 0.0 && c.y > 0.0 && c.x + c.y < 1.0))
    throw std::invalid_argument("colour temperature: (" + std::to_string(c.x) + ", " + std::to_string(c.y) +
                                ") is not a chromaticity");
  const std::array<double, 2> p = uv_1960(c);
  const auto distance = [&](double log_kelvin) {
    const std::array<double, 2> q = uv_1960(planckian(std::exp(log_kelvin)));
    return std::hypot(p[0] - q[0], p[1] - q[1]);
  };
  // Nearest at the search's hot end: the point lies beyond the locus' blue end, the chromaticity of
  // Planck's law as T → ∞ (Rayleigh–Jeans, B ∝ λ⁻⁴), which 10⁶ K is within 2e-4 in (u, v) of.
  const Minimum nearest = scan_then_golden_section(distance, std::log(1000.0), std::log(1e6), 200);
  const double kelvin = nearest.at_upper_end ? std::numeric_limits<double>::infinity() : std::exp(nearest.x);
  const std::array<double, 2> q = uv_1960(planckian(std::isinf(kelvin) ? 1e12 : kelvin));
  // Above the locus (v larger, toward green) is positive Duv.
  const double duv = std::copysign(std::hypot(p[0] - q[0], p[1] - q[1]), p[1] - q[1]);
  return {kelvin, duv};
}

double effective_blackbody_temperature_K(std::span<const double> wavelengths_nm, std::span<const double> spectrum,
                                         double from_nm, double to_nm) {
  if (spectrum.size() != wavelengths_nm.size())
    throw std::invalid_argument("effective blackbody temperature: " + std::to_string(spectrum.size()) + " values for " +
                                std::to_string(wavelengths_nm.size()) + " wavelengths");
  std::vector<std::pair<double, double>> band;  // λ [nm], ln S
  for (std::size_t i = 0; i < spectrum.size(); ++i) {
    if (!(wavelengths_nm[i] >= from_nm && wavelengths_nm[i] <= to_nm)) continue;
    if (!std::isfinite(spectrum[i]) || !(spectrum[i] > 0.0))
      throw std::invalid_argument(
          fmt::format("effective blackbody temperature: the value at {:g} nm is {:g} (must be "
                      "finite and positive)",
                      wavelengths_nm[i], spectrum[i]));
    band.emplace_back(wavelengths_nm[i], std::log(spectrum[i]));
  }
  if (band.size() < 3)
    throw std::invalid_argument(fmt::format(
        "effective blackbody temperature: {} wavelengths in {:g}–{:g} nm (at least 3)", band.size(), from_nm, to_nm));
  // The scale drops out: the residuals' variance about their mean.
  const auto misfit = [&](double log_kelvin) {
    const double kelvin = std::exp(log_kelvin);
    double sum = 0.0, sum2 = 0.0;
    for (const auto& [nm, ln_s] : band) {
      const double r = ln_s - std::log(core::planck_W_m2_sr_nm(nm, kelvin));
      sum += r;
      sum2 += r * r;
    }
    const double n = double(band.size());
    return sum2 / n - (sum / n) * (sum / n);
  };
  const Minimum best = scan_then_golden_section(misfit, std::log(1000.0), std::log(1e8), 400);
  return best.at_upper_end ? std::numeric_limits<double>::infinity() : std::exp(best.x);
}

}  // namespace zenith::image
