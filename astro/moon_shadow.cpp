#include "astro/moon_shadow.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

#include "astro/eclipsed_sky.h"
#include "astro/solar_eclipse.h"
#include "atmosphere/lut/gauss_legendre.h"
#include "atmosphere/rayleigh_polarization.h"
#include "core/parallel_for.h"
#include "core/spherical_harmonics.h"
#include "core/strings.h"
#include "core/units.h"

namespace zenith::astro {
namespace {

using core::kPi;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// A unit vector across `axis` (unit): `hint` without its part along the axis, or any perpendicular.
glm::dvec3 across(const glm::dvec3& axis, const glm::dvec3& hint) {
  glm::dvec3 v = hint - glm::dot(hint, axis) * axis;
  if (glm::length(v) < 1e-9) {
    const glm::dvec3 other = std::abs(axis.x) < 0.9 ? glm::dvec3{1, 0, 0} : glm::dvec3{0, 1, 0};
    v = other - glm::dot(other, axis) * axis;
  }
  return glm::normalize(v);
}

/// `n` directions spread evenly over the sphere (a Fibonacci lattice).
std::vector<glm::dvec3> sphere_directions(std::size_t n) {
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  std::vector<glm::dvec3> d;
  for (std::size_t i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * double(i) + 1.0) / double(n), rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    d.push_back({rho * std::cos(golden * double(i)), rho * std::sin(golden * double(i)), z});
  }
  return d;
}

/// k₁ … k₅ of a phase function P(x) normalised over the sphere: P = (1/4π) Σ (2l+1) k_l P_l(x),
/// k_l = 2π ∫ P(x) P_l(x) dx (Henyey–Greenstein: g^l; Rayleigh: 0, 0.1, 0, 0, 0), by Gauss–Legendre
/// nodes on [−1, 1] in panels crowded forward, where an aerosol's peak is.
template <class Phase>
std::array<double, 5> legendre_k1_k5(Phase phase) {
  static const atmosphere::lut::GaussLegendre rule(16);
  const double breaks[] = {-1.0, 0.0, 0.5, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.998, 0.999, 1.0};
  std::array<double, 5> k{};
  for (std::size_t b = 0; b + 1 < std::size(breaks); ++b) {
    const double half = 0.5 * (breaks[b + 1] - breaks[b]), mid = 0.5 * (breaks[b + 1] + breaks[b]);
    for (std::size_t n = 0; n < rule.nodes.size(); ++n) {
      const double x = mid + half * rule.nodes[n], w = 2.0 * kPi * half * rule.weights[n] * phase(x);
      k[0] += w * x;
      k[1] += w * 0.5 * (3.0 * x * x - 1.0);
      k[2] += w * 0.5 * (5.0 * x * x * x - 3.0 * x);
      k[3] += w * (35.0 * x * x * x * x - 30.0 * x * x + 3.0) / 8.0;
      k[4] += w * x * (63.0 * x * x * x * x - 70.0 * x * x + 15.0) / 8.0;
    }
  }
  return k;
}

/// A scatterer from its phase function's k₁ … k₅ by delta-M (Wiscombe 1977, J. Atmos. Sci. 34, 1408):
/// the share f = k₅ of the scattering goes straight on, the rest has k_l' = (k_l − f)/(1 − f), so the
/// l ≤ 4 terms are still k_l but the cut phase function no longer goes negative sideways (Henyey–Greenstein
/// of g = 0.85 at 90°: 1 − 5g²/2 = −0.81 of isotropic cut at l ≤ 2, 0.123 exactly, 0.126 by delta-M).
MoonShadow::Scatterer delta_m_scatterer(double scattering_m1, const std::array<double, 5>& k, double dipole) {
  const double f = k[4] > 1e-6 ? std::min(k[4], 0.99) : 0.0;  // Rayleigh's k₅ is 0
  const auto past = [&](double k_l) { return (k_l - f) / (1.0 - f); };
  return {scattering_m1, past(k[0]), past(k[1]), dipole, f, past(k[2]), past(k[3])};
}

/// Where the harmonics' coefficients lie: in a node's field values (kShadowFieldValues), eclipsed then in
/// daylight, and in its sums while they are made (kLightSums).
constexpr std::size_t kEclipsedHarmonics = 25, kDaylightHarmonics = kEclipsedHarmonics + kShadowHigherMoments;
constexpr std::size_t kHarmonicsSums = 32;

/// The terms l = 3 and 4 of ∫ P(ω·v) L dω, times 2l + 1: (2l + 1) ∫ P_l(ω·v) L dω = 4π Σ_m Y_lm(v) c_lm
/// (core/spherical_harmonics.h), from a node's coefficients c of the light and v's harmonics.
struct HigherTerms {
  double l3 = 0.0, l4 = 0.0;
};
HigherTerms higher_terms(const double* c, const double* harmonics) {
  HigherTerms t;
  for (std::size_t n = 0; n < 7; ++n) t.l3 += c[n] * harmonics[n];
  for (std::size_t n = 7; n < kShadowHigherMoments; ++n) t.l4 += c[n] * harmonics[n];
  t.l3 *= 4.0 * kPi;
  t.l4 *= 4.0 * kPi;
  return t;
}

/// vᵀTv for a symmetric T given as xx, yy, zz, xy, xz, yz.
double quadratic(const double* T, const double* v) {
  return T[0] * v[0] * v[0] + T[1] * v[1] * v[1] + T[2] * v[2] * v[2] +
         2.0 * (T[3] * v[0] * v[1] + T[4] * v[0] * v[2] + T[5] * v[1] * v[2]);
}

/// The light arriving from straight behind, L(v) = a + 3 m·v + 5 (3 vᵀMv − a)/2 (its terms l ≤ 2: the
/// header), clipped at 0.
double straight_behind(const double* v, double a, const double* m, const double* M) {
  return std::max(0.0, a + 3.0 * (m[0] * v[0] + m[1] * v[1] + m[2] * v[2]) + 2.5 * (3.0 * quadratic(M, v) - a));
}

/// The light arriving from straight behind, eclipsed and in daylight per unit a of daylight, from a node's
/// values: the daylight's terms l ≤ 2, and the eclipsed light as `behind_left` of it where the caller knows
/// that share (the view ray's own light), else the eclipsed light's terms l ≤ 2.
struct LightBehind {
  double eclipsed, daylight;
};
LightBehind light_behind(const double* v, const double* values, std::optional<double> behind_left) {
  const double daylight = straight_behind(v, 1.0, values + 10, values + 13);
  return {behind_left ? *behind_left * daylight : straight_behind(v, values[0], values + 1, values + 4), daylight};
}

/// ∫ P(ω·v) L dω for a scatterer, from a node's sums (the header; the 1/4π
/// dropped, it cancels), never negative: (1 − f) [a + 3 k₁ (m·v) + 5 k₂ (3 vᵀMv − a)/2
/// + 7 k₃ ∫ P₃ L + 9 k₄ ∫ P₄ L + (3Δ/4) vᵀPv] + f L(v), M and P as xx, yy, zz, xy,
/// xz, yz, the terms l = 3, 4 from the light's harmonics (higher_terms), v in the
/// field's basis, `straight` the light L(v) arriving from straight behind (the
/// forward share f's), the spread part clipped at 0; without P (null) as scalar
/// transfer weighs it.
double phase_weight(const double* v, double a, const double* m, const double* M, const HigherTerms& h, const double* P,
                    double straight, const MoonShadow::Scatterer& t) {
  const double mv = m[0] * v[0] + m[1] * v[1] + m[2] * v[2], q = 2.5 * (3.0 * quadratic(M, v) - a);
  const double spread =
      a + 3.0 * t.k1 * mv + t.k2 * q + t.k3 * h.l3 + t.k4 * h.l4 + (P ? t.dipole * quadratic(P, v) : 0.0);
  return (1.0 - t.forward) * std::max(0.0, spread) + t.forward * straight;
}

glm::dmat3 symmetric(const double* t) { return glm::dmat3(t[0], t[3], t[4], t[3], t[1], t[5], t[4], t[5], t[2]); }

ShadowTensor components(const glm::dmat3& t) { return {t[0][0], t[1][1], t[2][2], t[0][1], t[0][2], t[1][2]}; }

}  // namespace

