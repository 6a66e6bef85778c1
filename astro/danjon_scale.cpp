#include "astro/danjon_scale.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace zenith::astro {

double implied_danjon_class(double observed_l, double measured_drop_mag, double model_drop_mag) {
  if (!(observed_l >= 0.0 && observed_l <= 4.0))
    throw std::invalid_argument("Danjon's L " + std::to_string(observed_l) + " is outside the scale's [0, 4]");
  if (!std::isfinite(measured_drop_mag) || !std::isfinite(model_drop_mag))
    throw std::invalid_argument("a lunar eclipse's drop in magnitude must be finite");
  return std::clamp(observed_l + kDanjonPerMagnitude * (measured_drop_mag - model_drop_mag), 0.0, 4.0);
}

int nearest_danjon_class(double l) {
  return std::isfinite(l) ? static_cast<int>(std::lround(std::clamp(l, 0.0, 4.0))) : 0;
}

std::string_view danjon_description(double l) {
  // Danjon's five descriptions, as Espenak gives them (eclipsewise.com, "Danjon Scale of Lunar Eclipse
  // Brightness").
  static constexpr std::array<std::string_view, 5> kDescriptions = {
      "very dark: the Moon almost invisible at mid-totality",
      "dark, grey or brownish: details distinguishable only with difficulty",
      "deep red or rust-coloured: a very dark central shadow, the umbra's outer edge relatively bright",
      "brick-red: the umbra usually with a bright or yellow rim",
      "very bright copper-red or orange: the umbra's rim bluish and very bright",
  };
  return kDescriptions[static_cast<std::size_t>(nearest_danjon_class(l))];
}

}  // namespace zenith::astro
