#include "warp/output_window.h"

#include <string_view>

#include "core/json_reader.h"

namespace zenith::warp {

using config::brief;
using config::cat;
using nlohmann::json;

namespace {

/// An array of `n` integers in [lo, hi] at `key` of `r`.
template <std::size_t N>
std::array<int, N> integers(JsonReader& r, const std::string& key, int lo, int hi, const char* what) {
  const json& v = r.raw(key);
  std::array<int, N> out{};
  if (!v.is_array() || v.size() != N) r.fail(key, cat("= ", brief(v), ": must be ", what));
  for (std::size_t i = 0; i < N; ++i) {
    if (!v[i].is_number_integer() || v[i].get<long long>() < lo || v[i].get<long long>() > hi)
      r.fail(key, cat("= ", brief(v), ": must be ", what, ", each an integer in [", lo, ", ", hi, "]"));
    out[i] = v[i].get<int>();
  }
  return out;
}

bool boolean_or(JsonReader& r, const std::string& key, bool fallback) {
  if (!r.has(key)) return fallback;
  const json& v = r.raw(key);
  if (!v.is_boolean()) r.fail(key, cat("= ", brief(v), ": must be true or false"));
  return v.get<bool>();
}

}  // namespace

std::string OutputWindow::describe_monitor() const {
  if (monitor_name) return cat("monitor '", *monitor_name, "'");
  if (monitor_index) return cat("monitor ", *monitor_index);
  return "the desktop";
}

OutputWindow read_output_window(JsonReader& parent, const std::string& key, const std::string& output_name) {
  const json& v = parent.raw(key);
  if (!v.is_object())
    parent.fail(key, cat("= ", brief(v),
                         ": must be an object such as {\"monitor\": 0, \"fullscreen\": true} or "
                         "{\"position\": [x, y], \"size\": [w, h], \"decorated\": false}"));
  JsonReader r(v, parent.file(), parent.key_path(key));
  OutputWindow w;
  w.name = r.has("name") ? r.string("name") : output_name;
  if (w.name.empty()) r.fail("name", "= \"\": must not be empty");
  if (r.has("monitor")) {
    const json& m = r.raw("monitor");
    if (m.is_string() && !m.get<std::string>().empty())
      w.monitor_name = m.get<std::string>();
    else if (m.is_number_integer() && m.get<long long>() >= 0 && m.get<long long>() < 64)
      w.monitor_index = m.get<int>();
    else
      r.fail("monitor", cat("= ", brief(m),
                            ": must be a monitor's name (\"DP-1\"; `zenith displays` lists them) or "
                            "its index, an integer in [0, 63]"));
  }
  w.fullscreen = boolean_or(r, "fullscreen", false);
  if (r.has("position"))
    w.position =
        integers<2>(r, "position", -kMaxScreenCoordinate, kMaxScreenCoordinate, "[x, y] in screen coordinates");
  if (r.has("size")) {
    if (w.fullscreen)
      r.fail("size", "is not allowed with \"fullscreen\": true (the monitor's current video mode sets the size)");
    w.size = integers<2>(r, "size", 1, kMaxScreenCoordinate, "[width, height] in screen coordinates");
  }
  if (r.has("position") && w.fullscreen)
    r.fail("position", "is not allowed with \"fullscreen\": true (the window covers the monitor)");
  w.decorated = boolean_or(r, "decorated", !w.fullscreen);
  if (w.decorated && w.fullscreen) r.fail("decorated", "= true: a fullscreen window has no decoration");
  if (r.has("rect")) {
    w.rect = integers<4>(r, "rect", 0, kMaxScreenCoordinate, "[x, y, width, height] in the window's pixels");
    if ((*w.rect)[2] < 1 || (*w.rect)[3] < 1)
      r.fail("rect", cat("= ", brief(r.raw("rect")), ": width and height must be ≥ 1"));
  }
  w.vsync = boolean_or(r, "vsync", true);
  if (r.has("encoding")) {
    const json& e = r.raw("encoding");
    if (e.is_string() && e.get<std::string>() == "srgb") {
      w.gamma = 0.0;
    } else if (e.is_object()) {
      JsonReader g(e, r.file(), r.key_path("encoding"));
      w.gamma = g.number("gamma", 1.0, 3.0);
      g.finish();
    } else {
      r.fail("encoding", cat("= ", brief(e), ": must be \"srgb\" or {\"gamma\": γ} with γ in [1, 3]"));
    }
  }
  r.finish();
  return w;
}

}  // namespace zenith::warp