MoonShadow::MoonShadow(const EclipseGeometry& g, const atmosphere::lut::TableQueries& tables,
                       const atmosphere::AtmosphereModel& model, const glm::dvec3& camera_m,
                       const MoonShadowOptions& options, std::stop_token stop)
    : geometry_(g), options_(options), wavelengths_(model.wavelengths_nm.size()) {
  if (!finite(g.moon_centre_m) || !finite(g.sun_direction) || !finite(camera_m))
    throw std::invalid_argument("MoonShadow: the Moon's centre, the Sun's direction and the camera must be finite");
  if (!(g.moon_radius_m > 0.0) || !(g.sun_angular_radius_rad > 0.0) || !(g.sun_angular_radius_rad < 0.1))
    throw std::invalid_argument(core::cat("MoonShadow: Moon radius ", g.moon_radius_m,
                                          " m must be > 0 and the Sun's angular radius ", g.sun_angular_radius_rad,
                                          " rad in (0, 0.1)"));
  if (std::abs(glm::length(g.sun_direction) - 1.0) > 1e-6)
    throw std::invalid_argument("MoonShadow: the Sun's direction must be a unit vector");
  if (glm::length(g.moon_centre_m - camera_m) <= g.moon_radius_m)
    throw std::invalid_argument("MoonShadow: the camera is inside the Moon");
  if (g.limb_darkening.size() != wavelengths_)
    throw std::invalid_argument(
        core::cat("MoonShadow: ", g.limb_darkening.size(), " limb darkening laws for ", wavelengths_, " wavelengths"));
  for (const atmosphere::LimbDarkening& law : g.limb_darkening) atmosphere::check_limb_darkening(law, "MoonShadow");
  const std::vector<double>& z = options.field_altitudes_m;
  if (options.profile_samples < 2 || options.field_across < 3 || options.field_side < 2 || z.empty() ||
      z.front() != 0.0 || !std::is_sorted(z.begin(), z.end()) || std::adjacent_find(z.begin(), z.end()) != z.end() ||
      options.directions < 1 || options.higher_order_directions < 1 || options.segments < 1 || options.iterations < 1)
    throw std::invalid_argument(
        "MoonShadow: the profile needs ≥ 2 samples, the field ≥ 3 × 2 nodes and increasing altitudes from 0, the "
        "rays ≥ 1 direction and segment, the field ≥ 1 pass");
  ground_radius_m_ = model.ground_radius_m;
  rayleigh_density_ = model.rayleigh_density;
  mie_density_ = model.mie_density;
  const auto r = legendre_k1_k5([&](double x) { return model.rayleigh_phase_function(x); });  // one for all λ
  if (!(model.rayleigh_depolarization >= 0.0) || !(model.rayleigh_depolarization < 1.0))
    throw std::invalid_argument(
        core::cat("MoonShadow: the gas's depolarization ", model.rayleigh_depolarization, " must be in [0, 1)"));
  dipole_share_ = atmosphere::dipole_share(model.rayleigh_depolarization);
  for (std::size_t i = 0; i < wavelengths_; ++i) {
    const auto m = legendre_k1_k5([&](double x) { return model.mie_phase(i, x); });
    rayleigh_.push_back(delta_m_scatterer(model.rayleigh_scattering_m1[i], r, 0.75 * dipole_share_));
    mie_.push_back(delta_m_scatterer(model.mie_scattering_m1[i], m, 0.0));
  }
  set_frame(camera_m);
  axis_zenith_0_rad_ = axis_zenith_rad(g);
  fill_profile();
  fill_field(tables, model, stop);
}

