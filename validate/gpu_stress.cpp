#include "validate/gpu_stress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "atmosphere/photometry.h"
#include "core/units.h"
#include "validate/stress_geometry.h"
#include "warp/fisheye_projection.h"
#include "warp/planar_projection.h"

namespace zenith::validate {
namespace {

using core::kDeg;

/// Camera frame (+x right, +y up, −z forward) → world, looking along `forward` with `up` above.
glm::dquat look_rotation(const glm::dvec3& forward, const glm::dvec3& up) {
  const glm::dvec3 z = -glm::normalize(forward);
  const glm::dvec3 x = glm::normalize(glm::cross(up, z));
  const glm::dvec3 y = glm::cross(z, x);
  return glm::quat_cast(glm::dmat3(x, y, z));
}

}  // namespace

std::vector<GpuFrameResult> run_gpu_stress(render::Renderer& renderer, const std::string& label,
                                           const atmosphere::LoadedAtmosphere& atmosphere,
                                           const atmosphere::lut::TableQueries& queries, const GpuStressOptions& o) {
  const atmosphere::AtmosphereModel& m = atmosphere.model;
  const double R = m.ground_radius_m, H = m.atmosphere_height_m();
  scene::Scene s;
  s.name = label;
  s.wavelengths_nm = m.wavelengths_nm;
  scene::Body planet;
  planet.name = "planet";
  planet.radius_m = R;
  planet.albedo.colour_linear_rgb = {0.1, 0.1, 0.1};
  planet.atmosphere = scene::BodyAtmosphere{label, atmosphere};
  s.bodies.push_back(planet);
  s.sun.angular_radius_rad = 4.65e-3;
  for (double w : s.wavelengths_nm) s.sun.irradiance_W_m2_nm.push_back(atmosphere::solar_irradiance_W_m2_nm(w));
  s.camera.exposure = 1.0;

  const Vec3 up{0.0, 0.0, 1.0};
  const Vec3 east = tangent_at_azimuth(up, 0.0);               // the sun's azimuth
  const Vec3 north = tangent_at_azimuth(up, 0.5 * core::kPi);  // the view's azimuth
  std::vector<GpuFrameResult> results;
  for (double altitude : {1.0, 0.5 * H, H + 1e6, kMaxCameraDistance_m - R}) {
    const double r = R + altitude;
    const Vec3 camera = r * up;
    s.camera.position_m = camera;
    const bool outside = r > m.top_radius_m;
    for (double sun_zenith_deg : {30.0, 89.5, 96.0, 104.0, 150.0}) {
      const Vec3 sun = std::cos(sun_zenith_deg * kDeg) * up + std::sin(sun_zenith_deg * kDeg) * east;
      s.sun.direction = sun;
      for (const char* view : {"horizon", "wide"}) {
        GpuFrameResult f;
        f.model = label;
        f.view = view;
        f.altitude_m = altitude;
        f.sun_zenith_deg = sun_zenith_deg;
        std::unique_ptr<warp::Projection> projection;
        const double planet_angular_radius = std::asin(std::min(1.0, R / r));
        const bool horizon = f.view == "horizon";
        if (horizon) {
          const Vec3 forward = horizon_direction(camera, north, R, 0.0);
          const Vec3 frame_up = atmosphere::normalize(atmosphere::cross(atmosphere::cross(forward, up), forward));
          s.camera.orientation = look_rotation(forward, frame_up);
          const double half_deg = outside ? std::max(0.25 * planet_angular_radius, 2e-7) / kDeg : 0.5;
          const double half_width_deg = half_deg / 16.0;
          projection = std::make_unique<warp::PlanarProjection>(
              4, o.size_px, warp::PlanarFrustum{-half_width_deg, half_width_deg, -half_deg, half_deg});
        } else if (outside) {
          s.camera.orientation = look_rotation(-up, east);
          const double half_deg = std::min(80.0, 1.5 * std::asin(std::min(1.0, m.top_radius_m / r)) / kDeg);
          projection = std::make_unique<warp::PlanarProjection>(
              o.size_px, o.size_px, warp::PlanarFrustum{-half_deg, half_deg, -half_deg, half_deg});
        } else {
          s.camera.orientation = look_rotation(north, up);
          warp::FisheyeParameters p;
          p.fov_deg = 220.0;
          p.tilt_deg = 90.0;
          projection = std::make_unique<warp::FisheyeProjection>(o.size_px, o.size_px, p);
        }
        const auto start = std::chrono::steady_clock::now();
        const std::vector<float> image = renderer.render_image(s, *projection);
        f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        for (float v : image) {
          ++f.values;
          if (std::isnan(v))
            ++f.nan;
          else if (std::isinf(v))
            ++f.inf;
          else if (v < 0.0f)
            ++f.negative;
        }
        const int w = projection->width(), h = projection->height();
        auto value = [&](int x, int y, std::size_t c) {
          return double(image[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3 + c]);
        };
        // Direct colour mapping: channel c is the radiance at wavelength c (longest first, as the model's).
        const double floor =
            o.floor_sr * *std::min_element(s.sun.irradiance_W_m2_nm.begin(), s.sun.irradiance_W_m2_nm.end());
        if (horizon && !outside) {  // from space the frame's top is black space: a step of 1 by construction
          for (int y = 1; y < h; ++y)
            for (std::size_t c = 0; c < 3; ++c) {
              const double a = value(w / 2, y - 1, c), b = value(w / 2, y, c);
              const double jump = std::abs(a - b) / std::max({a, b, floor});
              if (jump > f.max_row_jump || std::isnan(jump)) {
                f.max_row_jump = std::isnan(jump) ? std::numeric_limits<double>::infinity() : jump;
                f.max_row_jump_row = y;
              }
            }
        }
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const auto ray_camera = projection->ray(x + 0.5, y + 0.5);
            if (!ray_camera) continue;
            const Vec3 ray = atmosphere::normalize(s.camera.orientation * *ray_camera);
            // Away from the sun's disc, which a pixel larger than it spreads over the pixel.
            if (atmosphere::dot(ray, sun) > std::cos(std::max(1.0 * kDeg, 3.0 * projection->max_pixel_angle_rad())))
              continue;
            if (offset_from_horizon_rad(camera, ray, R) <= 0.0) continue;  // the ground: the body's albedo
            const atmosphere::Spectrum expected = queries.sky_radiance(camera, ray, sun);
            for (std::size_t c = 0; c < 3 && c < expected.size(); ++c) {
              const double e = expected[c] * s.sun.irradiance_W_m2_nm[c] * s.camera.exposure;
              const double d = std::abs(value(x, y, c) - e) / std::max(e, floor);
              if (!(d <= f.max_cpu_difference)) f.max_cpu_difference = std::isnan(d) ? 1e300 : d;
            }
            ++f.compared;
          }
        results.push_back(f);
      }
    }
  }
  return results;
}

}  // namespace zenith::validate
