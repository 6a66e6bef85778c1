#include "validate/cpu_stress.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <vector>

#include "atmosphere/reference/geometry.h"
#include "core/parallel_for.h"
#include "core/strings.h"
#include "core/units.h"

namespace zenith::validate {
namespace {

using atmosphere::lut::kMaxChannels;
constexpr std::size_t kChunk = 2048;  ///< configurations per work item

std::string describe(const std::string& label, const Configuration& c, double ground_radius_m, double epsilon_rad) {
  const double r = atmosphere::length(c.camera_m);
  const double sun_zenith_deg =
      std::acos(std::clamp(atmosphere::dot(c.camera_m, c.sun) / r, -1.0, 1.0)) * 180.0 / core::kPi;
  return core::cat(label, " altitude ", r - ground_radius_m, " m, sun zenith ", sun_zenith_deg, " deg, eps ",
                   epsilon_rad, " rad");
}

}  // namespace

void evaluate_configuration(const atmosphere::lut::TableQueries& q, const StressSample& sample, double floor_sr,
                            const std::string& label, RegionStatistics& into) {
  const auto& g = q.tables().geometry;
  const std::size_t n = q.channels();
  const Configuration& c = sample.configuration;
  ++into.samples;

  const atmosphere::Spectrum radiance = q.sky_radiance(c.camera_m, c.view, c.sun);
  for (double v : radiance) into.health.check(v);

  const atmosphere::reference::Ray ray(c.camera_m, c.view);
  const auto interval = atmosphere::reference::atmosphere_interval(ray, g.bottom_radius_m, g.top_radius_m);
  std::array<double, kMaxChannels> out{};
  if (interval.intersects) {
    const Vec3 start = ray.point_at(interval.begin_t_m);
    const double r = atmosphere::length(start);
    q.transmittance(r, std::clamp(atmosphere::dot(start, ray.direction()) / r, -1.0, 1.0),
                    interval.end_t_m - interval.begin_t_m, interval.ends_on_ground, out.data());
    for (std::size_t i = 0; i < n; ++i) into.health.check(out[i], true);
  }

  const double r_camera = atmosphere::length(c.camera_m);
  q.irradiance(std::clamp(r_camera, g.bottom_radius_m, g.top_radius_m),
               std::clamp(atmosphere::dot(c.camera_m, c.sun) / r_camera, -1.0, 1.0), true, out.data());
  for (std::size_t i = 0; i < n; ++i) into.health.check(out[i]);

  // From space a pair at ±ε spans the whole limb (at 40 au the planet is 1e-6 rad
  // across): the jump is only measured for cameras inside the atmosphere.
  if (sample.horizon_pair && atmosphere::length(c.camera_m) <= g.top_radius_m) {
    const HorizonPair& p = *sample.horizon_pair;
    const atmosphere::Spectrum above = q.sky_radiance(c.camera_m, p.above, c.sun);
    const atmosphere::Spectrum below = q.sky_radiance(c.camera_m, p.below, c.sun);
    double jump = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      into.health.check(above[i]);
      into.health.check(below[i]);
      const double j = std::abs(above[i] - below[i]) / std::max({above[i], below[i], floor_sr});
      if (!(j <= jump)) jump = std::isnan(j) ? std::numeric_limits<double>::infinity() : j;
    }
    if (jump > into.horizon_jump.value || into.horizon_jump.where.empty())
      into.horizon_jump.add(jump, describe(label, c, g.bottom_radius_m, p.epsilon_rad));
  }
}

CpuStressResult run_cpu_stress(const atmosphere::lut::TableQueries& q, const std::string& label,
                               const CpuStressOptions& o) {
  const auto& g = q.tables().geometry;
  const StressSampler sampler(g.bottom_radius_m, g.top_radius_m, o.seed, o.stream);
  const std::vector<StressSample> sweep = o.sweep ? sampler.sweep() : std::vector<StressSample>{};
  const std::size_t total = sweep.size() + o.random_samples;
  const std::size_t chunks = (total + kChunk - 1) / kChunk;
  std::vector<RegionTable> per_chunk(chunks);
  std::mutex progress_mutex;
  std::size_t done = 0;
  core::parallel_for(chunks, o.threads, [&](std::size_t chunk) {
    RegionTable& regions = per_chunk[chunk];
    const std::size_t end = std::min(total, (chunk + 1) * kChunk);
    for (std::size_t i = chunk * kChunk; i < end; ++i) {
      const StressSample s = i < sweep.size() ? sweep[i] : sampler.random(i - sweep.size());
      const Region region = classify(s.configuration, g.bottom_radius_m, g.top_radius_m);
      evaluate_configuration(q, s, o.floor_sr, label, regions[std::size_t(region)]);
    }
    if (o.progress) {
      std::lock_guard lock(progress_mutex);
      done += end - chunk * kChunk;
      o.progress(done);
    }
  });
  CpuStressResult result;
  result.samples = total;
  for (const RegionTable& t : per_chunk) merge(result.regions, t);
  return result;
}

}  // namespace zenith::validate
