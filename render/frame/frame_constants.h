#pragma once
// A frame's constants, in double on the CPU before anything reaches the GPU
// (render/renderer.cpp): the camera and the sun in the world and the camera
// frame, the pixels' footprints, the colour weights, the sun's centre radiance
// and limb-darkening exponents per wavelength, and what direct_light.comp
// gets from them. No GL.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "atmosphere/solar_limb_darkening.h"
#include "image/colour.h"
#include "render/frame/sun_occulter.h"
#include "scene/scene.h"
#include "warp/projection.h"

namespace zenith::render {

struct FrameConstants {
  std::size_t n = 0;       ///< wavelengths
  std::size_t groups = 0;  ///< groups of 4 wavelengths (kWavelengthLanes)
  glm::dmat3 camera_to_world{1.0}, world_to_camera{1.0};
  glm::dvec3 sun{0.0}, sun_camera{0.0};               ///< unit direction to the sun: world, camera frame
  double sun_radius = 0.0;                            ///< the disc's angular radius [rad]
  double pixel_angle = 0.0;                           ///< the projection's largest pixel angle [rad]
  double sun_pixel_angle = 0.0;                       ///< the pixel angle where the sun lands [rad]
  double sun_point_sigma = 0.0;                       ///< > 0: the sun drawn as a Gaussian of this σ [rad]
  std::vector<std::array<double, 3>> rgb_weights;     ///< spectral → RGB, per wavelength
  std::vector<std::array<double, 3>> albedo_weights;  ///< the albedo's RGB → reflectance, per wavelength
  std::vector<double> sun_centre;  ///< the disc's centre radiance (or the Gaussian's peak) per wavelength
  /// The drawn sun's limb darkening per wavelength: uniform without limb darkening or for a Gaussian point.
  std::vector<atmosphere::LimbDarkening> sun_limb;
  /// The sun's limb darkening behind the bodies' shadows, per wavelength: the
  /// disc the shadow covers, however it is drawn (uniform without limb darkening).
  std::vector<atmosphere::LimbDarkening> shadow_limb;
  std::vector<std::array<float, 4>> shadow_limb_channels;  ///< shadow_limb_rgb(): frame.glsl's shadow_limb_rgb[]
  SunOcculter occulter;  ///< the Moon in front of the sun (render/frame/sun_occulter.h)
};

/// The constants of a frame of `scene` through `projection` with the colour
/// mapping, the sun's limb darkening, the Moon and the bodies' shadows
/// (RenderOptions::colour, limb_darkening, night_sky.moon: the Moon's disc
/// masks the sun's in a solar eclipse; atmosphere.eclipses: a body's shadow
/// falls on another and its air).
FrameConstants compute_frame_constants(const scene::Scene& scene, const FrameSky& sky,
                                       const warp::Projection& projection, image::ColourMapping colour,
                                       bool limb_darkening, bool moon, bool eclipses);

/// direct_light.comp's colour matrix, column-major (column = albedo channel):
/// a body lit by the sun alone is rgb = (cos i V / π) M a with
/// M = exposure Σ_λ w(λ) E(λ) f(λ)ᵀ (w: the spectral → RGB weights, f: the
/// albedo's RGB → reflectance weights). With `light_left` (per wavelength,
/// E / E_sun where another body's air shadows the sun: render/frame/air_shadows.h)
/// E(λ) is that share of the sun's; empty: the whole sun.
std::array<float, 9> direct_light_colour_matrix(const FrameConstants& frame, const scene::Scene& scene,
                                                const std::vector<double>& light_left = {});

/// frame.glsl's shadow_limb_rgb[k] for direct_light.comp: per channel c,
/// B_ck = Σ_λ w_c(λ) E(λ) b_k(λ) / Σ_λ w_c(λ) E(λ), with b_k = a_k / m each
/// wavelength's law over its disc's mean (shadow_limb): a grey surface in a
/// body's shadow keeps 1 − Σ_k B_ck J_k of channel c's light, J_k the moments
/// of the disc the body covers (frame.glsl's covered_moments).
std::vector<std::array<float, 4>> shadow_limb_rgb(const FrameConstants& frame, const scene::Scene& scene);

/// b_k = a_k / m of each wavelength's shadow_limb law: frame.glsl's shadow_limb_lanes[k].
std::vector<double> shadow_limb_over_mean(const FrameConstants& frame, std::size_t k);

/// Where the sun can be drawn: a cone of the disc's radius (in an eclipse, the
/// corona's) plus a pixel, or 6σ of the Gaussian, at most π/2.
double sun_reach_rad(const FrameConstants& frame);

}  // namespace zenith::render
