#include "render/window/output_windows.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>
#include <stdexcept>

#include "render/gl/gl_error.h"
#include "render/window/frame_presenter.h"
#include "render/window/swap_sync.h"

namespace zenith::render::window {
namespace {

/// The keys that describe the window itself (not the output's place in it):
/// outputs sharing a window must agree on them.
bool same_window(const warp::OutputWindow& a, const warp::OutputWindow& b) {
  return a.monitor_name == b.monitor_name && a.monitor_index == b.monitor_index && a.fullscreen == b.fullscreen &&
         a.position == b.position && a.size == b.size && a.decorated == b.decorated && a.vsync == b.vsync;
}

/// The default window's size: the outputs side by side, shrunk to fit a
/// 1280 × 1024 screen area at first (it can be resized or made full screen).
std::array<int, 2> default_window_size(int width, int height) {
  const double shrink = std::min(1.0, std::min(1280.0 / width, 1024.0 / height));
  return {std::max(1, static_cast<int>(width * shrink)), std::max(1, static_cast<int>(height * shrink))};
}

}  // namespace

OutputWindows::OutputWindows(const std::vector<ShownOutput>& outputs, const std::string& title,
                             const gl::ContextOptions& context) {
  if (outputs.empty()) throw std::invalid_argument("OutputWindows: no outputs to show");
  // Group the outputs into windows, in order of first appearance.
  struct Plan {
    std::string name;
    std::optional<warp::OutputWindow> config;  // unset: the default window
    std::string first_output;
    std::vector<std::size_t> outputs;
  };
  std::vector<Plan> plans;
  std::map<std::string, std::size_t> by_name;
  placements_.resize(outputs.size());
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const ShownOutput& o = outputs[k];
    if (o.width_px < 1 || o.height_px < 1)
      throw std::invalid_argument(fmt::format("output '{}': size {}x{}", o.name, o.width_px, o.height_px));
    // The default window's key cannot clash with a configured name: those are never empty.
    const std::string key = o.window ? "w:" + o.window->name : std::string();
    auto [it, added] = by_name.emplace(key, plans.size());
    if (added) plans.push_back({o.window ? o.window->name : title, o.window, o.name, {}});
    Plan& plan = plans[it->second];
    if (o.window && !same_window(*plan.config, *o.window))
      throw std::invalid_argument(fmt::format(
          "outputs '{}' and '{}' share window '{}' but describe it differently (monitor, fullscreen, position, size, "
          "decorated, vsync): give every output of a window the same values, or different window names",
          plan.first_output, o.name, plan.name));
    plan.outputs.push_back(k);
    placements_[k] = {it->second, o.width_px, o.height_px, o.window ? o.window->rect : std::nullopt, 0};
  }

  const std::vector<MonitorInfo> monitors = list_monitors();
  for (const Plan& plan : plans) {
    WindowOptions w;
    w.title = plan.config ? fmt::format("{} — {}", title, plan.name) : title;
    bool vsync = true;
    if (plan.config) {
      const warp::OutputWindow& c = *plan.config;
      const MonitorInfo* monitor = find_monitor(monitors, c, fmt::format("output '{}'", plan.first_output));
      w.fullscreen = c.fullscreen;
      w.monitor = monitor != nullptr ? monitor->index : 0;
      w.decorated = c.decorated;
      w.hide_cursor = c.fullscreen;
      w.resizable = c.decorated;
      vsync = c.vsync;
      // Windowed: the given size, else the bounding box of its outputs' rectangles, else the first output's size.
      std::array<int, 2> size{outputs[plan.outputs.front()].width_px, outputs[plan.outputs.front()].height_px};
      if (c.size) {
        size = *c.size;
      } else {
        bool any_rect = false;
        std::array<int, 2> box{0, 0};
        for (const std::size_t k : plan.outputs)
          if (const auto& r = placements_[k].rect) {
            any_rect = true;
            box = {std::max(box[0], (*r)[0] + (*r)[2]), std::max(box[1], (*r)[1] + (*r)[3])};
          }
        if (any_rect) size = box;
      }
      w.width = size[0];
      w.height = size[1];
      if (!c.fullscreen && (c.position || monitor != nullptr)) {
        const std::array<int, 2> offset = c.position.value_or(std::array<int, 2>{0, 0});
        w.position = std::array<int, 2>{(monitor != nullptr ? monitor->x : 0) + offset[0],
                                        (monitor != nullptr ? monitor->y : 0) + offset[1]};
      }
    } else {
      for (const std::size_t k : plan.outputs) {
        placements_[k].side_by_side_x = combined_width_;
        combined_width_ += outputs[k].width_px;
        combined_height_ = std::max(combined_height_, outputs[k].height_px);
      }
      const std::array<int, 2> size = default_window_size(combined_width_, combined_height_);
      w.width = size[0];
      w.height = size[1];
    }
    // One vertical blank paces the node: the first window's; the others swap without waiting.
    w.swap_interval = windows_.empty() && vsync ? 1 : 0;
    const WindowContext* share = windows_.empty() ? nullptr : &windows_.front().context;
    Window window{WindowContext(w, context, share), plan.outputs, !plan.config, 0};
    glCreateFramebuffers(1, &window.framebuffer);
    gl::check_gl_error("OutputWindows: creating a framebuffer");
    const FramebufferSize fb = window.context.framebuffer_size();
    spdlog::info("window '{}': {}x{}{}{} on {}{}", plan.name, fb.width, fb.height, w.fullscreen ? ", fullscreen" : "",
                 w.swap_interval == 1 ? ", vsync" : "",
                 plan.config ? plan.config->describe_monitor() : std::string("the desktop"),
                 w.position ? fmt::format(" at ({}, {})", (*w.position)[0], (*w.position)[1]) : std::string());
    windows_.push_back(std::move(window));
  }
  windows_.front().context.make_current();
  // Late frames can only be told with vsync on (the first window's) and a known refresh rate.
  const bool first_vsync = !plans.front().config || plans.front().config->vsync;
  clock_ = PresentClock(first_vsync ? windows_.front().context.refresh_hz() : 0.0);
  sync_control_ = first_vsync && swap_sync_support(windows_.front().context).sync_control;
}

