#pragma once
// What the driver offers to put a node's swaps on the same vertical blank as
// every other node's (docs/cluster.md, "Pacing and swap groups"):
//
//  - GLX_NV_swap_group: the node's windows join swap group G (they swap
//    together), and the group is bound to swap barrier 1 — with a Quadro Sync
//    (Frame Lock) board cabled between the machines, every bound group of the
//    cluster swaps on the same vblank, in hardware. Where the extension is
//    missing (Mesa, an AMD or consumer board), the network barrier (every node
//    swaps right after the master's Present) plus vsync is what keeps the
//    projectors together: within a refresh, not to the vblank.
//  - GLX_OML_sync_control: the display's vblank counter (MSC), so a node knows
//    exactly how many refreshes a present took instead of estimating it from
//    the wall clock (render/window/present_clock.h).
//
// Both are queried on the window's GLX display; nothing here needs a GPU to
// build or to run (on llvmpipe both report "not offered").
#include <cstdint>
#include <optional>
#include <string>

namespace zenith::render::window {

class WindowContext;

/// What swap_sync_support() found on a window's display.
struct SwapSyncSupport {
  bool glx = false;                           ///< the window is a GLX (X11) window
  bool swap_group = false;                    ///< GLX_NV_swap_group
  unsigned max_groups = 0, max_barriers = 0;  ///< glXQueryMaxSwapGroupsNV
  bool sync_control = false;                  ///< GLX_OML_sync_control
};
SwapSyncSupport swap_sync_support(const WindowContext& window);

/// Joins `window` to swap group `group` (≥ 1) and, the first time, binds the
/// group to barrier 1 when the driver has a barrier. Returns a line for the
/// log saying what was done, or why not (never throws: a missing swap group
/// leaves the network barrier plus vsync).
std::string join_swap_group(const WindowContext& window, unsigned group, bool bind_barrier);

/// The display's vblank counter (GLX_OML_sync_control's MSC) of `window`,
/// whose display offers the extension (swap_sync_support().sync_control);
/// nullopt when the query fails.
std::optional<std::int64_t> vblank_count(const WindowContext& window);

}  // namespace zenith::render::window
