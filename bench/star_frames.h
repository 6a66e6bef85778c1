#pragma once
// render_bench --stars LIMIT : what the night sky's pass
// (render/night/star_pass.h) adds to a frame. The scene (the ground view by
// default) gets a sky clock at the camera's own latitude and longitude at
// --stars-time (default 2026-12-21T22:00:00Z, a winter night) and a night
// exposure (--stars-exposure, default 3e5); the stars are the catalogue's to V
// LIMIT (8.7: about 100 000). Frames with the stars and without (the night
// floor on in both), interleaved round by round, medians; then the same scene
// at its own daylight sun and exposure, where the pass's test skips it. Prints
// the figures and writes them to --stars-csv (default
// bench/results/star_frame_times.csv).
//
// render_bench --moonlight: the same for the Moon's light of the atmosphere
// passes (render/night/moon_light.h): frames with the moonlight and without
// (no stars, the night floor and the Moon's disc in both) at a full Moon
// (--stars-time, default for it 2026-01-03T20:00:00Z: the full Moon some 20°
// up in the east of the ground view's site), then by day with the Moon up
// (StarTiming::day_time_utc, the scene's exposure), where its test skips it;
// CSV default bench/results/moonlight_frame_times.csv.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "render/renderer.h"
#include "scene/scene.h"

namespace zenith::bench {

struct StarTiming {
  bool moonlight = false;  ///< time the moonlight passes instead of the stars
  double magnitude_limit = 8.7;
  std::string time_utc = "2026-12-21T22:00:00Z";
  /// --moonlight's day: the sky clock at a daylight hour with the Moon up (near first quarter, some 25° up in the
  /// south-east of the ground view's site, the sun some 15° up), at the scene's own exposure.
  std::string day_time_utc = "2026-01-26T14:00:00Z";
  double exposure = 3e5;
  int rounds = 3, iterations = 3;
  std::vector<std::pair<int, int>> sizes;  // planar views at fov_deg
  double fov_deg = 79.0;
  std::filesystem::path csv;
};

/// The median of `values` (the mean of the middle two for an even count; needs one).
double median(std::vector<double> values);

/// Runs the cases above and writes the CSV; `device` names the GL renderer.
void time_stars(const StarTiming& timing, const std::string& device, const scene::Scene& scene,
                const render::TableSource& tables);

}  // namespace zenith::bench
