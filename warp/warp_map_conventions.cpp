#include "warp/warp_map_conventions.h"

namespace zenith::warp {

const char* to_string(WarpValues values) {
  switch (values) {
    case WarpValues::absolute: return "absolute";
    case WarpValues::offsets: return "offsets";
  }
  return "?";
}

const char* to_string(WarpVDirection direction) {
  switch (direction) {
    case WarpVDirection::down: return "down";
    case WarpVDirection::up: return "up";
  }
  return "?";
}

WarpSourcePoint to_source_point(double stored_u, double stored_v, int column, int columns, int row, int rows,
                                const WarpMapConventions& conventions) {
  const bool v_up = conventions.v_direction == WarpVDirection::up;
  double u = stored_u, v = stored_v;
  if (conventions.values == WarpValues::offsets) {
    const double s_node = columns > 1 ? static_cast<double>(column) / (columns - 1) : 0.0;
    const double t_node = rows > 1 ? static_cast<double>(row) / (rows - 1) : 0.0;
    u += s_node;
    v += v_up ? 1.0 - t_node : t_node;  // the node's own place, in the map's v direction
  }
  return {u, v_up ? 1.0 - v : v};
}

}  // namespace zenith::warp
