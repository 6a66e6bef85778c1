#pragma once
// The configurations of the numerical-stability stress, for one planet:
// a deterministic sweep over the corners, then random samples. No GL.
//
// Random sample i of seed S draws from its own PCG32 stream (S, model, i), so
// any sample can be regenerated alone and the run does not depend on the
// thread count. Distributions (each a mixture, to reach the hard corners often):
//  * camera altitude log-uniform in [1 m, 40 au], direction from the centre
//    uniform on the sphere;
//  * view: 35% within 1e-10…1e-2 rad of the geometric horizon (log-uniform
//    |δ|, either side; 1 in 8 of those exactly on it, δ = 0); 15% aimed at the
//    atmosphere shell (closest approach uniform in [0, 1.02 R_top], for cameras
//    outside it; else uniform); the rest uniform on the sphere;
//  * sun: 40% in twilight (zenith angle at the camera uniform in 90°–108°),
//    the rest uniform on the sphere (day and night);
//  * 30% of the samples also get a horizon pair: the same vertical plane at
//    δ = ±ε, ε log-uniform in [1e-6, 1e-2] rad.
#include <cstdint>
#include <optional>
#include <vector>

#include "validate/stress_geometry.h"

namespace zenith::validate {

struct HorizonPair {
  Vec3 above{}, below{};  ///< view directions at δ = +ε and −ε
  double epsilon_rad;
};

struct StressSample {
  Configuration configuration;
  std::optional<HorizonPair> horizon_pair;
};

class StressSampler {
 public:
  StressSampler(double ground_radius_m, double top_radius_m, std::uint64_t seed, std::uint64_t stream);

  /// The deterministic sweep: altitudes {1 m, 10 m, 1 km, R_top − R − 1 m, top, top + 1 m,
  /// 1000 km above the top, 1e9 m, 40 au} × horizon offsets {0, ±1e-6, ±1e-3, ±0.1 rad, zenith, nadir}
  /// × sun zenith {0°, 45°, 89°, 90°, 91°, 96°, 102°, 108°, 120°, 180°} × sun azimuth
  /// relative to the view {0°, 90°, 180°}; each with a horizon pair at ε = 1e-6.
  std::vector<StressSample> sweep() const;
  /// Random sample `index` (see above).
  StressSample random(std::uint64_t index) const;

 private:
  double ground_radius_m_, top_radius_m_;
  std::uint64_t seed_, stream_;
};

}  // namespace zenith::validate
