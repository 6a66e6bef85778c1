#include "render/frame/frame_constants.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "core/units.h"
#include "render/frame/frame_conditions.h"
#include "render/lut/shader_model.h"
#include "scene/sun_disc.h"

namespace zenith::render {

FrameConstants compute_frame_constants(const scene::Scene& scene, const FrameSky& sky,
                                       const warp::Projection& projection, image::ColourMapping colour,
                                       bool limb_darkening, bool moon, bool eclipses) {
  FrameConstants f;
  f.n = scene.wavelengths_nm.size();
  f.groups = (f.n + kWavelengthLanes - 1) / kWavelengthLanes;
  f.camera_to_world = glm::mat3_cast(glm::normalize(scene.camera.orientation));
  f.world_to_camera = glm::transpose(f.camera_to_world);
  f.sun = glm::normalize(scene.sun.direction);
  f.sun_radius = scene.sun.angular_radius_rad;
  // The worst-case footprint over the image bounds culling and decides
  // ALBEDO_LOD0 (the shaders take each pixel's own footprint for the level of
  // detail, frame.glsl); the sun is sized from the footprint where it lands (a
  // warp mesh's worst case can be tens of times the local one).
  f.pixel_angle = projection.max_pixel_angle_rad();
  f.sun_camera = f.world_to_camera * f.sun;
  f.sun_pixel_angle = projection.pixel_angle_rad_at(f.sun_camera);

  f.rgb_weights = image::spectral_to_rgb_weights(scene.wavelengths_nm, colour);
  f.albedo_weights = image::rgb_to_spectral_weights(scene.wavelengths_nm, colour);
  // A sun resolved by the pixels is drawn as its limb-darkened disc; one
  // under 1.5 pixels in radius as a Gaussian of σ = 0.7 pixel carrying the
  // same irradiance (exp(−θ²/2σ²) E / 2πσ²): a disc sampled at pixel centres
  // would flicker and lose or gain light with its sub-pixel position.
  f.sun_point_sigma = f.sun_radius < 1.5 * f.sun_pixel_angle ? 0.7 * f.sun_pixel_angle : 0.0;
  if (moon_can_eclipse_the_sun(scene, moon, eclipses)) f.occulter = sun_occulter(scene, sky, limb_darkening);
  f.sun_centre.resize(f.n);
  f.sun_limb.resize(f.n);
  f.shadow_limb.resize(f.n);
  for (std::size_t i = 0; i < f.n; ++i) {
    const double e = scene.sun.irradiance_W_m2_nm[i];
    if (f.sun_point_sigma > 0.0)  // the Gaussian carries the light the Moon leaves of the disc
      f.sun_centre[i] = e * (f.occulter.any() ? f.occulter.uncovered[i] : 1.0) /
                        (2.0 * core::kPi * f.sun_point_sigma * f.sun_point_sigma);
    else
      f.sun_centre[i] = limb_darkening ? scene::disc_centre_radiance(e, f.sun_radius, scene.wavelengths_nm[i])
                                       : scene::uniform_disc_radiance(e, f.sun_radius);
    if (limb_darkening) f.shadow_limb[i] = atmosphere::solar_limb_darkening(scene.wavelengths_nm[i]);
    if (limb_darkening && f.sun_point_sigma == 0.0) f.sun_limb[i] = f.shadow_limb[i];
  }
  f.shadow_limb_channels = shadow_limb_rgb(f, scene);
  return f;
}

std::array<float, 9> direct_light_colour_matrix(const FrameConstants& frame, const scene::Scene& scene,
                                                const std::vector<double>& light_left) {
  const double exposure = scene.camera.exposure;
  std::array<float, 9> rgb_from_albedo{};  // column-major: column = albedo channel
  for (int out = 0; out < 3; ++out)
    for (int in = 0; in < 3; ++in) {
      double m = 0.0;
      for (std::size_t i = 0; i < frame.n; ++i)
        m += frame.rgb_weights[i][static_cast<std::size_t>(out)] * scene.sun.irradiance_W_m2_nm[i] *
             (light_left.empty() ? 1.0 : light_left[i]) * frame.albedo_weights[i][static_cast<std::size_t>(in)];
      rgb_from_albedo[static_cast<std::size_t>(in * 3 + out)] = static_cast<float>(exposure * m);
    }
  return rgb_from_albedo;
}

std::vector<double> shadow_limb_over_mean(const FrameConstants& frame, std::size_t k) {
  std::vector<double> b;
  for (const atmosphere::LimbDarkening& law : frame.shadow_limb)
    b.push_back(law.coefficients[k] / law.mean_over_centre());
  return b;
}

std::vector<std::array<float, 4>> shadow_limb_rgb(const FrameConstants& frame, const scene::Scene& scene) {
  const std::size_t terms = std::tuple_size_v<decltype(atmosphere::LimbDarkening::coefficients)>;
  std::vector<std::array<float, 4>> out(terms, {0.0f, 0.0f, 0.0f, 0.0f});
  std::vector<std::vector<double>> b_k;
  for (std::size_t k = 0; k < terms; ++k) b_k.push_back(shadow_limb_over_mean(frame, k));
  for (std::size_t c = 0; c < 3; ++c) {
    double weight = 0.0;
    for (std::size_t i = 0; i < frame.n; ++i) weight += frame.rgb_weights[i][c] * scene.sun.irradiance_W_m2_nm[i];
    for (std::size_t k = 0; k < terms; ++k) {
      const std::vector<double>& b = b_k[k];
      double sum = 0.0;
      for (std::size_t i = 0; i < frame.n; ++i) sum += frame.rgb_weights[i][c] * scene.sun.irradiance_W_m2_nm[i] * b[i];
      // A channel the sun does not reach (weight 0) keeps the uniform disc's share.
      out[k][c] = static_cast<float>(weight != 0.0 ? sum / weight : (k == 0 ? 1.0 : 0.0));
    }
  }
  return out;
}

double sun_reach_rad(const FrameConstants& frame) {
  if (frame.sun_point_sigma > 0.0) return std::min(core::kPi / 2, 6.0 * frame.sun_point_sigma);
  // In an eclipse the corona reaches kCoronaOuterRadii solar radii.
  const double drawn = frame.occulter.any() ? kCoronaOuterRadii * frame.sun_radius : frame.sun_radius;
  return std::min(core::kPi / 2, drawn + frame.sun_pixel_angle);
}

}  // namespace zenith::render
