#pragma once
// Whether any catalogue star can show in a frame
// (docs/night-sky.md, "Rendering the night sky"): the star pass's own test,
// on the CPU before any star is placed or any GPU work, against the sky the
// atmosphere passes will draw behind the stars — not against black.
//
// The display chain turns a channel's exposed linear radiance x into the
// 8-bit code value D(x) = 255 · E(T(x)) (image/tone_mapping.h: T the tone
// operator, exponential 1 − e^(−x) or clamp min(x, 1); E the sRGB encoding).
// T and E are concave and non-decreasing (E's two branches meet with a step
// down of 2.9e-8), so a star adding Δ to a pixel whose background is x ≥ B
// moves its code value by at most
//     |D(x + Δ) − D(x)| ≤ D'(B) · Δ,   D'(y) = 255 E'(T(y)) T'(y)
// (for Δ ≥ 0; a Δ of either sign, from negative colour weights, at the slope
// of max(B − |Δ|, 0))
// (the code's slope falls as the background rises: on a sky at x = 1 one code
// is 1/54 of exposed radiance, at black 1/3294). The stars are invisible when
// that is below half a code (less 1 % for the GPU's float rounding) in every
// channel, for the brightest pixel the stars can make,
//     Δ ≤ exposure · Σ_λ |w_c(λ)| Ê(λ) K(λ) / Ω_min,
// Ê(λ) the brightest cluster of stars a pixel can gather (StarField::
// brightest_cluster_irradiance, within two pixel angles of a pixel's centre,
// widened for refraction's compression of the sky near the horizon),
// K the most of a star's light the line of sight keeps: the largest
// transmittance T(r, μ) (at the zenith: T grows with μ) or, with twinkling,
// the largest T(e) · f(e) over apparent elevations e (f the brightest factor
// any star's draw gives in the frame's interval at e's variance, which falls
// as e rises; per degree, T at its top and f at its bottom),
// Ω_min the smallest pixel solid angle, and the sky's floor from the tables
// (atmosphere/lut/sky_radiance_lower_bound.h)
//     B = exposure · Σ_λ w_c(λ) E_sun(λ) S_min(λ).
// Starlight lands only on pixels whose ray meets no body (night_sky.comp):
// the ground and other bodies may be darker than any sky, and a star's splat
// next to one leaves that pixel alone. Every other pixel of a camera inside
// the site body's air reads its sky at the camera, and what else is drawn
// there (the Moon's light, the night floor, other atmospheres, the sun) adds.
//
// B needs the camera inside the site body's air and colour weights ≥ 0 (the
// direct mapping; cie1931's negative lobes could subtract); otherwise B = 0,
// the test on a black sky. B depends only on the frame state (camera, sun,
// exposure, tables, colour weights): the same on every node. The stars' Δ
// needs the node's smallest pixel — a point source is brighter per pixel on a
// finer output — so nodes of different pixel sizes may decide differently,
// each conservatively for its own pixels: a node that skips would have changed
// none of its code values by half a code, so no seam can come of it.
//
// That first stage is cheap and global, and loose where the sky is not much
// brighter than the brightest stars (the evening show keeps its sky at about
// a quarter of full display, where Sirius moves ~0.1 code and the global
// bound allows ~2: the rim's Ω_min against the star's own pixel ×3, the
// brightest twinkle ×1.5, the blue end of the spectrum for every channel,
// the darkest sky anywhere against the sky behind the star ×1.1–3). Where it
// cannot rule the stars out, the second stage decides star by star for the
// brightest m of the catalogue (sorted brightest first; m the least of 16,
// 64, …, 4096 whose rest passes below with a quarter of the budget, else
// 4096 if it passes at all), with each one's own figures. Ê and K are
// refined first: a pixel gathers the stars within ρ_c (the first stage's
// cluster radius) of its centre, which lie within 2ρ_c of each other, so of
// any set of stars a pixel gathers, each one's neighbourhood N_i(λ) — the
// irradiance of the stars after the m-th within 2ρ_c of star i
// (StarField::neighbourhood_irradiance, on the catalogue's places, cached) —
// holds all of the rest among them; K_e(λ) is the largest T · f over the
// degrees of apparent elevation within 2ρ_c + 1° (refraction's lift) of
// elevation e: the rest's stars near i are seen through no more air than that.
//
//   the rest, on pixels no bright star touches: for every star j after the
//     m-th that can be drawn (above the ground, in the view's cone),
//       F_j,c = exposure · Σ_λ |w_c(λ)| N_j(λ) K_e(j)(λ) / Ω_min,
//     against B, or where that is not enough against the sky over the cap
//     around j's cube of the (east, north, up) grid (side 0.06: within
//     asin(δ/(1 − δ)), δ = √3 · 0.06 / 2, of the cube's centre, + 1° for the
//     lift, + 2 pixel angles for the splat): its pixels lie in that cap;
//   a bright star s: placed as star_splats places it (place_star: its own
//     refracted direction, its own transmittance T_s(λ), its own colour
//     weights, its own twinkle draw f_s, the solid angle Ω_s of a pixel at its
//     position in this node's projection), rgb_s = exposure · Σ_λ w_c E_s T_s
//     f_s / Ω_s, which its splat spreads with weights ≤ 1 over the 2 × 2
//     pixels around it. A pixel it touches gathers every bright star within 2
//     pixels of it in x and in y (their splats share pixels) and the rest's
//     stars within 2ρ_c of it:
//       Δ_s,c = (Σ_{s' within 2 px} |rgb_s',c|) (1 + 1e-3) + F_s,c
//     (1e-3: the splat's float and the accumulator's 2⁻²⁸ step; F_s,c as
//     F_j,c with s's neighbourhood of the rest);
//   the sky behind it (SkyBehindStarBound): every pixel it touches has its centre
//     within 1 pixel of the star's position in x and y, so its ray lies within
//     ρ of the star's direction (splat_footprint_radius); the sky those pixels
//     read is bounded from the same tables the frame reads over that cap only
//     (SkyLowerBoundSlice: the camera's rows and the sun's μs columns, the μ texels
//     and ν slices a read in the cap weighs, the phases over the cap's ν; with
//     the sky-view table, over the texels of that table the cap's pixels
//     interpolate, each a read of the 4D tables at its own direction; the
//     lesser of both where the frame may read either). Near the sun (5° plus
//     ρ), within 1° of the horizon and within 0.5° of another body's limb the
//     star is kept on B, the floor of the whole sky (not bounded there: the
//     disc, the ground's edge and the limb are where passes meet).
// A star is invisible when D'(max(B, B_s)) Δ_s < kInvisibleCodeChange in
// every channel; the stars are skipped when every bright star and every
// drawable star of the rest is. Every pixel a star touches is then covered:
// by a bright star's test where one touches it, by the rest's where none
// does. As the first stage, Ω_s and the pixel offsets are the node's own, so
// nodes decide each for its own pixels. It costs a turn of every star's
// place, a pass over the drawable ones per rung of the ladder, the sky over
// a few hundred cubes and the placing of the m brightest (render_bench
// --stars-show: docs/night-sky.md, "Where it skips, measured"). Before the
// ladder, the 16 brightest alone: where one of them, its own splat against
// the sky behind it, could move a code, so could it within any rung (its Δ
// there only adds to its own light, and the bound grows with Δ), and the test
// answers "could show" at once — at night, the price of placing a few stars
// instead of the ladder's.
//
// The pass's placement reads three figures faster than their formulas
// (star_placement.h; render_bench --stars-placement), and the bounds above cover
// each: the transmittance from CameraTransmittance's blended row is the same
// bilinear read as star_transmittance to a few ulps (1e-15 of values ≤ 1),
// inside the 1 % kInvisibleCodeChange keeps from half a code, so K is unchanged; Ω_s by
// the projection's closed form (warp::Projection::pixel_solid_angle_sr) is within a²/6 (fisheye) or t²/4 (planar) of
// the rays' quotient, so never below the first stage's Ω_min, half the
// rays' smallest on the grid (1 − 1e-5 ≫ ½ at any pixel size), and the second
// stage places its bright stars with the same place_star as the pass; the
// twinkle's s from TwinkleSigmaTable is within its error_bound() ε of the
// formula, so a star's factor within exp(ε (|g| + s + ε)) of the formula's
// (s ≤ √ln 2): the first stage's twinkle per degree is widened by that
// (ε 2–6e-6 for the eye on Earth, from 10 km and on Mars: 6e-5 at the largest draw).
#include <array>
#include <optional>

