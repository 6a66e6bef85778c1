#include "warp/export_warp_map.h"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "warp/warped_projection.h"

namespace zenith::warp {

ExportedWarpMap export_warp_map(const OutputConfig& output) {
  if (!output.projection)
    throw std::invalid_argument("output '" + output.name + "': no projection (its warp cannot be used)");
  const int width = output.width_px, height = output.height_px;
  if (width > kMaxExportedWarpSidePx || height > kMaxExportedWarpSidePx)
    throw std::invalid_argument("output '" + output.name + "': " + std::to_string(width) + "x" +
                                std::to_string(height) +
                                " px: the exported warp map has 2 · side + 1 nodes per "
                                "side, so each side must be at most " +
                                std::to_string(kMaxExportedWarpSidePx) + " px");
  const auto* warped = dynamic_cast<const WarpedProjection*>(output.projection.get());

  ExportedWarpMap out;
  out.source_width_px = warped ? warped->base().width() : width;
  out.source_height_px = warped ? warped->base().height() : height;
  PfmImage& map = out.map;
  map.width = 2 * width + 1;
  map.height = 2 * height + 1;
  map.channels = 3;
  constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();
  map.samples.assign(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height) * 3, kNoData);
  const auto at = [&](int i, int j) { return &map.samples[(static_cast<std::size_t>(j) * map.width + i) * 3]; };

  // (u, v) at every node where the renderer has them.
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      // The renderer's own arguments: s = x_px / width with x_px = i / 2 (a pixel centre x + 0.5).
      const double s = (0.5 * i) / width, t = (0.5 * j) / height;
      std::optional<glm::dvec2> uv = glm::dvec2(s, t);
      if (warped) {
        const auto sample = warped->mesh().sample(s, t);
        uv = sample ? std::optional(glm::dvec2(sample->u, sample->v)) : std::nullopt;
      }
      if (!uv) continue;
      float* node = at(i, j);
      node[0] = static_cast<float>(uv->x);
      node[1] = static_cast<float>(uv->y);
      node[2] = 0.0f;
    }
  if (!warped) return out;

  // Corner and edge nodes without data next to pixel centres with data: the
  // mean of those centres.
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      if (i % 2 == 1 && j % 2 == 1) continue;  // a pixel centre
      float* node = at(i, j);
      if (std::isfinite(node[0])) continue;
      double u = 0.0, v = 0.0;
      int count = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ci = i + di, cj = j + dj;
          if (ci % 2 == 0 || cj % 2 == 0 || ci < 0 || cj < 0 || ci >= map.width || cj >= map.height) continue;
          const float* centre = at(ci, cj);
          if (!std::isfinite(centre[0])) continue;
          u += centre[0];
          v += centre[1];
          ++count;
        }
      if (count == 0) continue;
      node[0] = static_cast<float>(u / count);
      node[1] = static_cast<float>(v / count);
      node[2] = 0.0f;
    }
  return out;
}

}  // namespace zenith::warp
