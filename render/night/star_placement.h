#pragma once
// Stars as light (docs/night-sky.md, "Rendering the night
// sky"): the catalogue's stars (render/night/star_field.h) placed in a frame, on the CPU in double, as
// point sources of flux. No GL: render/night/star_pass.h draws what this
// computes.
//
// For each star, per frame:
//   1. its direction: ERFA's geometric place at an epoch (astro/sky_positions.h,
//      recomputed when the sky clock moves more than kStarEpochSpan_s from it)
//      turned about the celestial pole by the Earth's rotation since then,
//      ω = 2π · 1.00273781191135448 / 86400 s⁻¹ (the Earth rotation angle's
//      rate, IAU 2000 B1.8); lifted by the model's own refraction
//      (astro/refraction.h) where the camera stands in the site body's air;
//   2. its flux above the atmosphere E(λ) [W m⁻² nm⁻¹] (astro/star_photometry.h:
//      a blackbody of Ballesteros' temperature for B−V scaled to V);
//   3. attenuated along its line of sight by every atmosphere it crosses, from
//      each one's transmittance table T(r, μ) (the same table the sky is drawn
//      with: Mars's dust dims stars as it dims the Sun), and hidden by every
//      body it meets (the ground, a moon);
//   4. where it lands: the projection's pixel() of its camera-frame direction
//      (any projection: fisheye, planar, a warp mesh's ray table), and the
//      solid angle Ω of a pixel there, |∂d/∂x × ∂d/∂y| from the projection's own
//      rays half a pixel either side;
//   5. its colour: rgb = exposure · Σ_λ w(λ) E(λ) T(λ) / Ω (w: the frame's
//      spectral → linear sRGB weights): the radiance a pixel of solid angle Ω
//      holding all the star's flux has. The pass spreads it bilinearly over the
//      2 × 2 pixels around its position (weights summing to 1), so the image
//      holds Σ L Ω = E: the same energy on a dome master, through a warp mesh
//      and on a flat screen.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "astro/refraction.h"
#include "astro/scintillation.h"
#include "render/night/star_field.h"
#include "render/night/star_transmittance.h"
#include "render/night/twinkle_sigma_table.h"
#include "scene/scene.h"
#include "warp/projection.h"

