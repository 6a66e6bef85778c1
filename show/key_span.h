#pragma once
// Where a show time falls among a track's key times.
#include <cstddef>
#include <vector>

namespace zenith::show {

/// Segment `segment` runs from key `segment` to key `segment + 1`; `fraction`
/// in [0, 1] is how far along it the time is, linearly in time.
struct KeySpan {
  std::size_t segment = 0;
  double fraction = 0.0;
};

/// Locates `t_s` among strictly increasing `key_times_s` (at least one).
/// Times before the first key give (0, 0), after the last (last segment, 1);
/// a single key gives (0, 0). A time equal to key i > 0 gives (i, 0) except
/// for the last key, (n − 2, 1): exactly the key, never a blend.
KeySpan locate(const std::vector<double>& key_times_s, double t_s);

}  // namespace zenith::show
