#include "validate/stress_sampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "atmosphere/reference/random.h"
#include "core/units.h"

namespace zenith::validate {
namespace {

using atmosphere::reference::Pcg32;
using core::kDeg;
using core::kPi;

double log_uniform(Pcg32& rng, double lo, double hi) {
  return std::exp(std::log(lo) + rng.uniform() * (std::log(hi) - std::log(lo)));
}

Vec3 uniform_sphere(Pcg32& rng) {
  const double z = 1.0 - 2.0 * rng.uniform(), phi = 2.0 * kPi * rng.uniform();
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

/// The sun at zenith angle z at the camera, azimuth φ about its vertical.
Vec3 sun_at(const Vec3& up, double zenith_rad, double azimuth_rad) {
  return std::cos(zenith_rad) * up + std::sin(zenith_rad) * tangent_at_azimuth(up, azimuth_rad);
}

}  // namespace

StressSampler::StressSampler(double ground_radius_m, double top_radius_m, std::uint64_t seed, std::uint64_t stream)
    : ground_radius_m_(ground_radius_m), top_radius_m_(top_radius_m), seed_(seed), stream_(stream) {}

std::vector<StressSample> StressSampler::sweep() const {
  const double R = ground_radius_m_, H = top_radius_m_ - ground_radius_m_;
  const double altitudes_m[] = {1.0,     10.0, std::min(1e3, 0.5 * H),  H - 1.0, H, H + 1.0,
                                H + 1e6, 1e9,  kMaxCameraDistance_m - R};
  const double offsets_rad[] = {0.0, 1e-6, -1e-6, 1e-3, -1e-3, 0.1, -0.1};
  const double sun_zeniths_deg[] = {0.0, 45.0, 89.0, 90.0, 91.0, 96.0, 102.0, 108.0, 120.0, 180.0};
  const double sun_azimuths_deg[] = {0.0, 90.0, 180.0};
  std::vector<StressSample> out;
  const Vec3 up{0.0, 0.0, 1.0};
  for (double h : altitudes_m) {
    const Vec3 camera = (R + h) * up;
    const Vec3 tangent = tangent_at_azimuth(up, 0.0);
    std::vector<Vec3> views;
    for (double o : offsets_rad) views.push_back(horizon_direction(camera, tangent, R, o));
    views.push_back(up);
    views.push_back(-up);
    for (const Vec3& view : views)
      for (double z : sun_zeniths_deg)
        for (double a : sun_azimuths_deg) {
          StressSample s;
          s.configuration = {camera, view, sun_at(up, z * kDeg, a * kDeg)};
          s.horizon_pair = HorizonPair{horizon_direction(camera, tangent, R, 1e-6),
                                       horizon_direction(camera, tangent, R, -1e-6), 1e-6};
          out.push_back(s);
        }
  }
  return out;
}

StressSample StressSampler::random(std::uint64_t index) const {
  Pcg32 rng = Pcg32::for_sample(seed_, stream_, index);
  const double R = ground_radius_m_;
  StressSample s;
  Configuration& c = s.configuration;
  const double altitude_m = log_uniform(rng, kMinCameraAltitude_m, kMaxCameraDistance_m - R);
  const Vec3 up = uniform_sphere(rng);
  c.camera_m = (R + altitude_m) * up;
  const double r = R + altitude_m;
  const Vec3 tangent = tangent_at_azimuth(up, 2.0 * kPi * rng.uniform());

  const double view_kind = rng.uniform();
  if (view_kind < 0.35) {
    const double magnitude = log_uniform(rng, 1e-10, 1e-2);
    const double offset = rng.uniform() < 0.125 ? 0.0 : (rng.uniform() < 0.5 ? -magnitude : magnitude);
    c.view = horizon_direction(c.camera_m, tangent, R, offset);
  } else if (view_kind < 0.5 && r > top_radius_m_) {
    // Closest approach p: nadir angle asin(p/r), taken as atan2 for accuracy at 40 au.
    const double p = std::min(1.02 * top_radius_m_ * rng.uniform(), r);
    c.view = direction_at_nadir_angle(up, tangent, std::atan2(p, std::sqrt((r - p) * (r + p))));
  } else {
    c.view = uniform_sphere(rng);
  }

  if (rng.uniform() < 0.4) {
    c.sun = sun_at(up, (90.0 + 18.0 * rng.uniform()) * kDeg, 2.0 * kPi * rng.uniform());
  } else {
    c.sun = uniform_sphere(rng);
  }

  if (rng.uniform() < 0.3) {
    const double eps = log_uniform(rng, 1e-6, 1e-2);
    const Vec3 pair_tangent = tangent_at_azimuth(up, 2.0 * kPi * rng.uniform());
    s.horizon_pair = HorizonPair{horizon_direction(c.camera_m, pair_tangent, R, eps),
                                 horizon_direction(c.camera_m, pair_tangent, R, -eps), eps};
  }
  return s;
}

}  // namespace zenith::validate