void MoonShadow::set_frame(const glm::dvec3& camera_m) {
  const glm::dvec3& s = geometry_.sun_direction;
  const glm::dvec3 up = glm::normalize(camera_m);
  // e1 toward the planet's centre across the axis: the planet and the shadow are then mirror images of
  // themselves across the plane of the axis and e1 (along a central line, any direction across will do).
  const glm::dvec3 to_centre = -geometry_.moon_centre_m;
  const glm::dvec3 centre_across = to_centre - glm::dot(to_centre, s) * s;
  e1_ = glm::length(centre_across) > 1.0 ? glm::normalize(centre_across) : across(s, up);
  e2_ = glm::cross(s, e1_);
  const glm::dvec3 w = geometry_.moon_centre_m - camera_m;
  moon_distance_0_m_ = glm::length(w);
  moon_radius_0_rad_ = std::asin(std::min(1.0, geometry_.moon_radius_m / moon_distance_0_m_));
}

void MoonShadow::fill_profile() {
  const double r_s = geometry_.sun_angular_radius_rad, r_m = moon_radius_0_rad_;
  profile_end_rad_ = r_s + r_m;
  const std::size_t n = options_.profile_samples;
  profile_.assign(n * wavelengths_, 1.0f);
  for (std::size_t i = 0; i < wavelengths_; ++i) {
    const atmosphere::LimbDarkening& law = geometry_.limb_darkening[i];
    for (std::size_t k = 0; k < n; ++k) {
      const double x = profile_end_rad_ * double(k) / double(n - 1);
      profile_[k * wavelengths_ + i] = float(1.0 - limb_darkened_obscuration(x, r_s, r_m, law));
    }
  }
}

