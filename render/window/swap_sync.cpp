#include "render/window/swap_sync.h"

#include "render/window/window_context.h"

#include <epoxy/glx.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

// GLFW's native access for X11 and GLX (glfw3native.h declares them, but with
// GLFW_EXPOSE_NATIVE_X11 it also includes the RandR headers, which only a
// development package provides): the two functions are GLFW's public API.
extern "C" {
Display* glfwGetX11Display(void);
GLXWindow glfwGetGLXWindow(GLFWwindow* window);
}

namespace zenith::render::window {
namespace {

/// The window's X display and GLX drawable; nullopt on another platform (Wayland).
struct Native {
  Display* display = nullptr;
  GLXDrawable drawable = 0;
  int screen = 0;
};
std::optional<Native> native_of(const WindowContext& window) {
  Native n;
  n.display = glfwGetX11Display();
  n.drawable = glfwGetGLXWindow(window.glfw_window());
  if (n.display == nullptr || n.drawable == 0) return std::nullopt;
  n.screen = DefaultScreen(n.display);
  return n;
}

}  // namespace

SwapSyncSupport swap_sync_support(const WindowContext& window) {
  SwapSyncSupport s;
  const std::optional<Native> n = native_of(window);
  if (!n) return s;
  s.glx = true;
  s.swap_group = epoxy_has_glx_extension(n->display, n->screen, "GLX_NV_swap_group");
  if (s.swap_group) {
    GLuint groups = 0, barriers = 0;
    if (glXQueryMaxSwapGroupsNV(n->display, n->screen, &groups, &barriers)) {
      s.max_groups = groups;
      s.max_barriers = barriers;
    }
  }
  s.sync_control = epoxy_has_glx_extension(n->display, n->screen, "GLX_OML_sync_control");
  return s;
}

std::string join_swap_group(const WindowContext& window, unsigned group, bool bind_barrier) {
  const SwapSyncSupport s = swap_sync_support(window);
  if (!s.glx) return fmt::format("swap group {} not joined: the window is not a GLX window", group);
  if (!s.swap_group)
    return fmt::format(
        "swap group {} not joined: {} offers no GLX_NV_swap_group; the network barrier and vsync "
        "keep the projectors together (within a refresh)",
        group, window.renderer());
  if (group > s.max_groups)
    return fmt::format("swap group {} not joined: the driver has {} swap group{}", group, s.max_groups,
                       s.max_groups == 1 ? "" : "s");
  const std::optional<Native> n = native_of(window);
  if (!glXJoinSwapGroupNV(n->display, n->drawable, group))
    return fmt::format("swap group {} not joined: glXJoinSwapGroupNV failed", group);
  if (!bind_barrier) return fmt::format("joined swap group {}", group);
  if (s.max_barriers == 0)
    return fmt::format(
        "joined swap group {}; no swap barrier (no Quadro Sync board): nodes swap within a refresh of "
        "each other through the network barrier",
        group);
  if (!glXBindSwapBarrierNV(n->display, group, 1))
    return fmt::format(
        "joined swap group {}; binding it to swap barrier 1 failed (is Frame Lock on in nvidia-settings?)", group);
  return fmt::format(
      "joined swap group {} and bound it to swap barrier 1 (Quadro Sync: every node swaps on the same "
      "vblank)",
      group);
}

std::optional<std::int64_t> vblank_count(const WindowContext& window) {
  const std::optional<Native> n = native_of(window);
  if (!n) return std::nullopt;
  int64_t ust = 0, msc = 0, sbc = 0;
  if (!glXGetSyncValuesOML(n->display, n->drawable, &ust, &msc, &sbc)) return std::nullopt;
  return msc;
}

}  // namespace zenith::render::window
