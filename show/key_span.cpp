#include "show/key_span.h"

#include <algorithm>

namespace zenith::show {

KeySpan locate(const std::vector<double>& key_times_s, double t_s) {
  const std::size_t n = key_times_s.size();
  if (n < 2 || !(t_s > key_times_s.front())) return {0, 0.0};
  if (t_s >= key_times_s.back()) return {n - 2, 1.0};
  // The first key strictly after t; t lies in [key i, key i + 1).
  const auto after = std::upper_bound(key_times_s.begin(), key_times_s.end(), t_s);
  const std::size_t i = std::size_t(after - key_times_s.begin()) - 1;
  const double t0 = key_times_s[i], t1 = key_times_s[i + 1];
  return {i, t_s == t0 ? 0.0 : (t_s - t0) / (t1 - t0)};
}

}  // namespace zenith::show