#include "astro/civil_time.h"
#include "astro/sky_positions.h"
#include "atmosphere/lut/sky_radiance_lower_bound.h"
#include "render/frame/frame_in_progress.h"
#include "render/night/night_sky_stats.h"
#include "render/night/star_placement.h"

namespace zenith::render {

/// Half an 8-bit code value, less 1 % for the float rounding of the GPU's
/// tone curve and encoding: a smaller change of a display value is invisible.
inline constexpr double kInvisibleCodeChange = 0.495;
/// The second stage's ladder of the brightest stars tested one by one: 16,
/// 64, 256, 1024, 4096 (kNeighbourhoodFirsts after the whole catalogue); past that the pass runs.
inline constexpr std::size_t kFirstStarsTested = kNeighbourhoodFirsts[1], kMostStarsTested = kNeighbourhoodFirsts[5];
/// Before the ladder, the first kFirstStarsTested stars placed in the image
/// among the catalogue's kFirstStarsScanned brightest answer alone where one
/// of them could show.
inline constexpr std::size_t kFirstStarsScanned = kNeighbourhoodFirsts[4];

/// Whether adding at most |delta| of exposed linear radiance to a display
/// channel whose background is at least `background` changes its 8-bit sRGB
/// code value by less than kInvisibleCodeChange, for either tone operator:
/// display_code_slope_bound(y) · |delta| below it, y the lowest value the
/// channel can pass through — `background`, or with `may_subtract` (negative
/// colour weights) max(background − |delta|, 0).
bool invisible_change(double background, double delta, bool may_subtract);

/// The most a channel's code value can move for a change |delta_c| on a
/// background ≥ background_c, over the channels [codes]: D'(y) |Δ| at the
/// lowest value y it passes through (invisible_change).
double largest_code_change(const std::array<double, 3>& background, const std::array<double, 3>& delta,
                           bool may_subtract);

/// Whether every colour weight is ≥ 0 (the direct and sRGB mappings; the
/// cie1931 mapping's negative lobes can take light away from a channel).
bool colour_weights_non_negative(const std::vector<std::array<double, 3>>& rgb_weights);

/// The first stage's B: per linear sRGB channel × exposure, the least the
/// atmosphere passes draw on any pixel of sky of `frame` (a ray from the camera
/// inside the air of body `site` that meets no body), from that air's
/// SkyRadianceLowerBound through the colour weights and the sun's irradiance. Zeros
/// where it does not apply: no such air resident, or colour weights that may
/// subtract. What the stars and the night floor are tested against.
std::array<double, 3> darkest_sky(const FrameInProgress& frame, std::size_t site, double exposure,
                                  const std::vector<std::array<double, 3>>& rgb_weights);

/// The sky behind one star: the second stage's B_s (above), per linear sRGB
/// channel × exposure. Built per frame for the camera in the site body's air.
class SkyBehindStarBound {
 public:
  /// `floor` of the site body's tables; the camera and the planet's centre
  /// (world), its ground radius; the sun (world, unit); whether the sky-view
  /// table may be read (AtmospherePass::sky_view: then the least of both
  /// ways); the colour weights (≥ 0), the sun's irradiance and the exposure;
  /// the other bodies (centre, radius) whose limbs keep a star; `whole_sky`
  /// the first stage's B, the least of every sky pixel.
  SkyBehindStarBound(const atmosphere::lut::SkyRadianceLowerBound& floor, const glm::dvec3& camera_m,
                     const glm::dvec3& planet_centre_m, double ground_radius_m, const glm::dvec3& sun, bool sky_view,
                     const std::vector<std::array<double, 3>>& rgb_weights, const std::vector<double>& sun_irradiance,
                     double exposure, std::vector<std::pair<glm::dvec3, double>> bodies,
                     std::array<double, 3> whole_sky);

