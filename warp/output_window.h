#pragma once
// Where an output is shown on a render node's displays: the "window" key of an
// output in a viewport config (docs/window.md, "Outputs on displays").
//
//   "window": {"monitor": "DP-1", "fullscreen": true}                a projector on its own connector
//   "window": {"monitor": 0, "fullscreen": true}                     …by index (GLFW's order, 0 = primary)
//   "window": {"position": [1920, 0], "size": [1920, 1200],          an undecorated window placed on the
//              "decorated": false}                                    desktop (several projectors as one)
//   "window": {"name": "wall", "monitor": 0, "fullscreen": true,     outputs sharing one window (a Mosaic or
//              "rect": [1920, 0, 1920, 1080]}                         Eyefinity desktop): each in its rectangle
//
// Keys: "name" (outputs with the same name share one window; default the
// output's own name), "monitor" (a name or an index), "fullscreen" (default
// false), "position" ([x, y] screen coordinates of the window's top-left
// corner; with "monitor", relative to that monitor's origin), "size" ([w, h]
// in screen coordinates; default the output's size; not with "fullscreen":
// the monitor's current mode decides), "decorated" (default true; fullscreen
// windows have no decoration), "rect" ([x, y, w, h]: where in the window the
// output is drawn, top-left origin, in pixels; default the whole window),
// "vsync" (default true: swaps wait for the display's refresh),
// "encoding" ("srgb", the default, or {"gamma": γ} with γ in [1, 3]: a
// projector calibrated to a power law).
//
// Pure data, no window system: render/window/output_windows.h opens them and
// checks what only the window system knows (that a monitor exists).
#include <array>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace zenith {
class JsonReader;  // core/json_reader.h
}

namespace zenith::warp {

/// Screen coordinates and sizes are limited to this magnitude (a desktop of
/// several 8K projectors side by side fits).
inline constexpr int kMaxScreenCoordinate = 65536;

struct OutputWindow {
  std::string name;  ///< the window's name; outputs with equal names share it
  std::optional<std::string> monitor_name;
  std::optional<int> monitor_index;  ///< at most one of monitor_name, monitor_index
  bool fullscreen = false;
  std::optional<std::array<int, 2>> position;  ///< top-left corner, screen coordinates
  std::optional<std::array<int, 2>> size;      ///< screen coordinates (not with fullscreen)
  bool decorated = true;
  std::optional<std::array<int, 4>> rect;  ///< x, y, width, height in the window, pixels, top-left origin
  bool vsync = true;
  /// The display's transfer function: 0 for sRGB, else the exponent γ of V = L^(1/γ).
  double gamma = 0.0;

  /// "monitor 'DP-1'", "monitor 0", or "the desktop".
  std::string describe_monitor() const;
};

/// Reads the "window" object of output `output_name` (the key `key` of `r`).
/// Throws zenith::ConfigError naming the key for an unknown key, a value of the
/// wrong type or out of range, both a monitor name and index, "size" or
/// "decorated": true with "fullscreen", or a rect with a side below 1.
OutputWindow read_output_window(JsonReader& r, const std::string& key, const std::string& output_name);

}  // namespace zenith::warp
