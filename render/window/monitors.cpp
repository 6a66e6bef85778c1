#include "render/window/monitors.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <stdexcept>

#include "render/window/glfw_library.h"

namespace zenith::render::window {

std::vector<MonitorInfo> list_monitors() {
  const std::shared_ptr<GlfwLibrary> library = acquire_glfw();
  int count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&count);
  std::vector<MonitorInfo> out;
  for (int i = 0; i < count; ++i) {
    MonitorInfo m;
    m.index = i;
    const char* name = glfwGetMonitorName(monitors[i]);
    m.name = name != nullptr ? name : fmt::format("monitor-{}", i);
    glfwGetMonitorPos(monitors[i], &m.x, &m.y);
    if (const GLFWvidmode* mode = glfwGetVideoMode(monitors[i])) {
      m.width = mode->width;
      m.height = mode->height;
      m.refresh_hz = mode->refreshRate;
    }
    glfwGetMonitorPhysicalSize(monitors[i], &m.width_mm, &m.height_mm);
    out.push_back(std::move(m));
  }
  return out;
}

std::string describe_monitors(const std::vector<MonitorInfo>& monitors) {
  if (monitors.empty()) return "  (the window system reports no monitor)\n";
  std::string text;
  for (const MonitorInfo& m : monitors) {
    text += fmt::format("  {}: {} {}x{} at ({}, {})", m.index, m.name, m.width, m.height, m.x, m.y);
    if (m.refresh_hz > 0) text += fmt::format(", {} Hz", m.refresh_hz);
    if (m.width_mm > 0 && m.height_mm > 0) text += fmt::format(", {}x{} mm", m.width_mm, m.height_mm);
    text += m.index == 0 ? " (primary)\n" : "\n";
  }
  return text;
}

const MonitorInfo* find_monitor(const std::vector<MonitorInfo>& monitors, const warp::OutputWindow& window,
                                const std::string& what) {
  for (const MonitorInfo& m : monitors) {
    if (window.monitor_name && m.name == *window.monitor_name) return &m;
    if (window.monitor_index && m.index == *window.monitor_index) return &m;
  }
  if (!window.monitor_name && !window.monitor_index) {
    if (window.fullscreen && !monitors.empty()) return &monitors.front();  // fullscreen on the primary monitor
    return nullptr;
  }
  throw std::invalid_argument(fmt::format("{}: window '{}' asks for {}, which does not exist; the monitors are:\n{}",
                                          what, window.name, window.describe_monitor(), describe_monitors(monitors)));
}

}  // namespace zenith::render::window
