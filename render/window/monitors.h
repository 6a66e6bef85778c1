#pragma once
// The monitors a node's window system offers (GLFW's list: with NVIDIA Mosaic
// or AMD Eyefinity, a group of projectors is one large monitor), for placing
// outputs (warp/output_window.h) and for `zenith displays`. Main thread only.
#include <string>
#include <vector>

#include "warp/output_window.h"

namespace zenith::render::window {

struct MonitorInfo {
  int index = 0;                    ///< GLFW's order; 0 is the primary monitor
  std::string name;                 ///< the connector or the name the system gives ("DP-1", "HDMI-0", "screen")
  int x = 0, y = 0;                 ///< the monitor's origin on the virtual desktop, screen coordinates
  int width = 0, height = 0;        ///< its current video mode, pixels
  int refresh_hz = 0;               ///< its current refresh rate (0 where the system does not say)
  int width_mm = 0, height_mm = 0;  ///< physical size where known (0 otherwise)
};

/// The monitors, in GLFW's order. Throws std::runtime_error "no display: …" without a window system.
std::vector<MonitorInfo> list_monitors();

/// One line a monitor: "0: DP-1 1920x1200 at (0, 0), 60 Hz, 518x324 mm".
std::string describe_monitors(const std::vector<MonitorInfo>& monitors);

/// The monitor a window asks for (by name or index); nullptr when it names
/// none (the desktop). Throws std::invalid_argument naming the monitor asked
/// for, `what` (e.g. "output 'p1'"), and every monitor that exists with its
/// size and position, when there is no such monitor.
const MonitorInfo* find_monitor(const std::vector<MonitorInfo>& monitors, const warp::OutputWindow& window,
                                const std::string& what);

}  // namespace zenith::render::window