void MoonShadow::fill_field(const atmosphere::lut::TableQueries& tables, const atmosphere::AtmosphereModel& model,
                            const std::stop_token& stop) {
  // Beyond the penumbra's edge V̄ = V = 1.
  field_end_m_ = moon_distance_0_m_ * std::tan(profile_end_rad_);
  // The once-scattered light does not depend on V̄ (only on V): summed once,
  // and each later pass adds to it only the multiply scattered light under
  // the V̄ before.
  const MoonShadowOptions& o = options_;
  const std::vector<double> once =
      light_sums(tables, model, ArrivingOrders::once_scattered, o.directions, o.polarized, stop);
  field_ = field_from(once);
  for (int pass = 1; pass < o.iterations; ++pass) {
    if (o.polarized) {
      // The coherency arriving at each point with the multiply scattered light in it, as if unpolarized:
      // the polarization of all the light the gas there scatters on (the header).
      std::vector<double> arriving =
          light_sums(tables, model, ArrivingOrders::multiply_scattered, o.coherency_directions, false, stop);
      for (std::size_t n = 0; n < arriving.size(); ++n) arriving[n] += once[n];
      coherency_ = field_from(arriving);
    }
    std::vector<double> all =
        light_sums(tables, model, ArrivingOrders::multiply_scattered, o.higher_order_directions, o.polarized, stop);
    coherency_.clear();
    for (std::size_t n = 0; n < all.size(); ++n) all[n] += once[n];
    field_ = field_from(all);
  }
}