std::string OutputWindows::join_swap_group(unsigned group) {
  std::string line;
  for (std::size_t i = 0; i < windows_.size(); ++i) {  // the barrier once: it binds the group, not a window
    line = window::join_swap_group(windows_[i].context, group, i == 0);
    if (!line.starts_with("joined")) break;
  }
  return line;
}

OutputWindows::~OutputWindows() {
  for (Window& w : windows_) {
    if (w.framebuffer == 0) continue;
    try {
      w.context.make_current();
      glDeleteFramebuffers(1, &w.framebuffer);
    } catch (const std::exception&) {
      // The context is going away with its window: its framebuffer goes with it.
    }
  }
}

FramebufferRect OutputWindows::output_rect(std::size_t output) const {
  const Placement& p = placements_.at(output);
  const Window& w = windows_.at(p.window);
  const FramebufferSize fb = w.context.framebuffer_size();
  if (w.side_by_side) {
    const Letterbox box = letterbox(combined_width_, combined_height_, std::max(1, fb.width), std::max(1, fb.height));
    const double scale = static_cast<double>(box.width) / combined_width_;
    const int x0 = box.x + static_cast<int>(std::lround(p.side_by_side_x * scale));
    const int width = std::max(1, static_cast<int>(std::lround(p.width_px * scale)));
    const int height = std::max(1, static_cast<int>(std::lround(p.height_px * scale)));
    return {x0, box.y + box.height - height, width, height};  // top-aligned within the picture
  }
  if (!p.rect) return {0, 0, fb.width, fb.height};
  const auto& r = *p.rect;
  return {r[0], fb.height - r[1] - r[3], r[2], r[3]};
}

void OutputWindows::draw(Window& w, std::span<const gl::Texture* const> displays) {
  const FramebufferSize fb = w.context.framebuffer_size();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDisable(GL_FRAMEBUFFER_SRGB);  // the display pass encoded the values
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glViewport(0, 0, fb.width, fb.height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (fb.width < 1 || fb.height < 1) return;  // minimised
  for (const std::size_t k : w.outputs) {
    const gl::Texture* texture = k < displays.size() ? displays[k] : nullptr;
    if (texture == nullptr || texture->id() == 0) continue;
    const FramebufferRect r = output_rect(k);
    glNamedFramebufferTexture(w.framebuffer, GL_COLOR_ATTACHMENT0, texture->id(), 0);
    glNamedFramebufferReadBuffer(w.framebuffer, GL_COLOR_ATTACHMENT0);
    // Row 0 of the texture is the top of the picture: the destination's y runs downward.
    glBlitNamedFramebuffer(w.framebuffer, 0, 0, 0, texture->width(), texture->height(), r.x, r.y + r.height,
                           r.x + r.width, r.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  gl::check_gl_error("OutputWindows: drawing the outputs");
}

void OutputWindows::present(std::span<const gl::Texture* const> displays, PresentClock::Clock::time_point asked) {
  // The textures were written in the first window's context: the other
  // contexts wait (on the GPU) for those commands before reading them.
  const std::optional<std::int64_t> vblank_before =
      sync_control_ ? vblank_count(windows_.front().context) : std::nullopt;
  GLsync written = nullptr;
  if (windows_.size() > 1) written = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();
  for (std::size_t i = windows_.size(); i-- > 0;) {  // the first window last: it stays current
    Window& w = windows_[i];
    w.context.make_current();
    if (written != nullptr && i != 0) glWaitSync(written, 0, GL_TIMEOUT_IGNORED);
    draw(w, displays);
    if (i != 0) glFlush();
  }
  for (std::size_t i = windows_.size(); i-- > 1;) windows_[i].context.swap_buffers();
  windows_.front().context.swap_buffers();
  // With vsync the swap completes at the vertical blank: glFinish waits for it
  // (drivers queue the swap and return), so the clock sees when it showed.
  glFinish();
  const PresentClock::Clock::time_point done = PresentClock::Clock::now();
  std::optional<std::int64_t> vblanks;
  if (vblank_before)
    if (const std::optional<std::int64_t> after = vblank_count(windows_.front().context))
      vblanks = *after - *vblank_before;
  clock_.record(asked, done, vblanks);
  if (written != nullptr) glDeleteSync(written);
}

void OutputWindows::redraw_if_asked(std::span<const gl::Texture* const> displays) {
  bool drew = false;
  for (Window& w : windows_) {
    if (!w.context.take_redraw_request()) continue;
    w.context.make_current();
    draw(w, displays);
    w.context.swap_buffers();
    drew = true;
  }
  if (drew) windows_.front().context.make_current();
}

bool OutputWindows::poll_close_request() {
  windows_.front().context.poll_events();
  bool close = false;
  for (Window& w : windows_) {
    for (const KeyEvent& e : w.context.take_key_events())
      if (e.key == Key::escape && e.action == KeyAction::press) w.context.request_close();
    close = close || w.context.should_close();
  }
  return close;
}

}  // namespace zenith::render::window
