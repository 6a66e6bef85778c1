#pragma once
// render_bench --stars LIMIT (issue 29 goal 8): what the night sky's pass
// (render/frame/star_pass.h) adds to a frame. The scene (the ground view by
// default) gets a sky clock at the camera's own latitude and longitude at
// --stars-time (default 2026-12-21T22:00:00Z, a winter night) and a night
// exposure (--stars-exposure, default 3e5); the stars are the catalogue's to V
// LIMIT (8.7: about 100 000). Frames with the stars and without (the night
// floor on in both), interleaved round by round, medians; then the same scene
// at its own daylight sun and exposure, where the pass's test skips it. Prints
// the figures and writes them to --stars-csv (default
// bench/results/star_frame_times.csv).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "render/renderer.h"
#include "scene/scene.h"

namespace zenith::bench {

struct StarTiming {
  double magnitude_limit = 8.7;
  std::string time_utc = "2026-12-21T22:00:00Z";
  double exposure = 3e5;
  int rounds = 3, iterations = 3;
  std::vector<std::pair<int, int>> sizes;  // planar views at fov_deg
  double fov_deg = 79.0;
  std::filesystem::path csv;
};

/// Runs the cases above and writes the CSV; `device` names the GL renderer.
void time_stars(const StarTiming& timing, const std::string& device, const scene::Scene& scene,
                const render::TableSource& tables);

}  // namespace zenith::bench