std::vector<double> MoonShadow::light_sums(const atmosphere::lut::TableQueries& tables,
                                           const atmosphere::AtmosphereModel& model, ArrivingOrders orders,
                                           std::size_t ray_count, bool polarization,
                                           const std::stop_token& stop) const {
  const MoonShadowOptions& o = options_;
  const glm::dvec3& s = geometry_.sun_direction;
  const std::vector<glm::dvec3> directions = sphere_directions(ray_count);
  const double weight = 1.0 / double(directions.size());  // means over the sphere: passes may differ in rays
  const std::size_t nodes = o.field_across * o.field_side * o.field_altitudes_m.size();
  std::vector<double> sums(nodes * wavelengths_ * kLightSums, 0.0);
  core::parallel_for(nodes, o.threads, [&](std::size_t node) {
    // parallel_for stops handing out nodes at the first exception and rethrows it.
    if (stop.stop_requested()) throw ShadowBuildStopped();
    const std::size_t j = node % o.field_across, k = (node / o.field_across) % o.field_side;
    const double altitude = o.field_altitudes_m[node / (o.field_across * o.field_side)];
    const double tu = -1.0 + 2.0 * double(j) / double(o.field_across - 1), tv = double(k) / double(o.field_side - 1);
    const double u = field_end_m_ * tu * std::abs(tu), v = field_end_m_ * tv * tv;
    double* out = &sums[node * wavelengths_ * kLightSums];
    // The point at this altitude on the line through (u, v) parallel to the axis, on the Sun's side.
    const glm::dvec3 line = geometry_.moon_centre_m + u * e1_ + v * e2_;
    const double radius = ground_radius_m_ + altitude, b = glm::dot(line, s);
    const double disc = b * b - (glm::dot(line, line) - radius * radius);
    if (disc < 0.0) {
      // No air there: V itself, isotropic, so interpolation toward the air is smooth (the once-scattered
      // sums only: a later pass adds nothing here).
      if (orders == ArrivingOrders::multiply_scattered) return;
      const double limb = std::atan(std::hypot(u, v) / moon_distance_0_m_);
      for (std::size_t i = 0; i < wavelengths_; ++i) {
        out[i * kLightSums] = profile_at(limb, i);
        out[i * kLightSums + 10] = 1.0;
      }
      return;
    }
    const glm::dvec3 p = line - (b - std::sqrt(disc)) * s;
    // The directions in the node's own frame (up, the sun's azimuth): as the shadow moves over the planet
    // the rays keep their place relative to the node's horizon and sun, so no ray crosses the horizon
    // from one frame to the next and the field changes smoothly with the eclipse.
    const glm::dvec3 up = glm::normalize(p), toward_sun = across(up, s), side = glm::cross(up, toward_sun);
    // The multiply scattered light's polarization, summed over every ray (each has the same weight).
    const bool polarized_multiple = polarization && orders == ArrivingOrders::multiply_scattered;
    ArrivingPolarization multiple;
    for (const glm::dvec3& local : directions) {
      const glm::dvec3 d = local.x * toward_sun + local.y * side + local.z * up;
      const ArrivingLight l =
          arriving_light(tables, model, *this, p, d, o.segments, orders, polarized_multiple ? &multiple : nullptr);
      const double w[3] = {glm::dot(d, e1_), glm::dot(d, e2_), glm::dot(d, s)};
      const double moments[10] = {1.0,         w[0],        w[1],        w[2],        w[0] * w[0],
                                  w[1] * w[1], w[2] * w[2], w[0] * w[1], w[0] * w[2], w[1] * w[2]};
      const std::array<double, kShadowHigherMoments> harmonics = core::spherical_harmonics_3_4(w[0], w[1], w[2]);
      for (std::size_t i = 0; i < wavelengths_; ++i) {
        for (std::size_t c = 0; c < 10; ++c) {
          out[i * kLightSums + c] += weight * l.eclipsed[i] * moments[c];
          out[i * kLightSums + 10 + c] += weight * l.daylight[i] * moments[c];
        }
        for (std::size_t c = 0; c < kShadowHigherMoments; ++c) {
          out[i * kLightSums + kHarmonicsSums + c] += weight * l.eclipsed[i] * harmonics[c];
          out[i * kLightSums + kHarmonicsSums + kShadowHigherMoments + c] += weight * l.daylight[i] * harmonics[c];
        }
      }
      if (!polarization || orders == ArrivingOrders::multiply_scattered) continue;
      // The gas's once-scattered light, from the sun's beam along −s into −d: Π(d) − 2 N, in the basis (e1, e2, s).
      const glm::dmat3 excess = atmosphere::transverse_projector(d) -
                                2.0 * atmosphere::once_scattered_rayleigh_coherency(dipole_share_, -s, -d);
      const glm::dvec3 basis[3] = {e1_, e2_, s};
      const auto component = [&](int row, int column) { return glm::dot(basis[row], excess * basis[column]); };
      const double shape[6] = {component(0, 0), component(1, 1), component(2, 2),
                               component(0, 1), component(0, 2), component(1, 2)};
      for (std::size_t i = 0; i < wavelengths_; ++i)
        for (std::size_t c = 0; c < 6; ++c) {
          out[i * kLightSums + 20 + c] += weight * l.rayleigh_single_eclipsed[i] * shape[c];
          out[i * kLightSums + 26 + c] += weight * l.rayleigh_single_daylight[i] * shape[c];
        }
    }
    if (!polarized_multiple) return;
    for (std::size_t i = 0; i < wavelengths_; ++i)
      for (std::size_t c = 0; c < 6; ++c) out[i * kLightSums + 20 + c] += weight * multiple.eclipsed[i][c];
  });
  return sums;
}

std::vector<float> MoonShadow::field_from(const std::vector<double>& sums) const {
  std::vector<float> field(sums.size() / kLightSums * kShadowFieldValues, 0.0f);
  for (std::size_t n = 0; n < sums.size() / kLightSums; ++n) {
    const double* sum = &sums[n * kLightSums];
    float* values = &field[n * kShadowFieldValues];
    const double daylight = sum[10];
    if (!(daylight > 0.0)) {
      values[0] = 1.0f;  // no light arrives even in daylight (the night side): nothing to take away
      continue;
    }
    // a_e, m_e, M_e; m_d, M_d (a_d is 1); P_e; H_e, H_d; P_d (kShadowFieldValues).
    for (std::size_t c = 0; c < 10; ++c) values[c] = float(sum[c] / daylight);
    for (std::size_t c = 1; c < 10; ++c) values[9 + c] = float(sum[10 + c] / daylight);
    for (std::size_t c = 0; c < 6; ++c) values[19 + c] = float(sum[20 + c] / daylight);
    for (std::size_t c = 0; c < 2 * kShadowHigherMoments; ++c)
      values[kEclipsedHarmonics + c] = float(sum[kHarmonicsSums + c] / daylight);
    for (std::size_t c = 0; c < 6; ++c) values[kShadowSkyValues + c] = float(sum[26 + c] / daylight);
  }
  return field;
}

