#pragma once
// The operator's fade on the CPU, for files (docs/operator.md, "Fades"): the
// same step as the GPU's display pass (shaders/render/display_transform.glsl,
// P = mix(P, fade_colour, f)), on display-linear values after tone mapping and
// before the output stage (blend mask and black level), so a faded projector
// keeps its calibration and a fade blends across overlaps like the picture.
#include <array>
#include <span>

namespace zenith::image {

/// P' = P·(1 − f) + c·f for every RGB triple of `rgb` (display-linear, each
/// channel in [0, 1]); f = `level` in [0, 1], c = `colour` (display-linear,
/// each in [0, 1]). Level 0 leaves the values untouched. Throws
/// std::invalid_argument for a level or colour outside [0, 1] or a size that
/// is not a multiple of 3.
void apply_fade(std::span<float> rgb, double level, const std::array<double, 3>& colour);

}  // namespace zenith::image
