#include "atmosphere/reference/delta_tracking.h"

#include <cmath>

#include "atmosphere/reference/shell_traversal.h"

namespace zenith::atmosphere::reference {

namespace {

/// Exponential variate of unit mean: an optical distance in majorant units.
double sample_unit_exponential(Pcg32& rng) { return -std::log1p(-rng.uniform()); }

/// The tentative collisions within one shell segment, where they come at `rate`
/// [m^-1]: `remaining` is the optical depth (at that rate) to the next one,
/// carried from segment to segment. Calls `collide(t)` at each collision inside
/// the segment, then samples the next; false when `collide` ends the walk (it
/// returned false), true when the segment is crossed.
template <class Collide>
bool cross_segment(const ShellSegment& segment, double rate, double& remaining, Pcg32& rng, Collide&& collide) {
  double t = segment.begin_t_m;
  while (true) {
    const double available = rate * (segment.end_t_m - t);
    if (remaining >= available) {
      remaining -= available;
      return true;  // on to the next segment
    }
    t += remaining / rate;
    if (!collide(t)) return false;
    remaining = sample_unit_exponential(rng);
  }
}

}  // namespace

FreeFlight sample_free_flight(const TrackingMedium& tracking, const Ray& ray, double t_begin_m, double stretch,
                              std::size_t i, Pcg32& rng, std::size_t& majorant_violations) {
  const double ground_radius = tracking.medium->model().ground_radius_m;
  ShellTraversal walk(*tracking.majorants, ray, t_begin_m);
  ShellSegment segment;
  double remaining = sample_unit_exponential(rng);  // majorant optical depth to the next tentative collision
  while (walk.next(segment)) {
    const double majorant = tracking.majorants->majorant_m1(segment.shell, i);
    const double rate = stretch * majorant;  // s β̄ [m^-1]
    if (!(rate > 0.0)) continue;
    FreeFlight scattering;
    const bool crossed = cross_segment(segment, rate, remaining, rng, [&](double t) {
      const LocalCoefficients c = tracking.medium->coefficients(ray.radius_at(t) - ground_radius, i);
      if (c.extinction_m1 > majorant) ++majorant_violations;
      if (!(rng.uniform() * majorant < c.extinction_m1)) return true;  // a null collision
      scattering.event = FreeFlight::Event::Scattering;
      scattering.t_m = t;
      scattering.coefficients = c;
      return false;
    });
    if (!crossed) return scattering;
  }
  FreeFlight flight;
  if (walk.hit_ground()) {
    flight.event = FreeFlight::Event::Ground;
    flight.t_m = walk.ground_t_m();
  }
  return flight;
}

double ratio_tracking_transmittance(const TrackingMedium& tracking, const Ray& ray, double t_begin_m, double stretch,
                                    std::size_t i, Pcg32& rng, std::size_t& majorant_violations) {
  static constexpr double kRouletteThreshold = 1e-6;
  const double ground_radius = tracking.medium->model().ground_radius_m;
  ShellTraversal walk(*tracking.majorants, ray, t_begin_m);
  ShellSegment segment;
  double transmittance = 1.0;
  // Russian roulette on the running estimate: survive with probability T̂/threshold, then T̂ = threshold.
  auto roulette = [&]() {
    if (transmittance >= kRouletteThreshold) return true;
    if (!(rng.uniform() * kRouletteThreshold < transmittance)) return false;
    transmittance = kRouletteThreshold;
    return true;
  };
  double remaining = sample_unit_exponential(rng);  // residual-majorant optical depth to the next tentative collision
  while (walk.next(segment)) {
    const double majorant = tracking.majorants->majorant_m1(segment.shell, i);
    const double minorant = tracking.majorants->minorant_m1(segment.shell, i);
    transmittance *= std::exp(-stretch * minorant * (segment.end_t_m - segment.begin_t_m));  // the control
    if (!roulette()) return 0.0;
    const double residual_majorant = majorant - minorant;
    const double rate = stretch * residual_majorant;
    if (!(rate > 0.0)) continue;
    const bool crossed = cross_segment(segment, rate, remaining, rng, [&](double t) {
      const double extinction = tracking.medium->extinction_m1(ray.radius_at(t) - ground_radius, i);
      if (extinction > majorant) ++majorant_violations;
      transmittance *= 1.0 - (extinction - minorant) / residual_majorant;
      return roulette();
    });
    if (!crossed) return 0.0;
  }
  return walk.hit_ground() ? 0.0 : transmittance;
}

}  // namespace zenith::atmosphere::reference