MoonShadow::Place MoonShadow::place(const glm::dvec3& p) const {
  const glm::dvec3 w = geometry_.moon_centre_m - p;
  const double along = glm::dot(w, geometry_.sun_direction);
  const glm::dvec3 w_across = w - along * geometry_.sun_direction;
  const double perp = glm::length(w_across);
  // q = −w⊥: the point's offset from the axis.
  Place place{std::numeric_limits<double>::infinity(),
              {-glm::dot(w_across, e1_), -glm::dot(w_across, e2_)},
              glm::length(p) - ground_radius_m_};
  if (along <= 0.0) return place;  // the Moon is behind the point
  const double distance = std::hypot(along, perp);
  const double moon_radius = std::asin(std::min(1.0, geometry_.moon_radius_m / distance));
  place.limb_rad = std::max(0.0, std::atan2(perp, along) - (moon_radius - moon_radius_0_rad_));
  return place;
}

double MoonShadow::profile_at(double x, std::size_t i) const {
  if (!(x < profile_end_rad_)) return 1.0;
  const std::size_t n = options_.profile_samples;
  const double f = std::max(0.0, x) / profile_end_rad_ * double(n - 1);
  const std::size_t k = std::min<std::size_t>(std::size_t(f), n - 2);
  const double t = f - double(k);
  return (1.0 - t) * profile_[k * wavelengths_ + i] + t * profile_[(k + 1) * wavelengths_ + i];
}

double MoonShadow::direct_light(const glm::dvec3& p, std::size_t i) const { return direct_light(place(p), i); }

double MoonShadow::direct_light(const Place& place, std::size_t i) const { return profile_at(place.limb_rad, i); }

double MoonShadow::scattered_light(const glm::dvec3& p, const glm::dvec3& direction, std::size_t i) const {
  return scattered_light(place(p), direction, i);
}

std::array<MoonShadow::Scatterer, 2> MoonShadow::air_at(const Place& place, std::size_t i) const {
  const double h = std::clamp(place.altitude_m, 0.0, options_.field_altitudes_m.back());
  Scatterer gas = rayleigh_[i], aerosol = mie_[i];
  gas.scattering_m1 *= rayleigh_density_(h);
  aerosol.scattering_m1 *= mie_density_(h);
  return {gas, aerosol};
}

double MoonShadow::scattered_light(const Place& place, const glm::dvec3& direction, std::size_t i,
                                   std::optional<double> behind_left) const {
  if (std::isinf(place.limb_rad) || reach(place) >= 2.0) return 1.0;
  return share_left(field_at(field_, place, direction, i), air_at(place, i), behind_left);
}

double MoonShadow::skylight_left(const glm::dvec3& ground_m, std::size_t i) const {
  const Place place = this->place(ground_m);
  if (std::isinf(place.limb_rad) || reach(place) >= 2.0) return 1.0;
  // A horizontal surface weights the light from above by max(0, n·ω) = ¼ (1 + 2 P₁ + 5/4 P₂ + …).
  const Scatterer lambert[1] = {{1.0, 2.0 / 3.0, 0.25}};
  return share_left(field_at(field_, place, glm::normalize(ground_m), i), lambert, std::nullopt);
}

double MoonShadow::reach(const Place& place) const {
  return std::hypot(place.across_m[0], place.across_m[1]) / field_end_m_;
}

