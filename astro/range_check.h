#pragma once
// The range checks of astro/'s inputs, with one message form:
//   "<what> = <value>: must be in [lo, hi] <unit>"  (std::invalid_argument).
#include <string>

namespace zenith::astro {

/// Throws std::invalid_argument unless lo <= value <= hi (NaN fails).
void require_in_range(const std::string& what, double value, double lo, double hi, const std::string& unit);

}  // namespace zenith::astro
