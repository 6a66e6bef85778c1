#include "warp/dome_tiles.h"

#include <algorithm>
#include <cmath>

#include "warp/fisheye_projection.h"

namespace zenith::warp {

std::optional<std::vector<std::array<int, 2>>> dome_tile_origins(const std::vector<const OutputConfig*>& outputs) {
  if (outputs.empty()) return std::nullopt;
  std::vector<const FisheyeProjection*> fisheyes;
  for (const OutputConfig* o : outputs) {
    const auto* f = dynamic_cast<const FisheyeProjection*>(o->projection.get());
    if (f == nullptr ||
        f->radius_px() != dynamic_cast<const FisheyeProjection*>(outputs.front()->projection.get())->radius_px())
      return std::nullopt;
    fisheyes.push_back(f);
  }
  double max_cx = 0.0, max_cy = 0.0;
  for (const FisheyeProjection* f : fisheyes) {
    max_cx = std::max(max_cx, f->centre_x_px());
    max_cy = std::max(max_cy, f->centre_y_px());
  }
  std::vector<std::array<int, 2>> origins;
  for (const FisheyeProjection* f : fisheyes) {
    const double x0 = max_cx - f->centre_x_px(), y0 = max_cy - f->centre_y_px();
    if (x0 != std::floor(x0) || y0 != std::floor(y0)) return std::nullopt;  // stitching needs whole pixels
    origins.push_back({static_cast<int>(x0), static_cast<int>(y0)});
  }
  return origins;
}

}  // namespace zenith::warp