MoonShadow::FieldSample MoonShadow::field_at(const std::vector<float>& table, const Place& place,
                                             const glm::dvec3& direction, std::size_t i) const {
  const MoonShadowOptions& o = options_;
  FieldSample f;
  // Beyond the penumbra the nodes' edge holds light arriving from inside it;
  // farther out, over one more penumbra radius, V̄ eases to 1, so a shadow
  // that first reaches the air a camera sees changes nothing at once.
  const double r = reach(place);
  f.fade = r <= 1.0 ? 0.0 : r >= 2.0 ? 1.0 : (r - 1.0) * (r - 1.0) * (3.0 - 2.0 * (r - 1.0));
  // Node coordinates: q·e1 = end t|t| over [−1, 1], |q·e2| = end t² over [0, 1]: crowded toward the axis.
  const double u = std::clamp(place.across_m[0] / field_end_m_, -1.0, 1.0);
  const double fu = 0.5 * (1.0 + std::copysign(std::sqrt(std::abs(u)), u)) * double(o.field_across - 1);
  const double fv = std::sqrt(std::min(std::abs(place.across_m[1]) / field_end_m_, 1.0)) * double(o.field_side - 1);
  const std::size_t j = std::min<std::size_t>(std::size_t(fu), o.field_across - 2);
  const std::size_t k = std::min<std::size_t>(std::size_t(fv), o.field_side - 2);
  const double tu = fu - double(j), tv = fv - double(k);
  const std::vector<double>& z = o.field_altitudes_m;
  const double altitude = std::clamp(place.altitude_m, 0.0, z.back());
  const std::size_t level =
      std::clamp<std::size_t>(std::size_t(std::upper_bound(z.begin(), z.end(), altitude) - z.begin()), 1, z.size()) - 1;
  const std::size_t upper = std::min(level + 1, z.size() - 1);
  const double tz = upper == level ? 0.0 : (altitude - z[level]) / (z[upper] - z[level]);
  // Trilinear weights of the eight nodes around the point.
  for (std::size_t corner = 0; corner < 8; ++corner) {
    const std::size_t dj = corner & 1, dk = (corner >> 1) & 1, dl = corner >> 2;
    const double weight = (dj ? tu : 1.0 - tu) * (dk ? tv : 1.0 - tv) * (dl ? tz : 1.0 - tz);
    if (weight == 0.0) continue;
    const std::size_t node = ((dl ? upper : level) * o.field_side + k + dk) * o.field_across + j + dj;
    const float* at = &table[(node * wavelengths_ + i) * kShadowFieldValues];
    for (std::size_t c = 0; c < kShadowFieldValues; ++c) f.values[c] += weight * double(at[c]);
  }
  // v in the basis (e1, e2, s), mirrored across the plane of the axis and e1 where the point lies beyond it.
  f.mirrored = place.across_m[1] < 0.0;
  f.v[0] = glm::dot(direction, e1_);
  f.v[1] = (f.mirrored ? -1.0 : 1.0) * glm::dot(direction, e2_);
  f.v[2] = glm::dot(direction, geometry_.sun_direction);
  f.harmonics = core::spherical_harmonics_3_4(f.v[0], f.v[1], f.v[2]);
  return f;
}

double MoonShadow::share_left(const FieldSample& f, std::span<const Scatterer> scatterers,
                              std::optional<double> behind_left) {
  const double* values = f.values;
  const HigherTerms higher_eclipsed = higher_terms(values + kEclipsedHarmonics, f.harmonics.data()),
                    higher_daylight = higher_terms(values + kDaylightHarmonics, f.harmonics.data());
  const LightBehind behind = light_behind(f.v, values, behind_left);
  double eclipsed = 0.0, daylight = 0.0;
  for (const Scatterer& t : scatterers) {
    eclipsed += t.scattering_m1 *
                phase_weight(f.v, values[0], values + 1, values + 4, higher_eclipsed, values + 19, behind.eclipsed, t);
    // The daylight as the tables' scalar transfer has it (the header).
    daylight += t.scattering_m1 *
                phase_weight(f.v, 1.0, values + 10, values + 13, higher_daylight, nullptr, behind.daylight, t);
  }
  if (!(daylight > 0.0)) return 1.0;
  return std::clamp(eclipsed / daylight, 0.0, 1.0) * (1.0 - f.fade) + f.fade;
}

