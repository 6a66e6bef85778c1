#include "astro/eclipsed_sky.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "core/units.h"

namespace zenith::astro {
namespace {

using core::kPi;
using Channels = std::array<double, atmosphere::lut::kMaxChannels>;

/// Where the light arriving at a segment from straight behind comes from, for
/// the aerosols' forward share (MoonShadow::scattered_light): the ray's own
/// light beyond the segment's middle (the camera's view rays), or the terms
/// l ≤ 2 of the light arriving at the shadow's nodes (the nodes' own rays:
/// with their own light too, V̄ lit three eclipses' totality zeniths 2–9 %
/// over the path tracer, docs/validation.md, "Eclipses").
enum class ForwardLight { the_rays_own, the_nodes };

/// The three table terms at one point of a ray, carried to its start: T(x, p) S(p).
struct CarriedTerms {
  Channels rayleigh{}, mie{}, multiple{};
};

/// A ray through the atmosphere from x (inside the shell or on it) to where it
/// leaves it or meets the ground, cut into segments ending at t_k = d (k/N)².
class SegmentedRay {
 public:
  /// From `start_m` along `view`; empty where a ray from outside misses the shell.
  static std::optional<SegmentedRay> make(const atmosphere::lut::TableQueries& tables, const glm::dvec3& start_m,
                                          const glm::dvec3& view, const glm::dvec3& sun, int segments) {
    if (segments < 1) throw std::invalid_argument("eclipsed sky: segments must be ≥ 1");
    const atmosphere::lut::ShellGeometry& g = tables.tables().geometry;
    SegmentedRay ray(tables, view, segments);
    ray.x_ = start_m;
    double r = glm::length(ray.x_), rmu = glm::dot(ray.x_, view);
    if (r > g.top_radius_m) {
      // Outside: move to where the ray enters the shell, or see nothing.
      const double disc = rmu * rmu - r * r + g.top_radius_m * g.top_radius_m;
      if (disc < 0.0 || rmu >= 0.0) return std::nullopt;
      ray.x_ = ray.x_ + view * (-rmu - std::sqrt(disc));
      r = g.top_radius_m;
      rmu = glm::dot(ray.x_, view);
    }
    ray.r_ = std::max(r, g.bottom_radius_m);
    ray.mu_ = std::clamp(rmu / ray.r_, -1.0, 1.0);
    ray.mu_s_ = std::clamp(glm::dot(ray.x_, sun) / ray.r_, -1.0, 1.0);
    ray.nu_ = std::clamp(glm::dot(view, sun), -1.0, 1.0);
    ray.hits_ground_ = g.ray_hits_ground(ray.r_, ray.mu_);
    ray.end_m_ = g.distance_to_nearest_boundary_m(ray.r_, ray.mu_, ray.hits_ground_);
    return ray;
  }

  int segments() const { return segments_; }
  double nu() const { return nu_; }
  bool hits_ground() const { return hits_ground_; }
  double distance(int k) const { return end_m_ * double(k) * double(k) / (double(segments_) * double(segments_)); }
  glm::dvec3 point(double t) const { return x_ + view_ * t; }
  /// Segment k's middle.
  glm::dvec3 middle(int k) const { return point(0.5 * (distance(k) + distance(k + 1))); }

  /// The terms at the k-th cut carried to the start; zero at the end (nothing
  /// scatters beyond it). Reads the single-scattering tables with `single`,
  /// the multiple-scattering one with `multiple`.
  CarriedTerms carried(int k, bool single, bool multiple) const {
    CarriedTerms c;
    if (k == segments_) return c;
    const atmosphere::lut::ShellGeometry& g = tables_.tables().geometry;
    const double t = distance(k);
    const double r_k = std::clamp(std::sqrt(t * t + 2.0 * r_ * mu_ * t + r_ * r_), g.bottom_radius_m, g.top_radius_m);
    const double mu_k = std::clamp((r_ * mu_ + t) / r_k, -1.0, 1.0);
    const double mu_s_k = std::clamp((r_ * mu_s_ + t * nu_) / r_k, -1.0, 1.0);
    tables_.scattering_terms(r_k, mu_k, mu_s_k, nu_, hits_ground_, single ? c.rayleigh.data() : nullptr,
                             single ? c.mie.data() : nullptr, multiple ? c.multiple.data() : nullptr);
    if (k == 0) return c;
    Channels transmittance{};
    tables_.transmittance(r_, mu_, t, hits_ground_, transmittance.data());
    for (std::size_t i = 0; i < tables_.channels(); ++i) {
      c.rayleigh[i] *= transmittance[i];
      c.mie[i] *= transmittance[i];
      c.multiple[i] *= transmittance[i];
    }
    return c;
  }

