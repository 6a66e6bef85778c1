#include "validate/reference_comparison.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <numbers>
#include <vector>

#include "atmosphere/constants.h"
#include "atmosphere/reference/random.h"
#include "atmosphere/reference/single_scattering.h"
#include "core/parallel_for.h"
#include "core/strings.h"
#include "core/units.h"

namespace zenith::validate {
namespace {

using atmosphere::Spectrum;
using atmosphere::lut::kMaxChannels;
using atmosphere::reference::Pcg32;
using core::kPi;

double log_uniform(Pcg32& rng, double lo, double hi) {
  return std::exp(std::log(lo) + rng.uniform() * (std::log(hi) - std::log(lo)));
}

}  // namespace

Spectrum table_single_scattering(const atmosphere::AtmosphereModel& model, const atmosphere::lut::TableQueries& q,
                                 const Configuration& c) {
  const auto& g = q.tables().geometry;
  const std::size_t n = q.channels();
  Spectrum result(n, 0.0);
  // As TableQueries::sky_radiance: from outside, start where the ray enters the shell.
  Vec3 x = c.camera_m;
  double r = atmosphere::length(x);
  double rmu = atmosphere::dot(x, c.view);
  if (r > g.top_radius_m) {
    const double disc = rmu * rmu - r * r + g.top_radius_m * g.top_radius_m;
    if (disc < 0.0 || rmu >= 0.0) return result;
    x = x + c.view * (-rmu - std::sqrt(disc));
    r = g.top_radius_m;
    rmu = atmosphere::dot(x, c.view);
  }
  r = std::max(r, g.bottom_radius_m);
  const double mu = std::clamp(rmu / r, -1.0, 1.0);
  const double mu_s = std::clamp(atmosphere::dot(x, c.sun) / r, -1.0, 1.0);
  const double nu = std::clamp(atmosphere::dot(c.view, c.sun), -1.0, 1.0);
  const bool hits_ground = g.ray_hits_ground(r, mu);
  std::array<double, kMaxChannels> rayleigh{}, mie{};
  q.scattering_terms(r, mu, mu_s, nu, hits_ground, rayleigh.data(), mie.data(), nullptr);
  const double phase_r = model.rayleigh_phase_function(nu);
  for (std::size_t i = 0; i < n; ++i) result[i] = rayleigh[i] * phase_r + mie[i] * model.mie_phase(i, nu);
  if (hits_ground) {
    const double d = g.distance_to_bottom_m(r, mu);
    const Vec3 ground = x + c.view * d;
    const double mu_s_ground = std::clamp(atmosphere::dot(atmosphere::normalize(ground), c.sun), -1.0, 1.0);
    std::array<double, kMaxChannels> t{}, t_sun{};
    q.transmittance(r, mu, d, true, t.data());
    q.transmittance_to_sun(g.bottom_radius_m, mu_s_ground, t_sun.data());
    for (std::size_t i = 0; i < n; ++i)
      result[i] += t[i] * model.ground_albedo[i] / kPi * std::max(0.0, mu_s_ground) * t_sun[i];
  }
  return result;
}

Configuration configuration_in_region(Region region, double R, double R_top, std::uint64_t seed, std::uint64_t stream,
                                      std::uint64_t index) {
  Pcg32 rng = Pcg32::for_sample(seed ^ 0x5EFE2E4CEull, stream, index);
  const double H = R_top - R;
  const bool space = region == Region::space;
  const double altitude = space ? log_uniform(rng, H * (1.0 + 1e-9) + 1.0, kMaxCameraDistance_m - R)
                                : log_uniform(rng, kMinCameraAltitude_m, H);
  const double z = 1.0 - 2.0 * rng.uniform(), phi = 2.0 * kPi * rng.uniform();
  const double sz = std::sqrt(std::max(0.0, 1.0 - z * z));
  const Vec3 up{sz * std::cos(phi), sz * std::sin(phi), z};
  const double r = R + altitude;
  Configuration c;
  c.camera_m = r * up;
  const Vec3 tangent = tangent_at_azimuth(up, 2.0 * kPi * rng.uniform());
  const double beta = horizon_nadir_angle_rad(r, R);

  // Sun zenith at the camera.
  double sun_zenith = 0.0;
  switch (region) {
    case Region::night: sun_zenith = kTwilightEndZenith_rad + rng.uniform() * (kPi - kTwilightEndZenith_rad); break;
    case Region::twilight:
      sun_zenith = 0.5 * kPi + 1e-9 + rng.uniform() * (kTwilightEndZenith_rad - 0.5 * kPi - 2e-9);
      break;
    case Region::space: sun_zenith = std::acos(1.0 - 2.0 * rng.uniform()); break;
    default: sun_zenith = std::acos(std::max(1e-9, rng.uniform())); break;  // cos uniform in (0, 1]
  }
  c.sun = std::cos(sun_zenith) * up + std::sin(sun_zenith) * tangent_at_azimuth(up, 2.0 * kPi * rng.uniform());

  // View nadir angle.
  double nadir = 0.0;
  switch (region) {
    case Region::space: {
      const double p = R_top * rng.uniform();  // closest approach: the ray crosses the shell
      nadir = std::atan2(p, std::sqrt((r - p) * (r + p)));
      break;
    }
    case Region::horizon: {
      const double offset = log_uniform(rng, 1e-10, kHorizonBandHalfWidth_rad * (1.0 - 1e-9));
      nadir = beta + (rng.uniform() < 0.5 ? -offset : offset);
      break;
    }
    case Region::ground: nadir = rng.uniform() * (beta - kHorizonBandHalfWidth_rad); break;
    case Region::sky:
      nadir = beta + kHorizonBandHalfWidth_rad + rng.uniform() * (kPi - beta - kHorizonBandHalfWidth_rad);
      break;
    default: nadir = std::acos(1.0 - 2.0 * rng.uniform()); break;  // uniform on the sphere
  }
  c.view = direction_at_nadir_angle(up, tangent, nadir);
  return c;
}

void compare_with_reference(const atmosphere::AtmosphereModel& model, const atmosphere::lut::TableQueries& q,
                            const std::string& label, const ReferenceComparisonOptions& o, RegionTable& regions) {
  const auto& g = q.tables().geometry;
  const std::size_t per_region = o.samples_per_region, total = per_region * kRegionCount;
  struct Outcome {
    double error = 0.0;
    std::string where;
  };
  std::vector<Outcome> outcomes(total);
  atmosphere::reference::SingleScatteringOptions ss;
  ss.relative_tolerance = o.relative_tolerance;
  std::mutex progress_mutex;
  std::size_t done = 0;
  core::parallel_for(total, o.threads, [&](std::size_t k) {
    const Region region = kRegions[k / per_region];
    const Configuration c =
        configuration_in_region(region, g.bottom_radius_m, g.top_radius_m, o.seed, o.stream, k % per_region);
    const Spectrum tables = table_single_scattering(model, q, c);
    const auto ref = atmosphere::reference::single_scattering_radiance(model, c.camera_m, c.view, c.sun, ss);
    const Spectrum exact = ref.atmosphere_radiance + ref.ground_radiance;
    const double r = atmosphere::length(c.camera_m);
    outcomes[k].error = relative_error(tables.values().data(), exact.values().data(), q.channels(), o.floor_sr);
    outcomes[k].where =
        core::cat(label, " altitude ", r - g.bottom_radius_m, " m, view offset from horizon ",
                  offset_from_horizon_rad(c.camera_m, c.view, g.bottom_radius_m), " rad, sun zenith ",
                  std::acos(std::clamp(atmosphere::dot(c.camera_m, c.sun) / r, -1.0, 1.0)) * 180.0 / kPi, " deg, L1 ",
                  exact[exact.size() / 2], " (tables ", tables[tables.size() / 2], ") sr^-1 at ",
                  model.wavelengths_nm[exact.size() / 2], " nm");
    if (o.progress) {
      std::lock_guard lock(progress_mutex);
      o.progress(++done, total);
    }
  });
  for (std::size_t k = 0; k < total; ++k)
    regions[std::size_t(kRegions[k / per_region])].reference.add(outcomes[k].error, outcomes[k].where);
}

}  // namespace zenith::validate
