#pragma once
// Stars as light (issue 29 goal 3; docs/night-sky.md, "Rendering the night
// sky"): the catalogue's stars placed in a frame, on the CPU in double, as
// point sources of flux. No GL: render/frame/star_pass.h draws what this
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
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "astro/civil_time.h"
#include "astro/refraction.h"
#include "astro/scintillation.h"
#include "astro/sky_positions.h"
#include "astro/star_catalogue.h"
#include "atmosphere/lut/lookup_tables.h"
#include "scene/scene.h"
#include "warp/projection.h"

namespace zenith::render {

/// How far the sky clock may move from the epoch of the stars' ERFA places
/// before they are recomputed [s]: over 6 hours precession, nutation and
/// aberration move a star by < 0.2″ about the rotation's pole.
inline constexpr double kStarEpochSpan_s = 6.0 * 3600.0;
/// The Earth rotation angle's rate [rad per UT1 second].
inline constexpr double kEarthRotationRate_rad_s = 2.0 * 3.14159265358979323846 * 1.00273781191135448 / 86400.0;

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

/// The first stars of the faint rests whose neighbourhoods
/// (StarField::neighbourhood_irradiance) are filled together: the whole
/// catalogue and the rests after the brightest 16, 64, …, 4096 (the star
/// test's ladder, render/frame/star_visibility.h).
inline constexpr std::array<std::size_t, 6> kNeighbourhoodFirsts = {0, 16, 64, 256, 1024, 4096};

/// An atmosphere a star's light can cross: its planet and its transmittance table.
struct StarAtmosphere {
  glm::dvec3 centre_m{0.0};  ///< world frame
  double ground_radius_m = 0.0, top_radius_m = 0.0;
  const atmosphere::lut::LookupTables* transmittance = nullptr;  ///< geometry, sizes, channels, transmittance filled
};

/// The stars of a catalogue, their fluxes at a scene's wavelengths and their
/// places at an epoch.
class StarField {
 public:
  /// Throws std::invalid_argument for no wavelengths.
  StarField(astro::StarCatalogue catalogue, const std::vector<double>& wavelengths_nm);

  const astro::StarCatalogue& catalogue() const { return catalogue_; }
  const std::vector<double>& wavelengths_nm() const { return wavelengths_nm_; }
  std::size_t size() const { return catalogue_.stars.size(); }
  /// Star i's irradiance above the atmosphere at wavelength k [W m⁻² nm⁻¹].
  double irradiance(std::size_t i, std::size_t k) const { return irradiance_[i * wavelengths_nm_.size() + k]; }
  /// The largest irradiance of any star at any wavelength.
  double brightest_irradiance() const { return brightest_; }
  /// The most light one pixel can gather from several stars, per wavelength:
  /// the largest sum, over the stars within `radius_rad` of any point of the
  /// sky, of their irradiance at that wavelength [W m⁻² nm⁻¹], with the stars
  /// at their J2000 places and the radius widened by twice the largest proper
  /// motion over `years_from_j2000` (precession, nutation, aberration and the
  /// sky's turning move neighbours alike). ≥ each wavelength's brightest star.
  /// The stars within the radius of one point lie within twice it of each
  /// other: the largest sum over the stars within twice the radius of a star
  /// (candidates from a grid of cubes of that chord). Only the
  /// stars from index `first` on (the catalogue is sorted brightest first: the
  /// faint rest after the first `first`). Cached per radius step of 2^(1/4) and `first`.
  const std::vector<double>& brightest_cluster_irradiance(double radius_rad, double years_from_j2000,
                                                          std::size_t first = 0);
  /// Per star i (every one), the sum of the irradiances of the stars from
  /// index `first` on within twice the widened radius of it, per wavelength,
  /// at [i · wavelengths + k]: a pixel gathering star i gathers no more of
  /// them (brightest_cluster_irradiance is the largest over i ≥ `first`).
  /// Cached per radius step and `first`; for a `first` of kNeighbourhoodFirsts
  /// all of those are filled in one pass (on the worker threads).
  const std::vector<double>& neighbourhood_irradiance(double radius_rad, double years_from_j2000,
                                                      std::size_t first = 0);
  /// The largest standard normal astro::scintillation_normal draws for any
  /// star of the catalogue (by its index, as star_splats does) in integration
  /// interval `interval`: the brightest twinkle of that interval is
  /// scintillation_factor(σ², this). Cached for the last interval.
  double largest_scintillation_normal(std::int64_t interval);

  /// Every star's geometric direction at `time` from `site` as (east, north,
  /// up) unit vectors into `out`: ERFA at the epoch, turned by the Earth's
  /// rotation since (recomputing the epoch when `time` is more than
  /// kStarEpochSpan_s from it or the site changed). Only the first `count`
  /// stars are turned (the brightest: the star test's second stage).
  void directions_enu(const astro::AstroTime& time, const astro::Site& site, std::vector<glm::dvec3>& out,
                      std::size_t count = static_cast<std::size_t>(-1));

 private:
  astro::StarCatalogue catalogue_;
  std::vector<double> wavelengths_nm_;
  std::vector<double> irradiance_;  // n per star
  double brightest_ = 0.0;
  double largest_proper_motion_rad_yr_ = 0.0;
  /// The caches' key: the radius widened by twice the largest proper motion
  /// over the years, rounded up to a step of 2^(1/4) (as log2 × 4).
  int radius_step(double radius_rad, double years_from_j2000) const;
  // By radius step and first star: the largest sums, the sums per star.
  std::map<std::pair<int, std::size_t>, std::vector<double>> clusters_, neighbourhoods_;
  bool have_normal_ = false;
  std::int64_t normal_interval_ = 0;
  double largest_normal_ = 0.0;
  bool have_epoch_ = false;
  double epoch_ut1_jd_ = 0.0;
  astro::Site epoch_site_;
  std::vector<glm::dvec3> epoch_enu_;
};

/// A unit vector `v` turned by `angle_rad` about unit `axis` (right-handed; Rodrigues).
glm::dvec3 rotate_about(const glm::dvec3& v, const glm::dvec3& axis, double angle_rad);

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
};

/// The cone around the image's centre ray that holds every pixel's ray, widened
/// by `margin_rad` (refraction's lift, the splat's footprint): axis (camera
/// frame) and the cosine of its half-angle (−1 where it exceeds π). From the
/// rays of 64 points along each edge of the image and through its centre lines.
std::pair<glm::dvec3, double> view_cone(const warp::Projection& projection, double margin_rad);

/// The transmittance along a ray from `camera_m` in unit direction `d` to
/// infinity through `a` (1 where it misses the shell, 0 where it meets the
/// ground) into `out` (channels values).
void star_transmittance(const StarAtmosphere& a, const glm::dvec3& camera_m, const glm::dvec3& d, double* out);

/// Ω of the pixel at continuous image position (x, y) [sr], from the
/// projection's rays half a pixel either side; 0 where a ray is missing.
double pixel_solid_angle_sr(const warp::Projection& projection, double x_px, double y_px);

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
