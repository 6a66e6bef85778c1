#include "image/display_fade.h"

#include <fmt/format.h>

#include <stdexcept>

namespace zenith::image {

void apply_fade(std::span<float> rgb, double level, const std::array<double, 3>& colour) {
  if (!(level >= 0.0 && level <= 1.0))
    throw std::invalid_argument(fmt::format("fade: level {} must be in [0, 1]", level));
  for (const double c : colour)
    if (!(c >= 0.0 && c <= 1.0))
      throw std::invalid_argument(fmt::format("fade: colour component {} must be in [0, 1]", c));
  if (rgb.size() % 3 != 0) throw std::invalid_argument(fmt::format("fade: {} values are not RGB triples", rgb.size()));
  if (level == 0.0) return;
  const float f = static_cast<float>(level), keep = static_cast<float>(1.0 - level);
  const std::array<float, 3> c = {static_cast<float>(colour[0]) * f, static_cast<float>(colour[1]) * f,
                                  static_cast<float>(colour[2]) * f};
  for (std::size_t p = 0; p < rgb.size(); p += 3)
    for (std::size_t k = 0; k < 3; ++k) rgb[p + k] = rgb[p + k] * keep + c[k];
}

}  // namespace zenith::image
