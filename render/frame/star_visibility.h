#pragma once
// Whether any catalogue star can show in a frame (issue 29 goal 8;
// docs/night-sky.md, "Rendering the night sky"): the star pass's own test,
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
// (render/frame/sky_radiance_floor.h)
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
#include <array>

#include "render/frame/frame_state.h"
#include "render/frame/star_field.h"

namespace zenith::render {

/// Half an 8-bit code value, less 1 % for the float rounding of the GPU's
/// tone curve and encoding: a smaller change of a display value is invisible.
inline constexpr double kInvisibleCodeChange = 0.495;

/// Whether adding at most |delta| of exposed linear radiance to a display
/// channel whose background is at least `background` changes its 8-bit sRGB
/// code value by less than kInvisibleCodeChange, for either tone operator:
/// display_code_slope_bound(y) · |delta| below it, y the lowest value the
/// channel can pass through — `background`, or with `may_subtract` (negative
/// colour weights) max(background − |delta|, 0).
bool invisible_change(double background, double delta, bool may_subtract);

/// The test's figures for one frame (per linear sRGB channel, × exposure).
struct StarVisibility {
  std::array<double, 3> sky_floor{};  ///< B: the least the sky behind any star is (0: no bound)
  std::array<double, 3> sky_peak{};   ///< the most the stars add to a pixel of sky
  bool could_show = true;             ///< a change of half a code is possible somewhere
  /// The test this one replaced, for comparison (render_bench --stars-show):
  /// the brightest star alone through no air on a black sky, exposure ·
  /// E_max · Σ_λ max_c |w_c(λ)| · twinkle / Ω_min, drawn where ≥ kInvisibleDisplayStep.
  double black_sky_peak = 0.0;
};

/// The test for `field`'s stars in `frame` with the sky of `sky` (star_splats'
/// frame: its atmospheres, exposure, colour weights, twinkling),
/// `years_from_j2000` the sky time's distance from J2000 (proper motion).
StarVisibility star_visibility(const FrameState& frame, StarField& field, const StarFrame& sky,
                               double years_from_j2000);

/// The smallest pixel solid angle over a 33 × 33 grid of the image [sr], half
/// of it as the margin for what the grid misses (the projections' solid
/// angles vary smoothly: an equidistant fisheye's as sin θ / θ, by π/2 from
/// centre to rim and by 6 % between the grid's last point and a 180° rim).
double smallest_pixel_solid_angle_sr(const warp::Projection& projection);

}  // namespace zenith::render