namespace zenith::render {

/// One star's light in a frame: its continuous image pixel (the projection's
/// convention: pixel (i, j) covers [i, i+1) × [j, j+1)) and the linear sRGB
/// radiance × exposure of a pixel holding all its flux.
struct StarSplat {
  float x_px = 0.0f, y_px = 0.0f;
  std::array<float, 3> rgb{};
};

/// A splat's position is put on a grid of 1/256 pixel (at most 1/512 pixel
/// off: invisible, and the bilinear weights still sum to 1). Two outputs that
/// share pixel positions up to a whole-pixel shift — a dome master and its
/// quadrants, tiles of one projection — then compute the same weights bit for
/// bit (a float keeps a multiple of 1/256 exactly up to 65 536 pixels), where
/// the positions straight from each projection differ in their last float bits
/// and can move a pixel's code by one where the outputs meet.
inline constexpr double kSplatGridPerPixel = 256.0;
glm::dvec2 on_splat_grid(const glm::dvec2& pixel);

/// Whether a splat at `pixel` (centres at i + 0.5) lands on any pixel of a
/// `width` × `height` image: its 2 × 2 footprint reaches the image's edge
/// pixels from half a pixel outside, so a star just beyond an output's edge
/// still lights the edge's pixels, as it does in a larger output holding both.
bool splat_touches_image(const glm::dvec2& pixel, double width, double height);

/// What star_splats needs of a frame.
struct StarFrame {
  const warp::Projection* projection = nullptr;
  glm::dvec3 camera_m{0.0};
  glm::dmat3 world_to_camera{1.0};
  /// The site's horizon at the camera (east, north, up in the world frame).
  glm::dvec3 east{1, 0, 0}, north{0, 1, 0}, up{0, 0, 1};
  const astro::Refraction* refraction = nullptr;  ///< null: straight lines
  std::vector<StarAtmosphere> atmospheres;
  /// Spheres that hide a star (every body of the scene): centre, radius.
  std::vector<std::pair<glm::dvec3, double>> occluders;
  std::vector<std::array<double, 3>> rgb_weights;  ///< per wavelength
  double exposure = 1.0;
  /// Cheap rejections before any per-star work (view_cone below): a star
  /// whose geometric direction is further than this from `view_axis` (world,
  /// unit) cannot land in the image; cos of that angle (−1: none).
  glm::dvec3 view_axis{0, 0, -1};
  double view_cos_limit = -1.0;
  /// sin of the lowest true altitude that can still show (the ground's dip less
  /// refraction's lift and a margin; −1: none): below it the ground hides the star.
  double lowest_sin_altitude = -1.0;
  /// Twinkling (astro/scintillation.h; null: steady stars): the options, the
  /// integration interval the frame's sky time falls in (one draw per star and
  /// interval), the observer's altitude and the air's ground refractivity n₀ − 1.
  const astro::ScintillationOptions* scintillation = nullptr;
  std::int64_t scintillation_interval = 0;
  double observer_altitude_m = 0.0;
  double ground_refractivity = 0.0;
  /// astro::scintillation_variance_per_cubed_air_mass of the above: the frame's
  /// part of every star's variance (set_twinkling keeps it with them).
  double scintillation_per_cubed_air_mass = 0.0;
  /// Every star's deviate for scintillation_interval, by index
  /// (StarField::scintillation_normals: the star test's; null: drawn per star).
  const std::vector<double>* scintillation_normals = nullptr;
  /// s of the twinkle by the table (set_twinkling fills it; empty: the formula).
  std::optional<TwinkleSigmaTable> twinkle_sigma;
  /// Per atmosphere, its CameraTransmittance from camera_m (star_frame sets
  /// them; empty: star_transmittance).
  std::vector<CameraTransmittance> transmittances;
  /// Ω at a star's pixel by the projection's closed form where it has one
  /// (warp::Projection::pixel_solid_angle_sr; star_frame sets it), within the
  /// projection's solid_angle_relative_bound() of the rays' quotient; false:
  /// the quotient itself (pixel_solid_angle_by_rays_sr).
  bool closed_form_solid_angle = false;
  /// Sets the twinkling's five fields above together.
  void set_twinkling(const astro::ScintillationOptions& options, std::int64_t interval, double observer_altitude,
                     double refractivity);
};

/// The cone around the image's centre ray that holds every pixel's ray, widened
/// by `margin_rad` (refraction's lift, the splat's footprint): axis (camera
/// frame) and the cosine of its half-angle (−1 where it exceeds π). From the
/// rays of 64 points along each edge of the image and through its centre lines.
std::pair<glm::dvec3, double> view_cone(const warp::Projection& projection, double margin_rad);

/// place_star's steps, each on its own (render_bench --stars-placement times
/// them one by one). Whether the geometric direction `enu` (east, north, up) is
/// dropped before any per-star work: under the ground, outside the view's cone.
bool star_rejected(const glm::dvec3& enu, const StarFrame& frame);
/// Its apparent direction (world, unit): lifted by the frame's refraction.
glm::dvec3 star_apparent_direction(const glm::dvec3& enu, const StarFrame& frame);
/// Whether a body of the frame hides unit direction `d` from the camera.
bool star_hidden(const glm::dvec3& d, const StarFrame& frame);
/// Where `d` lands: the projection's pixel on the splat grid; nullopt off the image.
std::optional<glm::dvec2> star_pixel(const glm::dvec3& d, const StarFrame& frame);
/// The transmittance along `d` through every atmosphere of the frame into
/// `out` (one per wavelength); `scratch` as many.
void star_line_of_sight_transmittance(const glm::dvec3& d, const StarFrame& frame, double* out, double* scratch);
/// Σ_λ w(λ) E_i(λ) T(λ): star i's linear sRGB irradiance through `transmittance`.
std::array<double, 3> star_colour(const StarField& field, std::size_t i, const double* transmittance,
                                  const StarFrame& frame);
/// Star i's twinkle factor in the frame's interval at apparent direction `d` (1: steady).
double star_twinkle(std::size_t i, const glm::dvec3& d, const StarFrame& frame);

/// One star in a frame, in double (steps 1–5 above, with its twinkle): its
/// pixel on the splat grid, its apparent direction (world, unit), the solid
/// angle of a pixel there and rgb = exposure · Σ_λ w(λ) E(λ) T(λ) f / Ω.
struct PlacedStar {
  glm::dvec2 pixel{0.0};
  glm::dvec3 direction{0.0, 0.0, 1.0};
  double omega_sr = 0.0;
  std::array<double, 3> rgb{};
};

/// Star `index` of `field` at `enu` (its geometric direction) in `frame`, as
/// star_splats places it; nullopt where it is drawn nowhere (under the ground,
/// outside the view, hidden by a body, off the image, no light left).
/// `scratch`: two buffers of the field's wavelength count.
std::optional<PlacedStar> place_star(const StarField& field, std::size_t index, const glm::dvec3& enu,
                                     const StarFrame& frame, std::vector<double>& scratch_a,
                                     std::vector<double>& scratch_b);

/// The stars of `field` at `directions_enu` (StarField::directions_enu) that
/// land in the image, unhidden and with light left, sorted by y_px.
std::vector<StarSplat> star_splats(const StarField& field, const std::vector<glm::dvec3>& directions_enu,
                                   const StarFrame& frame);

}  // namespace zenith::render
