#pragma once
// render_bench --stars LIMIT --stars-show SHOW : where the
// star pass's test (render/night/star_visibility.h) lets the stars run
// through a show's twilight, and what skipping them saves. The show's frames
// every --stars-step seconds of show time on a fisheye dome master of
// --stars-dome pixels: the sun's altitude, the exposure, the test this one
// replaced (the brightest star on a black sky), the test's first stage (the
// global bound against the sky) and both stages (star by star), with their
// figures, for the show's own exposure track and for each of its exposures
// held through the twilight; then, at the last frame where the first stage
// ran and the second skips (else where the black-sky test ran and the sky's
// skips), frames with the test and with the stars forced on, interleaved,
// medians, and the test's own CPU time there. Prints the figures
// and writes the sweep to --stars-csv (default
// bench/results/star_twilight_skip.csv) and the timing beside it (…_times.csv).
#include <filesystem>
#include <string>

#include "render/renderer.h"

namespace zenith::bench {

struct StarTwilight {
  std::filesystem::path show;
  double magnitude_limit = 8.7;
  int dome_px = 1024;
  double step_s = 2.0;
  int rounds = 3, iterations = 3;
  std::filesystem::path csv;
};

/// Runs the sweep and the timing above; `device` names the GL renderer.
void sweep_star_twilight(const StarTwilight& sweep, const std::string& device, const render::TableSource& tables);

}  // namespace zenith::bench
