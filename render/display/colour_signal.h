#pragma once
// The CPU twin of the display pass's colour stage (display_transform.glsl,
// display_signal; render/display/display_encoder.h): an MPCDI region's colour
// profile applied to zenith's signal, as the files written on the CPU need it
// (offline/output_rendering.h, cluster/node/output_writer.h). Pure arithmetic.
#include <span>

#include "warp/blending.h"
#include "warp/colour_profile.h"

namespace zenith::render::display {

/// The CPU twin of the display pass's colour stage (display_transform.glsl,
/// display_signal): `rgb` holds `row_count` rows of display-linear P (tone
/// mapped and faded, no α or β) from row `first_row` of a `width_px`-wide
/// frame; each value becomes V = colour.process(E(P), α, β) with E the sRGB
/// encoding, α the mask's (1 when null) and β the mask's black_level_at
/// (its β map, else `black_level`), V in [0, 1] (the
/// display code divided by its maximum).
void apply_colour_profile(std::span<float> rgb, int first_row, int row_count, int width_px,
                          const warp::MpcdiColourProfile& colour, const warp::BlendMask* blend, double black_level);

/// For an 8-bit sRGB writer (image::open_png_writer with the clamp operator)
/// that must store the code round(255 · V): each V in `values` becomes
/// srgb_decode(round(255 · V) / 255), the linear value at the centre of that
/// code, which the writer's quantizer maps back to it.
void to_srgb_code_centres(std::span<float> values);

}  // namespace zenith::render::display