  /// Where the ray meets the ground: the sun's cosine there, the transmittance
  /// to it and the ground's direct and sky irradiance per unit solar irradiance.
  struct Ground {
    glm::dvec3 point_m;
    Channels transmittance{}, direct{}, sky{};
  };
  Ground ground(const glm::dvec3& sun) const {
    const atmosphere::lut::ShellGeometry& g = tables_.tables().geometry;
    Ground e;
    e.point_m = point(end_m_);
    const double mu_s = std::clamp(glm::dot(glm::normalize(e.point_m), sun), -1.0, 1.0);
    tables_.irradiance(g.bottom_radius_m, mu_s, false, e.sky.data());
    if (mu_s > 0.0) {
      tables_.transmittance_to_sun(g.bottom_radius_m, mu_s, e.direct.data());
      for (std::size_t i = 0; i < tables_.channels(); ++i) e.direct[i] *= mu_s;
    }
    tables_.transmittance(r_, mu_, end_m_, true, e.transmittance.data());
    return e;
  }

 private:
  SegmentedRay(const atmosphere::lut::TableQueries& tables, const glm::dvec3& view, int segments)
      : tables_(tables), view_(view), segments_(segments) {}

  const atmosphere::lut::TableQueries& tables_;
  glm::dvec3 view_, x_{0.0};
  int segments_;
  double r_ = 0.0, mu_ = 0.0, mu_s_ = 0.0, nu_ = 0.0, end_m_ = 0.0;
  bool hits_ground_ = false;
};

/// The light arriving at the ray's start, eclipsed and in daylight, of the
/// `orders` asked for: the single scattering and the ground's reflected direct
/// sun (V); the multiple scattering (V̄ along the ray's direction) and the
/// ground's reflected skylight (the skylight's share left). Where
/// `polarization` is given, each segment's multiply scattered light times its
/// excess Π − 2N is added to it.
ArrivingLight sum_along(const SegmentedRay& ray, const atmosphere::AtmosphereModel& model, const MoonShadow& shadow,
                        const glm::dvec3& view, std::size_t channels, ArrivingOrders orders,
                        ArrivingPolarization* polarization, ForwardLight forward) {
  const bool single = orders != ArrivingOrders::multiply_scattered;
  const bool multiple = orders != ArrivingOrders::once_scattered;
  if (forward == ForwardLight::the_rays_own && !(single && multiple))
    throw std::invalid_argument("eclipsed sky: the ray's own light from behind needs all its orders");
  // Summed from the ray's far end back to its start, so that each segment
  // knows the light arriving at its middle from straight behind — the air's
  // beyond it and the far half of its own, both orders, eclipsed and in
  // daylight — which the aerosols' forward share scatters on
  // (MoonShadow::scattered_light).
  ArrivingLight light;
  const double phase_r = model.rayleigh_phase_function(ray.nu());
  CarriedTerms far = ray.carried(ray.segments(), single, multiple);
  for (int k = ray.segments() - 1; k >= 0; --k) {
    const CarriedTerms near = ray.carried(k, single, multiple);
    const MoonShadow::Place middle = shadow.place(ray.middle(k));
    for (std::size_t i = 0; i < channels; ++i) {
      double direct = 0.0, rayleigh = 0.0, single_in = 0.0;
      if (single) {
        direct = shadow.direct_light(middle, i);
        rayleigh = std::max(0.0, near.rayleigh[i] - far.rayleigh[i]) * phase_r;
        single_in = rayleigh + std::max(0.0, near.mie[i] - far.mie[i]) * model.mie_phase(i, ray.nu());
      }
      const double multiple_in = multiple ? std::max(0.0, near.multiple[i] - far.multiple[i]) : 0.0;
      // Both sums carry the light to the ray's start alike: their ratio is the share left where it
      // arrives. The far half of the segment's own multiply scattered light is taken at the share of
      // the light beyond it.
      std::optional<double> behind_left;
      if (forward == ForwardLight::the_rays_own && light.daylight[i] > 0.0) {
        const double beyond = light.eclipsed[i] / light.daylight[i];
        behind_left = (light.eclipsed[i] + 0.5 * (direct * single_in + beyond * multiple_in)) /
                      (light.daylight[i] + 0.5 * (single_in + multiple_in));
      }
      if (single) {
        light.daylight[i] += single_in;
        light.eclipsed[i] += direct * single_in;
        light.rayleigh_single_daylight[i] += rayleigh;
        light.rayleigh_single_eclipsed[i] += direct * rayleigh;
      }
      if (multiple) {
        light.daylight[i] += multiple_in;
        if (polarization) {
          const MoonShadow::ScatteredLight s = shadow.polarized_scattered_light(middle, view, i, behind_left);
          light.eclipsed[i] += s.share_left * multiple_in;
          for (std::size_t c = 0; c < 6; ++c) polarization->eclipsed[i][c] += s.share_left * multiple_in * s.excess[c];
        } else {
          light.eclipsed[i] += shadow.scattered_light(middle, view, i, behind_left) * multiple_in;
        }
      }
    }
    far = near;
  }
  if (ray.hits_ground()) {
    // Lambertian ground: ρ/π (E_sun V + E_sky V̄), carried to the ray's start.
    const SegmentedRay::Ground e = ray.ground(shadow.geometry().sun_direction);
    const MoonShadow::Place ground = shadow.place(e.point_m);
    for (std::size_t i = 0; i < channels; ++i) {
      const double carried = e.transmittance[i] * model.ground_albedo[i] / kPi;
      if (single) {
        light.daylight[i] += carried * e.direct[i];
        light.eclipsed[i] += carried * e.direct[i] * shadow.direct_light(ground, i);
      }
      if (multiple) {
        light.daylight[i] += carried * e.sky[i];
        light.eclipsed[i] += carried * e.sky[i] * shadow.skylight_left(e.point_m, i);
      }
    }
  }
  return light;
}

}  // namespace

atmosphere::Spectrum eclipsed_sky_radiance(const atmosphere::lut::TableQueries& tables,
                                           const atmosphere::AtmosphereModel& model, const MoonShadow& shadow,
                                           const glm::dvec3& camera_m, const glm::dvec3& view, int segments) {
  atmosphere::Spectrum result(tables.channels(), 0.0);
  const std::optional<SegmentedRay> ray =
      SegmentedRay::make(tables, camera_m, view, shadow.geometry().sun_direction, segments);
  if (!ray) return result;
  const ArrivingLight light =
      sum_along(*ray, model, shadow, view, tables.channels(), ArrivingOrders::all, nullptr, ForwardLight::the_rays_own);
  for (std::size_t i = 0; i < tables.channels(); ++i) result[i] = light.eclipsed[i];
  return result;
}

ArrivingLight arriving_light(const atmosphere::lut::TableQueries& tables, const atmosphere::AtmosphereModel& model,
                             const MoonShadow& shadow, const glm::dvec3& point_m, const glm::dvec3& direction,
                             int segments, ArrivingOrders orders, ArrivingPolarization* multiple_polarization) {
  if (multiple_polarization && orders == ArrivingOrders::once_scattered)
    throw std::invalid_argument("arriving_light: the multiply scattered light's polarization needs its orders");
  const std::optional<SegmentedRay> ray =
      SegmentedRay::make(tables, point_m, direction, shadow.geometry().sun_direction, segments);
  if (!ray) return {};
  return sum_along(*ray, model, shadow, direction, tables.channels(), orders, multiple_polarization,
                   ForwardLight::the_nodes);
}

}  // namespace zenith::astro