  /// At least the sky on every pixel of sky whose ray lies within `radius_rad`
  /// of unit `direction` (world): max(B_s, B), or B where the star is kept.
  std::array<double, 3> at(const glm::dvec3& direction, double radius_rad) const;
  /// Whether a cap there is kept on B (near the sun, the horizon, a limb).
  bool kept(const glm::dvec3& direction, double radius_rad) const;

 private:
  atmosphere::lut::SkyLowerBoundSlice slice_;
  glm::dvec3 camera_m_, up_, sun_;
  double radius_m_, mu_horizon_, theta_horizon_, sun_theta_;
  bool sky_view_;
  std::vector<std::array<double, 3>> weights_;
  std::vector<double> sun_irradiance_;
  double exposure_;
  std::vector<std::pair<glm::dvec3, double>> bodies_;
  std::array<double, 3> whole_sky_;
};

/// ρ of a star's splat at `pixel` (on the splat grid), its direction
/// `direction` (world, unit): every pixel the splat touches has its centre
/// within one pixel of it in x and y; the largest angle from `direction` to
/// the rays of that square's corners and edge midpoints (`camera_to_world`
/// turns the projection's rays), × 1.05 for the projection's curvature across
/// two pixels, + 1e-6 rad. Nullopt where one of those rays is missing (a
/// fisheye's rim): the star is then tested on the darkest sky.
std::optional<double> splat_footprint_radius(const warp::Projection& projection, const glm::dmat3& camera_to_world,
                                             const glm::dvec2& pixel, const glm::dvec3& direction);

/// The test for `field`'s stars in `frame` with the sky of `sky` (star_splats'
/// frame: its atmospheres, exposure, colour weights, twinkling) at the sky
/// clock's `time` and `site` (the brightest stars' places; proper motion).
/// `star_by_star` false: the first stage alone. `directions_enu`: the
/// catalogue's directions at the instant (StarField::directions_enu), filled
/// where the second stage needs them and left empty otherwise, so the pass
/// places its stars from the same vector instead of turning the catalogue
/// twice a frame (0.9 ms for 101 922 stars on this project's VM).
StarVisibility star_visibility(const FrameInProgress& frame, StarField& field, const StarFrame& sky,
                               const astro::AstroTime& time, const astro::Site& site,
                               std::vector<glm::dvec3>& directions_enu, bool star_by_star = true);

/// The smallest pixel solid angle over a 33 × 33 grid of the image [sr], half
/// of it as the margin for what the grid misses (the projections' solid
/// angles vary smoothly: an equidistant fisheye's as sin θ / θ, by π/2 from
/// centre to rim and by 6 % between the grid's last point and a 180° rim).
double smallest_pixel_solid_angle_sr(const warp::Projection& projection);

}  // namespace zenith::render
