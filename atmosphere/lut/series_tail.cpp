#include "atmosphere/lut/series_tail.h"

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace zenith::atmosphere::lut {

namespace {

/// The tail over parallel arrays of the same layout (texel-major, channel-minor).
double add_tail(std::vector<float>& last, const std::vector<float>& before_last, std::vector<float>& sum,
                std::size_t channels) {
  if (last.size() != before_last.size() || last.size() != sum.size() || channels == 0)
    throw std::invalid_argument("add_series_tail: the three tables differ in size");
  std::vector<double> last_sum(channels, 0.0), before_sum(channels, 0.0), cap(channels);
  for (std::size_t i = 0; i < last.size(); ++i) {
    last_sum[i % channels] += last[i];
    before_sum[i % channels] += before_last[i];
  }
  for (std::size_t c = 0; c < channels; ++c) cap[c] = series_tail_ratio_cap(last_sum[c], before_sum[c]);
  double total = 0.0;
  for (std::size_t i = 0; i < last.size(); ++i) {
    const float tail = static_cast<float>(series_tail_factor(last[i], before_last[i], cap[i % channels]) * last[i]);
    sum[i] += tail;
    last[i] = tail;
    total += tail;
  }
  return total;
}

}  // namespace

double add_series_tail(Table3D& last, const Table3D& before_last, Table3D& sum) {
  return add_tail(last.data, before_last.data, sum.data, last.channels);
}

double add_series_tail(Table2D& last, const Table2D& before_last, Table2D& sum) {
  return add_tail(last.data, before_last.data, sum.data, last.channels);
}

}  // namespace zenith::atmosphere::lut
