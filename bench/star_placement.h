#pragma once
// render_bench --stars LIMIT --stars-show SHOW --stars-placement: what
// placing the stars costs the frame's thread, and where it goes.
//
// 1. The renderer through the show's own exposure track every --stars-step
//    show seconds on a fisheye dome master of --stars-dome pixels, each frame
//    drawn twice and the second timed (PassTimer's CPU parts): the star test
//    (render/night/star_visibility.h, both stages) and the star placement
//    (the catalogue's turn and star_splats), with the stars placed and tested.
// 2. At the show's last frame (night), star_splats alone on the CPU, outside
//    the renderer, on the catalogue's stars at that instant: the whole
//    placement on the worker threads, then place_star's steps
//    (render/night/star_placement.h) one after the other over every star on one
//    thread — the star test's deviates of the twinkle's interval for every star
//    (StarField::largest_scintillation_normal, on the worker threads; the
//    placement reads them), the turn, the rejections, refraction, the occluders, the
//    projection, the transmittance, the pixel's solid angle, the colour and the
//    twinkle — each over the stars that reach it, medians of --rounds ×
//    --iterations; then the transmittance, the solid angle, the twinkle and the
//    whole placement again with the exact reads (star_transmittance, the rays,
//    the formula) in place of the frame's tables.
// Prints both and writes the parts to --stars-csv (default
// bench/results/star_placement.csv) and the frames beside it (…_frames.csv).
#include <string>

#include "bench/star_twilight.h"
#include "render/renderer.h"

namespace zenith::bench {

/// Runs both and writes the CSVs (the options as --stars-show's: the show,
/// the magnitude limit, the dome's pixels, the step, rounds, iterations, the
/// CSV); `device` names the GL renderer.
void time_star_placement(const StarTwilight& bench, const std::string& device, const render::TableSource& tables);

}  // namespace zenith::bench
