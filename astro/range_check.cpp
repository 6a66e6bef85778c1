#include "astro/range_check.h"

#include <fmt/format.h>

#include <stdexcept>

namespace zenith::astro {

void require_in_range(const std::string& what, double value, double lo, double hi, const std::string& unit) {
  if (!(value >= lo && value <= hi))
    throw std::invalid_argument(fmt::format("{} = {}: must be in [{}, {}] {}", what, value, lo, hi, unit));
}

}  // namespace zenith::astro
