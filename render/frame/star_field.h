#pragma once
// Stars as light (docs/night-sky.md, "Rendering the night
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
#include "core/units.h"
#include "scene/scene.h"
#include "warp/projection.h"

namespace zenith::render {

/// How far the sky clock may move from the epoch of the stars' ERFA places
/// before they are recomputed [s]: over 6 hours precession, nutation and
/// aberration move a star by < 0.2″ about the rotation's pole.
inline constexpr double kStarEpochSpan_s = 6.0 * 3600.0;
/// The Earth rotation angle's rate [rad per UT1 second].
inline constexpr double kEarthRotationRate_rad_s = 2.0 * core::kPi * 1.00273781191135448 / 86400.0;

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
  /// Every star's astro::scintillation_normal for `interval` (by index), where
  /// largest_scintillation_normal computed them for it last; else null.
  const std::vector<double>* scintillation_normals(std::int64_t interval) const;

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
  std::vector<double> normals_;
  bool have_epoch_ = false;
  double epoch_ut1_jd_ = 0.0;
  astro::Site epoch_site_;
  std::vector<glm::dvec3> epoch_enu_;
};

/// star_transmittance from one camera, for every direction of a frame: every
/// ray is read at one radius — the camera's, or the top's where the camera is
/// outside the shell and the ray enters it — so the bilinear filter's weight
/// between the table's two rows there is the same for all, and the rows are
/// blended once, per channel, into one row. A star then costs its distance to
/// the top (the row's coordinate u_μ, as transmittance_uv), the row's two taps
/// and one lerp per channel, where star_transmittance recomputes the row
/// weight's square roots and reads four texels. The same bilinear filter with
/// its sum reordered: the same figures to a few ulps (values ≤ 1; asserted
/// within 1e-15 of star_transmittance by
/// StarField.TheCameraTransmittanceIsTheTablesReadWithinRounding), so neither
/// the pass's stars nor star_visibility's bounds move.
class CameraTransmittance {
 public:
  CameraTransmittance(const StarAtmosphere& atmosphere, const glm::dvec3& camera_m);
  /// star_transmittance(atmosphere, camera_m, d, out).
  void operator()(const glm::dvec3& d, double* out) const;

 private:
  atmosphere::lut::ShellGeometry geometry_;  // the table's
  glm::dvec3 p_;                             // the camera from the planet's centre
  double ground_ = 0.0, top_ = 0.0;          // StarAtmosphere's radii
  double r_ = 0.0, r_at_ = 0.0, d_min_ = 0.0, d_max_ = 0.0;
  std::size_t width_ = 0, channels_ = 0;
  std::vector<double> row_;  // [texel][channel]
};

/// The twinkle's s = √ln(1 + σ_I²) of a frame's stars (astro/scintillation.h),
/// a function of a star's apparent elevation alone: of μ = sin e (d · up,
/// clamped to [0, 1]) through Pickering's air mass X(e) and σ_I² = min(1,
/// C X³), C the frame's astro::scintillation_variance_per_cubed_air_mass.
/// Below μ_cap, where C X³ reaches the cap, s = √ln 2 exactly; above,
/// tabulated at μ_j = μ_cap + (1 − μ_cap) t_j², t_j = j/N (N = kNodes: dense
/// at the horizon, where Pickering's h^1.1 bends X; the cap's kink at the
/// first node) and read linearly in t: a star then costs a root and a lerp
/// where the formula takes an arcsine, a power, a sine, a log and a root.
/// The error on [t_j, t_j+1] is at most (h/4) times the variation of ds/dt there
/// (linear interpolation's kernel is ≤ h/4), which the table's own second
/// differences D_j = s_j−1 − 2 s_j + s_j+1 bound where s″ keeps its sign over
/// the neighbouring intervals: bound_j = (|D_j| + |D_j+1|)/4, doubled for
/// inflections and + 1e-15 for rounding
/// (StarField.TheTwinkleTableIsTheFormulaWithinItsOwnBound checks it at 64
/// points per interval). A factor exp(s g − s²/2) read with s + ε is within
/// exp(|ε| (|g| + s + |ε|)) of the formula's: star_visibility's first stage
/// widens its twinkle by that for error_bound().
class TwinkleSigmaTable {
 public:
  static constexpr std::size_t kNodes = 2048;
  explicit TwinkleSigmaTable(double per_cubed_air_mass);
  /// s at μ by the table.
  double operator()(double mu) const;
  /// s at μ by the formula.
  double exact(double mu) const;
  /// The bound above on the interval holding μ, and the largest over all.
  double bound_at(double mu) const;
  double error_bound() const { return largest_bound_; }

 private:
  double per_cubed_air_mass_;
  double mu_cap_ = 0.0, s_cap_ = 0.0, span_ = 1.0;  // σ_I² = 1 at and below μ_cap; 1 − μ_cap
  std::vector<double> s_, bound_;                   // at the nodes; per interval
  double largest_bound_ = 0.0;
};

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

/// The transmittance along a ray from `camera_m` in unit direction `d` to
/// infinity through `a` (1 where it misses the shell, 0 where it meets the
/// ground) into `out` (channels values).
void star_transmittance(const StarAtmosphere& a, const glm::dvec3& camera_m, const glm::dvec3& d, double* out);

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
