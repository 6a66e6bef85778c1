#include "warp/warp_map_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace zenith::warp {
namespace {

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double x) { lo = std::min(lo, x), hi = std::max(hi, x); }
  double spread() const { return hi - lo; }
  double largest_magnitude() const { return std::max(std::abs(lo), std::abs(hi)); }
};

}  // namespace

std::vector<std::string> warp_map_warnings(const PfmImage& map, const WarpMapConventions& conventions,
                                           const std::string& source) {
  std::vector<std::string> warnings;
  if (map.channels < 2) return warnings;
  Range stored_u, stored_v, u, v;
  std::size_t valid = 0, outside = 0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      const double su = map.at(x, y, 0), sv = map.at(x, y, 1);
      if (!std::isfinite(su) || !std::isfinite(sv)) continue;
      const WarpSourcePoint p = to_source_point(su, sv, x, map.width, y, map.height, conventions);
      ++valid;
      stored_u.add(su), stored_v.add(sv), u.add(p.u), v.add(p.v);
      const auto in_range = [](double c) { return c >= -kSourceRangeTolerance && c <= 1.0 + kSourceRangeTolerance; };
      if (!in_range(p.u) || !in_range(p.v)) ++outside;
    }
  if (valid == 0) return warnings;

  const bool absolute = conventions.values == WarpValues::absolute;
  if (u.spread() <= kCollapsedSpread && v.spread() <= kCollapsedSpread) {
    std::string hint = "the map shows one source pixel everywhere";
    if (absolute && stored_u.largest_magnitude() <= kCollapsedSpread &&
        stored_v.largest_magnitude() <= kCollapsedSpread)
      hint = "all zeros: an Evans & Sutherland offset map meaning \"no distortion\"? Set \"values\": \"offsets\"";
    warnings.push_back(
        fmt::format("{}: every valid sample ({}) maps to one point (u, v) = ({:g}, {:g}) of the "
                    "source image: {}",
                    source, valid, u.lo, v.lo, hint));
    return warnings;
  }
  if (absolute && stored_u.largest_magnitude() <= kOffsetLikeMaxValue &&
      stored_v.largest_magnitude() <= kOffsetLikeMaxValue)
    warnings.push_back(
        fmt::format("{}: the values look like offsets from the regular grid, not absolute "
                    "positions (u in [{:g}, {:g}], v in [{:g}, {:g}], all within ±{:g}): set "
                    "\"values\": \"offsets\" if the map comes from an Evans & Sutherland export",
                    source, stored_u.lo, stored_u.hi, stored_v.lo, stored_v.hi, kOffsetLikeMaxValue));
  if (2 * outside > valid)
    warnings.push_back(
        fmt::format("{}: {} of {} valid samples ({:.0f} %) map outside the source image (u in "
                    "[{:g}, {:g}], v in [{:g}, {:g}], expected [0, 1]; read as {} values, v {}): "
                    "check \"values\", \"v_direction\" and \"row_order\" (docs/warp-meshes.md)",
                    source, outside, valid, 100.0 * static_cast<double>(outside) / static_cast<double>(valid), u.lo,
                    u.hi, v.lo, v.hi, to_string(conventions.values), to_string(conventions.v_direction)));
  return warnings;
}

}  // namespace zenith::warp
