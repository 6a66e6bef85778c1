#include "render/frame/star_visibility.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "astro/scintillation.h"
#include "atmosphere/air_mass.h"
#include "core/units.h"
#include "image/tone_mapping.h"

namespace zenith::render {
namespace {

/// The pass's atmosphere that holds the camera and surrounds the site body
/// (`site`): every ray from the camera that meets no body reads its sky at the
/// camera from the 4D tables' sky half. Null where there is none.
const AtmospherePass* sky_at_camera(const FrameState& frame, std::size_t site) {
  for (const AtmospherePass& pass : frame.passes)
    if (pass.gpu && static_cast<std::size_t>(pass.body) == site && pass.distance_m <= pass.gpu->top_radius_m())
      return &pass;
  return nullptr;
}

}  // namespace

bool invisible_change(double background, double delta, bool may_subtract) {
  const double d = std::abs(delta);
  const double lowest = may_subtract ? std::max(background - d, 0.0) : std::max(background, 0.0);
  return image::display_code_slope_bound(lowest) * d < kInvisibleCodeChange;
}

double smallest_pixel_solid_angle_sr(const warp::Projection& projection) {
  double smallest = 0.0;
  for (int j = 0; j <= 32; ++j)
    for (int i = 0; i <= 32; ++i) {
      const double omega = pixel_solid_angle_sr(projection, (projection.width() - 1) * i / 32.0 + 0.5,
                                                (projection.height() - 1) * j / 32.0 + 0.5);
      if (omega > 0.0 && (smallest == 0.0 || omega < smallest)) smallest = omega;
    }
  return 0.5 * smallest;
}

StarVisibility star_visibility(const FrameState& frame, StarField& field, const StarFrame& sky,
                               double years_from_j2000) {
  StarVisibility out;
  const scene::Scene& scene = frame.scene;
  const std::size_t n = sky.rgb_weights.size();
  const std::size_t site = scene.sky_clock ? scene.sky_clock->body : 0;
  const scene::Body& planet = scene.bodies.at(site);
  const glm::dvec3 up = glm::normalize(sky.camera_m - planet.position_m);
  const double r = glm::length(sky.camera_m - planet.position_m);

  // A pixel gathers the stars whose 2 × 2 splat reaches its centre: within
  // √2 pixel spacings, two pixel angles with the margin. On the catalogue's
  // places the cluster is widened by half for refraction's compression of
  // the sky near the horizon (at most a fifth on Earth) and by 1′ for the
  // aberration's difference across it.
  const double reach = 2.0 * frame.projection.max_pixel_angle_rad();
  const std::vector<double>& gathered =
      field.brightest_cluster_irradiance(1.5 * reach + core::kDeg / 60.0, years_from_j2000);
  const double omega = smallest_pixel_solid_angle_sr(frame.projection);
  if (!(omega > 0.0)) return out;  // no pixel to bound: the pass runs

  // The most a star's light can keep through the air the camera is in and
  // its twinkling, per wavelength: T(r, μ) grows with the elevation and the
  // twinkling's variance falls with it (X³, capped at 1), so over each degree
  // [e_k, e_k+1] of apparent elevation T ≤ T(e_k+1) and the factor ≤ its value
  // at e_k with the largest normal any draw gives; without twinkling T at the
  // zenith. Without such air, 1 (and the largest factor at the horizon).
  const StarAtmosphere* air = nullptr;
  for (const StarAtmosphere& a : sky.atmospheres)
    if (a.centre_m == planet.position_m && r <= a.top_radius_m) air = &a;
  std::vector<double> kept(std::max<std::size_t>(n, 8), 1.0), t(kept.size(), 1.0);
  if (air) star_transmittance(*air, sky.camera_m, up, kept.data());
  if (sky.scintillation) {
    const double g = field.largest_scintillation_normal(sky.scintillation_interval);
    const auto factor = [&](double elevation_deg) {
      const double variance =
          astro::scintillation_variance(*sky.scintillation, atmosphere::pickering_air_mass(elevation_deg),
                                        sky.observer_altitude_m, sky.ground_refractivity);
      return astro::scintillation_factor(variance, g);
    };
    glm::dvec3 level = glm::cross(up, glm::dvec3(1, 0, 0));
    if (glm::length(level) < 0.1) level = glm::cross(up, glm::dvec3(0, 1, 0));
    level = glm::normalize(level);
    std::fill(kept.begin(), kept.end(), 0.0);
    for (int e = 0; e < 90; ++e) {
      const double above = (e + 1) * core::kDeg;
      if (air) star_transmittance(*air, sky.camera_m, std::cos(above) * level + std::sin(above) * up, t.data());
      const double f = factor(e);
      for (std::size_t i = 0; i < kept.size(); ++i) kept[i] = std::max(kept[i], t[i] * f);
    }
  }

  // The sky's floor B from the tables, where it applies.
  bool weights_non_negative = true;
  for (const auto& w : sky.rgb_weights) weights_non_negative &= w[0] >= 0.0 && w[1] >= 0.0 && w[2] >= 0.0;
  const AtmospherePass* pass = weights_non_negative ? sky_at_camera(frame, site) : nullptr;
  if (pass) {
    const double radius = std::max(pass->distance_m, pass->gpu->ground_radius_m());
    const std::vector<double> k = pass->gpu->radiance_floor().radiance_per_irradiance(glm::dot(up, frame.sun), radius);
    for (std::size_t i = 0; i < n && i < k.size() && i < scene.sun.irradiance_W_m2_nm.size(); ++i)
      for (std::size_t c = 0; c < 3; ++c)
        out.sky_floor[c] += sky.exposure * sky.rgb_weights[i][c] * scene.sun.irradiance_W_m2_nm[i] * k[i];
  }

  const double scale = sky.exposure / omega;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < n && i < gathered.size(); ++i)
      out.sky_peak[c] += scale * std::abs(sky.rgb_weights[i][c]) * gathered[i] * kept[i];
  double weight = 0.0;
  for (const auto& w : sky.rgb_weights) weight += std::max({std::abs(w[0]), std::abs(w[1]), std::abs(w[2])});
  const double twinkle = sky.scintillation ? astro::scintillation_factor(1.0, astro::kLargestScintillationNormal) : 1.0;
  out.black_sky_peak = sky.exposure * field.brightest_irradiance() * weight * twinkle / omega;
  out.could_show = false;
  for (std::size_t c = 0; c < 3; ++c)
    out.could_show = out.could_show || !invisible_change(out.sky_floor[c], out.sky_peak[c], !weights_non_negative);
  return out;
}

}  // namespace zenith::render
