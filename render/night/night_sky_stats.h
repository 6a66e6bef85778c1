#pragma once
// What the night sky's pass (render/night/star_pass.h) and its tests did in a
// frame: for logs, the renderer's FrameStats, tests and benchmarks.
#include <algorithm>
#include <array>
#include <cstddef>
#include <string>

namespace zenith::render {

/// The test's figures for one frame (per linear sRGB channel, × exposure).
struct StarVisibility {
  std::array<double, 3> sky_floor{};  ///< B: the least the sky behind any star is (0: no bound)
  std::array<double, 3> sky_peak{};   ///< the most the stars add to a pixel of sky (first stage)
  bool could_show = true;             ///< a change of half a code is possible somewhere
  /// The second stage (0 where the first decided): how many of the brightest
  /// stars it tested one by one (where one alone decided before the ladder:
  /// that star's rank, counting from 1, among the catalogue's brightest), how
  /// many of them landed in the image.
  std::size_t stars_tested = 0, stars_placed = 0;
  /// The largest change of a code value the deciding stage allows [codes]:
  /// D'(B) · peak (first stage) or the largest star's D'(B_s) Δ_s (second; where
  /// it stopped at a star that could show, that star's). Below
  /// kInvisibleCodeChange: skipped.
  double code_change = 0.0;
  /// The test this one replaced, for comparison (render_bench --stars-show):
  /// the brightest star alone through no air on a black sky, exposure ·
  /// E_max · Σ_λ max_c |w_c(λ)| · twinkle / Ω_min, drawn where ≥ kInvisibleDisplayStep.
  double black_sky_peak = 0.0;

  /// The largest channel of sky_floor and of sky_peak.
  double largest_sky_floor() const { return std::max({sky_floor[0], sky_floor[1], sky_floor[2]}); }
  double largest_sky_peak() const { return std::max({sky_peak[0], sky_peak[1], sky_peak[2]}); }
};

/// What the night sky's pass did in the last frame.
struct NightSkyStats {
  bool drawn = false;              ///< false: nothing drawn (no sky clock or night sky, or the tests)
  std::size_t stars = 0;           ///< stars placed in the image
  bool night_floor = false;        ///< the night floor was added
  bool moon = false;               ///< the Moon was drawn (a disc, or a point below a pixel's size)
  std::string catalogue_identity;  ///< StarCatalogue::identity_sha256 of the stars drawn ("" none)
  StarVisibility star_test;        ///< the stars' test (zeros, and could_show true, where it did not run)
  /// MoonAlbedoMap::identity_sha256 of the map loaded, given with the stars or the Moon's
  /// disc ("" neither drawn, or the uniform albedo of a missing map)
  std::string moon_map_identity;
  double moon_mean_albedo = 1.0;  ///< the map's photometric mean over the lit disc (moon_disc_mean_albedo)
};

}  // namespace zenith::render
