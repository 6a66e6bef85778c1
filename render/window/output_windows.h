#pragma once
// The windows of a render node (docs/window.md, "Outputs on displays"): each
// output of the node in a window of its own, fullscreen on a monitor or placed
// on the desktop, or several outputs in one window, each in its rectangle (a
// desktop spanning several projectors, as NVIDIA Mosaic and AMD Eyefinity
// present them). Outputs without a "window" key share one decorated window,
// side by side (the node's default window).
//
// One GL context renders (the first window's); every other window's context
// shares its objects (GLFW shared contexts), so the renderer renders each output
// once, into a texture, and each window draws the textures of its outputs:
// a blit per output into its rectangle, nearest-neighbour (a rectangle of the
// output's size shows exactly its pixels), flipped so that row 0 is at the top.
// Presenting draws every window, then swaps them all: the windows without
// vsync first, the first window (vsync on unless its config says "vsync":
// false) last, so one vertical blank paces the node. Main thread only (GLFW).
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "render/gl/texture.h"
#include "render/window/monitors.h"
#include "render/window/present_clock.h"
#include "render/window/window_context.h"
#include "warp/output_window.h"

namespace zenith::render::window {

/// One output a node shows.
struct ShownOutput {
  std::string name;
  int width_px = 0, height_px = 0;
  std::optional<warp::OutputWindow> window;  ///< unset: the default window
};

/// A rectangle of a window's framebuffer in GL's convention (pixels, origin at the bottom left).
struct FramebufferRect {
  int x = 0, y = 0, width = 0, height = 0;
  bool operator==(const FramebufferRect&) const = default;
};

class OutputWindows {
 public:
  /// Opens the windows of `outputs` (the default window titled `title`). The
  /// first window's context is current afterwards. Throws std::invalid_argument
  /// for a monitor that does not exist (naming the monitors that do, with their
  /// sizes and positions) and for outputs that share a window but give it
  /// different monitors, modes, positions, sizes, decorations or vsync;
  /// std::runtime_error without a display or when a window cannot be made.
  OutputWindows(const std::vector<ShownOutput>& outputs, const std::string& title,
                const gl::ContextOptions& context = {});
  ~OutputWindows();
  OutputWindows(const OutputWindows&) = delete;
  OutputWindows& operator=(const OutputWindows&) = delete;

  /// The window whose context renders (and is current between calls).
  WindowContext& primary() { return windows_.front().context; }
  const WindowContext& primary() const { return windows_.front().context; }
  std::size_t window_count() const { return windows_.size(); }
  const WindowContext& window(std::size_t index) const { return windows_.at(index).context; }

  /// Draws output k's texture `displays[k]` (an rgba8 or rgba16 display
  /// texture of its size, row 0 at the top; nullptr: a black rectangle) into
  /// its rectangle of its window, then swaps every window. `asked`: when the
  /// Present arrived (PresentClock). Leaves the first window's context current.
  void present(std::span<const gl::Texture* const> displays, PresentClock::Clock::time_point asked);
  /// Draws the textures again in the windows the window system asked to
  /// redraw (exposed, resized) and swaps those.
  void redraw_if_asked(std::span<const gl::Texture* const> displays);
  /// Processes window events; true once a window was closed or Escape was pressed in one.
  bool poll_close_request();

  /// Where output k is drawn now, in its window's framebuffer.
  FramebufferRect output_rect(std::size_t output) const;
  /// The presents so far and how many were late (the late-frame hook).
  const PresentClock& clock() const { return clock_; }
  /// Joins every window to swap group `group` (≥ 1; GLX_NV_swap_group) and
  /// binds it to swap barrier 1 (render/window/swap_sync.h). Returns the log
  /// line saying what was done, or why not; never throws.
  std::string join_swap_group(unsigned group);
  /// Whether late presents are counted from the display's vblank counter
  /// (GLX_OML_sync_control) rather than the wall clock.
  bool counts_vblanks() const { return sync_control_; }

 private:
  struct Window {
    WindowContext context;
    std::vector<std::size_t> outputs;
    bool side_by_side = false;  ///< the default window: its outputs letterboxed side by side
    unsigned framebuffer = 0;   ///< this context's read framebuffer for the blits
  };
  struct Placement {
    std::size_t window = 0;
    int width_px = 0, height_px = 0;
    std::optional<std::array<int, 4>> rect;  ///< top-left origin, from the config
    int side_by_side_x = 0;                  ///< the default window: first column in the combined picture
  };
  void draw(Window& w, std::span<const gl::Texture* const> displays);

  std::vector<Window> windows_;
  std::vector<Placement> placements_;             ///< per output
  int combined_width_ = 0, combined_height_ = 0;  ///< the default window's picture
  PresentClock clock_;
  bool sync_control_ = false;  ///< GLX_OML_sync_control on the first window's display
};

}  // namespace zenith::render::window
