#include "render/display/colour_signal.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "image/display_encoding.h"
#include "image/tone_mapping.h"

namespace zenith::render::display {

void apply_colour_profile(std::span<float> rgb, int first_row, int row_count, int width_px,
                          const warp::MpcdiColourProfile& colour, const warp::BlendMask* blend, double black_level) {
  const std::size_t pixels = static_cast<std::size_t>(row_count) * static_cast<std::size_t>(width_px);
  if (rgb.size() != pixels * 3 ||
      (blend != nullptr && (blend->width != width_px || first_row < 0 || first_row + row_count > blend->height)))
    throw std::invalid_argument(
        fmt::format("apply_colour_profile: rows {}+{} ({} values) of a {}-pixel-wide frame "
                    "do not fit {}",
                    first_row, row_count, rgb.size(), width_px,
                    blend ? fmt::format("the {}x{} mask", blend->width, blend->height) : std::string("their count")));
  const image::DisplayEncoding srgb;
  for (std::size_t i = 0; i < pixels; ++i) {
    const int x = static_cast<int>(i % static_cast<std::size_t>(width_px));
    const int y = first_row + static_cast<int>(i / static_cast<std::size_t>(width_px));
    const double alpha = blend != nullptr ? blend->at(x, y) : 1.0;
    const double beta = blend != nullptr ? blend->black_level_at(x, y, black_level) : black_level;
    float* p = rgb.data() + 3 * i;
    const std::array<double, 3> v = colour.process(
        {image::display_encode(p[0], srgb), image::display_encode(p[1], srgb), image::display_encode(p[2], srgb)},
        alpha, beta);
    for (std::size_t c = 0; c < 3; ++c) p[c] = static_cast<float>(v[c]);
  }
}

void to_srgb_code_centres(std::span<float> values) {
  for (float& v : values) v = image::srgb_decode(std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f);
}

}  // namespace zenith::render::display