MoonShadow::ScatteredLight MoonShadow::polarized_scattered_light(const Place& place, const glm::dvec3& direction,
                                                                 std::size_t i,
                                                                 std::optional<double> behind_left) const {
  ScatteredLight light;
  const FieldSample f = field_at(field_, place, direction, i);
  const std::array<Scatterer, 2> air = air_at(place, i);
  const bool in_field = !std::isinf(place.limb_rad) && f.fade < 1.0;
  light.share_left = in_field ? share_left(f, air, behind_left) : 1.0;
  if (!options_.polarized) return light;
  // The gas's share of Π(v) − 2N per unit of what the air scatters along v:
  //   β_R (w_R Π(v) − 2 T) / Σ β w,   T = eq. (1) of 𝒯 = (a·1 − M − P)/2,   w_R = tr T,
  // its scalar weight (phase_weight's, exactly: tests/atmosphere/polarization_test.cpp).
  const glm::dvec3 v{f.v[0], f.v[1], f.v[2]};
  const auto excess = [&](double a, const double* m, const double* M, const double* H, const double* P, double behind) {
    const glm::dmat3 arriving = 0.5 * (a * glm::dmat3(1.0) - symmetric(M) - symmetric(P));
    const glm::dmat3 t = atmosphere::rayleigh_scattered_coherency(dipole_share_, v, arriving);
    const double gas_weight = std::max(0.0, t[0][0] + t[1][1] + t[2][2]);
    double all = 0.0;
    const HigherTerms higher = higher_terms(H, f.harmonics.data());
    for (const Scatterer& s : air) all += s.scattering_m1 * phase_weight(f.v, a, m, M, higher, P, behind, s);
    if (!(all > 0.0) || !(gas_weight > 0.0)) return glm::dmat3(0.0);
    const Scatterer& gas = air[0];  // air_at's first: Rayleigh's
    return gas.scattering_m1 / all * (gas_weight * atmosphere::transverse_projector(v) - 2.0 * t);
  };
  // While the table is made, the polarization is the coherency pass's (the header).
  const FieldSample arriving = coherency_.empty() ? f : field_at(coherency_, place, direction, i);
  const double* values = arriving.values;
  const LightBehind behind = light_behind(f.v, values, behind_left);
  const glm::dmat3 daylight =
      excess(1.0, values + 10, values + 13, values + kDaylightHarmonics, values + kShadowSkyValues, behind.daylight);
  glm::dmat3 eclipsed = daylight;
  if (in_field && light.share_left > 0.0) {
    // Where V̄ eases to daylight, so does its light's polarization: the share (1 − fade) V̄_field is the
    // eclipsed field's light, the rest daylight's.
    const double field_share = light.share_left - f.fade;
    eclipsed = (field_share * excess(values[0], values + 1, values + 4, values + kEclipsedHarmonics, values + 19,
                                     behind.eclipsed) +
                f.fade * daylight) /
               light.share_left;
  }
  light.excess = components(eclipsed);
  if (f.mirrored) {  // back across the plane of the axis and e1: e2 changes sign
    light.excess[3] = -light.excess[3];
    light.excess[5] = -light.excess[5];
  }
  return light;
}

double MoonShadow::axis_zenith_rad(const EclipseGeometry& g) const {
  // The axis' distance b from the planet's centre; past the planet's edge the angle goes on growing with b.
  const glm::dvec3 to_centre = -g.moon_centre_m;
  const double b = glm::length(to_centre - glm::dot(to_centre, g.sun_direction) * g.sun_direction) / ground_radius_m_;
  return b <= 1.0 ? std::asin(b) : 0.5 * core::kPi + (b - 1.0);
}

bool MoonShadow::still_fits(const EclipseGeometry& g, const glm::dvec3& camera_m) const {
  const double distance = glm::length(g.moon_centre_m - camera_m);
  const double moon_radius = std::asin(std::min(1.0, g.moon_radius_m / distance));
  // A 1e-3 change of a radius moves the profile by half a sample; 0.3° of the axis' zenith angle changes the
  // sky by < 0.5 % (1.4 % per degree measured at 2017-08-21 17:50 UTC, docs/validation.md, "Eclipses").
  constexpr double kRelative = 1e-3, kAxisZenith_rad = 0.3 * core::kDeg;
  return g.limb_darkening == geometry_.limb_darkening &&
         std::abs(moon_radius / moon_radius_0_rad_ - 1.0) <= kRelative &&
         std::abs(g.sun_angular_radius_rad / geometry_.sun_angular_radius_rad - 1.0) <= kRelative &&
         std::abs(axis_zenith_rad(g) - axis_zenith_0_rad_) <= kAxisZenith_rad;
}

void MoonShadow::move_to(const EclipseGeometry& g, const glm::dvec3& camera_m) {
  const double moon_radius_0 = moon_radius_0_rad_;
  geometry_ = g;
  set_frame(camera_m);
  // The tables were made for these: keep mapping points onto them as they were.
  moon_radius_0_rad_ = moon_radius_0;
}

}  // namespace zenith::astro
