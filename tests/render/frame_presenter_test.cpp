// The window path's presentation (render/window/frame_presenter.h) drawn into
// a framebuffer object on the headless EGL context and read back: the bytes
// must be the PNG writer's (image::display_byte) within 1 (the GL conversion to
// 8 bits may pick either nearest byte: expect_presented), the right way up,
// letterboxed with black bars. WindowContext itself needs a display: its tests
// run where DISPLAY is set (ctest runs them under xvfb-run) and skip otherwise.
#include "render/window/frame_presenter.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/tone_mapping.h"
#include "render/gl/egl_context.h"
#include "render/window/window_context.h"

namespace zenith::render::window {
namespace {

gl::HeadlessContext& context() {
  static gl::HeadlessContext c;
  c.make_current();
  return c;
}

/// An RGBA8 framebuffer object of a given size; read() returns its rows top first.
class Rgba8Target {
 public:
  Rgba8Target(int width, int height) : width_(width), height_(height) {
    glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    glTextureStorage2D(texture_, 1, GL_RGBA8, width, height);
    glCreateFramebuffers(1, &framebuffer_);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture_, 0);
    EXPECT_EQ(glCheckNamedFramebufferStatus(framebuffer_, GL_DRAW_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  }
  ~Rgba8Target() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
  }
  Rgba8Target(const Rgba8Target&) = delete;
  Rgba8Target& operator=(const Rgba8Target&) = delete;

  PresentTarget target() const { return {framebuffer_, width_, height_}; }

  /// RGBA bytes, row 0 at the top (GL reads bottom first: flipped here).
  std::vector<std::uint8_t> read() const { return read_framebuffer(framebuffer_, width_, height_); }

  static std::vector<std::uint8_t> read_framebuffer(unsigned framebuffer, int width, int height) {
    std::vector<std::uint8_t> bottom_up(static_cast<std::size_t>(width) * height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    if (framebuffer == 0) glReadBuffer(GL_BACK);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
    std::vector<std::uint8_t> top_down(bottom_up.size());
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height; ++y)
      std::copy_n(bottom_up.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row), row,
                  top_down.begin() + static_cast<std::ptrdiff_t>(y * row));
    return top_down;
  }

 private:
  int width_, height_;
  unsigned texture_ = 0, framebuffer_ = 0;
};

/// A frame whose values sweep 1e-5 … 1e3 (log-spaced, a different phase per
/// channel, so rows and channels are all told apart), with 0, negative, NaN
/// and +∞ in a few pixels.
std::vector<float> test_frame(int width, int height) {
  std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
  const int n = width * height;
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double t = std::fmod(static_cast<double>(i) / n + c / 3.0, 1.0);
      rgb[static_cast<std::size_t>(i) * 3 + c] = static_cast<float>(std::pow(10.0, -5.0 + 8.0 * t));
    }
  rgb[0] = 0.0f;
  rgb[4] = -1.0f;
  rgb[8] = std::numeric_limits<float>::quiet_NaN();
  rgb[9] = std::numeric_limits<float>::infinity();
  rgb[rgb.size() - 1] = 0.5f;
  return rgb;
}

/// Each presented pixel against display_byte of the frame, letterbox `box`
/// (bottom-left origin) of a target read top first; outside the box black.
void expect_presented(const std::vector<std::uint8_t>& bytes, int target_width, int target_height,
                      const std::vector<float>& rgb, int width, int height, const Letterbox& box,
                      image::ToneMapping tone) {
  int mismatches = 0, off_by_one = 0;
  for (int y = 0; y < target_height; ++y)
    for (int x = 0; x < target_width; ++x) {
      const std::uint8_t* p = &bytes[(static_cast<std::size_t>(y) * target_width + x) * 4];
      const int y_up = target_height - 1 - y;  // the letterbox's rows count from the bottom
      const bool inside = x >= box.x && x < box.x + box.width && y_up >= box.y && y_up < box.y + box.height;
      for (int c = 0; c < 3; ++c) {
        int expected = 0;
        if (inside) {
          // The frame pixel under this target pixel's centre (nearest-neighbour scaling).
          const int fx = static_cast<int>((x - box.x + 0.5) * width / box.width);
          const int fy = static_cast<int>((y - (target_height - box.y - box.height) + 0.5) * height / box.height);
          expected = image::display_byte(rgb[(static_cast<std::size_t>(fy) * width + fx) * 3 + c], tone);
        }
        const int diff = std::abs(static_cast<int>(p[c]) - expected);
        if (diff == 1) ++off_by_one;
        if (diff > 1 && ++mismatches <= 5)
          ADD_FAILURE() << "pixel (" << x << ", " << y << ") channel " << c << ": " << int(p[c]) << ", expected "
                        << expected << " (" << image::to_string(tone) << ")";
      }
      EXPECT_EQ(p[3], 255) << "alpha at (" << x << ", " << y << ")";
    }
  EXPECT_EQ(mismatches, 0);
  // Within 1, and no bound on how many: GL 4.5 (section 2.3.5.2, conversion to
  // normalized fixed point) lets convert_float_uint return either of the two
  // integers nearest to c·255 ("rounding to nearest is preferred"), and the
  // shader's float exp and pow are a few ulp from the CPU's double ones, so any
  // byte may land on either side of a half. NVIDIA (580.159.04) gave 16 and 24
  // bytes off by one of the 192 of FollowsTheFrameSize's 8×8 target, where each
  // frame pixel of a 2×2 or 3×3 frame covers 7 to 16 target pixels; llvmpipe
  // (round to nearest) a few. Logged, not asserted.
  if (off_by_one > 0)
    std::printf("  %d of %d bytes off by one (allowed: either nearest byte)\n", off_by_one,
                target_width * target_height * 3);
}

TEST(Letterbox, KeepsTheAspectRatioCentred) {
  const Letterbox same = letterbox(160, 90, 160, 90);
  EXPECT_EQ(same.x, 0);
  EXPECT_EQ(same.y, 0);
  EXPECT_EQ(same.width, 160);
  EXPECT_EQ(same.height, 90);
  const Letterbox wide = letterbox(4, 2, 16, 4);  // bars left and right
  EXPECT_EQ(wide.x, 4);
  EXPECT_EQ(wide.y, 0);
  EXPECT_EQ(wide.width, 8);
  EXPECT_EQ(wide.height, 4);
  const Letterbox tall = letterbox(16, 9, 640, 480);  // bars above and below
  EXPECT_EQ(tall.x, 0);
  EXPECT_EQ(tall.width, 640);
  EXPECT_EQ(tall.height, 360);
  EXPECT_EQ(tall.y, 60);
  const Letterbox tiny = letterbox(1000, 1, 10, 10);  // never empty
  EXPECT_EQ(tiny.width, 10);
  EXPECT_EQ(tiny.height, 1);
  EXPECT_THROW(letterbox(0, 1, 1, 1), std::invalid_argument);
  EXPECT_THROW(letterbox(1, 1, 1, -1), std::invalid_argument);
}

TEST(FramePresenter, PresentedBytesAreThePngWritersBytes) {
  context();
  const int width = 61, height = 37;  // odd sizes: rows of 12·61 bytes, no power-of-two luck
  const std::vector<float> rgb = test_frame(width, height);
  FramePresenter presenter;
  Rgba8Target target(width, height);
  for (image::ToneMapping tone : {image::ToneMapping::exponential, image::ToneMapping::clamp}) {
    SCOPED_TRACE(image::to_string(tone));
    presenter.present(rgb, width, height, tone, target.target());
    expect_presented(target.read(), width, height, rgb, width, height, {0, 0, width, height}, tone);
  }
  EXPECT_EQ(presenter.frame_width(), width);
  EXPECT_EQ(presenter.frame_height(), height);
}

TEST(FramePresenter, LetterboxesWithBlackBarsTheRightWayUp) {
  context();
  const int width = 4, height = 2;
  std::vector<float> rgb(width * height * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.05f * static_cast<float>(i + 1);
  FramePresenter presenter;
  {
    Rgba8Target wide(16, 4);  // 2× scale, bars of 4 columns on both sides
    presenter.present(rgb, width, height, image::ToneMapping::clamp, wide.target());
    const auto bytes = wide.read();
    expect_presented(bytes, 16, 4, rgb, width, height, letterbox(width, height, 16, 4), image::ToneMapping::clamp);
    // The frame's first pixel (top left) at the box's top-left corner.
    EXPECT_NEAR(bytes[(0 * 16 + 4) * 4], image::display_byte(rgb[0], image::ToneMapping::clamp), 1);
    EXPECT_EQ(bytes[(0 * 16 + 3) * 4], 0);
  }
  {
    Rgba8Target tall(8, 12);                                   // 2× scale, bars of 4 rows above and below
    presenter.draw(image::ToneMapping::clamp, tall.target());  // the uploaded frame, drawn again
    expect_presented(tall.read(), 8, 12, rgb, width, height, letterbox(width, height, 8, 12),
                     image::ToneMapping::clamp);
  }
}

TEST(FramePresenter, FollowsTheFrameSize) {
  context();
  FramePresenter presenter;
  Rgba8Target target(8, 8);
  for (int size : {2, 8, 3}) {
    const std::vector<float> rgb = test_frame(size, size);
    presenter.present(rgb, size, size, image::ToneMapping::exponential, target.target());
    EXPECT_EQ(presenter.frame_width(), size);
    expect_presented(target.read(), 8, 8, rgb, size, size, letterbox(size, size, 8, 8),
                     image::ToneMapping::exponential);
  }
}

TEST(FramePresenter, RefusesBadInput) {
  context();
  FramePresenter presenter;
  EXPECT_THROW(presenter.draw(image::ToneMapping::clamp, {0, 4, 4}), std::logic_error);
  const std::vector<float> rgb(4 * 4 * 3, 0.5f);
  EXPECT_THROW(presenter.upload(rgb, 4, 5), std::invalid_argument);
  EXPECT_THROW(presenter.upload(rgb, 0, 4), std::invalid_argument);
  presenter.upload(rgb, 4, 4);
  EXPECT_THROW(presenter.draw(image::ToneMapping::clamp, {0, 0, 4}), std::invalid_argument);
}

// --- WindowContext: needs a display (ctest runs these under xvfb-run). ---

bool have_display() {
  const char* display = std::getenv("DISPLAY");
  return display != nullptr && *display != '\0';
}

TEST(WindowContext, RefusesClearlyWithoutADisplay) {
  // Without DISPLAY GLFW cannot reach an X server. The environment is restored
  // afterwards so later tests still see the display.
  const char* display = std::getenv("DISPLAY");
  const std::optional<std::string> saved = display != nullptr ? std::optional<std::string>(display) : std::nullopt;
  unsetenv("DISPLAY");
  try {
    WindowContext window;
    ADD_FAILURE() << "a window opened without DISPLAY";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no display: set DISPLAY or use the headless path (omit --window)"),
              std::string::npos)
        << e.what();
  }
  if (saved) setenv("DISPLAY", saved->c_str(), 1);
}

TEST(WindowContext, OpensAGl45CoreWindowAndPresents) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  WindowOptions options;
  options.width = 64;
  options.height = 32;
  options.resizable = false;
  WindowContext window(options);
  EXPECT_TRUE(window.is_current());
  EXPECT_GE(window.gl_major() * 10 + window.gl_minor(), 45) << window.version();
  EXPECT_FALSE(window.renderer().empty());
  const FramebufferSize fb = window.framebuffer_size();
  ASSERT_GT(fb.width, 0);
  ASSERT_GT(fb.height, 0);
  EXPECT_FALSE(window.should_close());
  EXPECT_TRUE(window.take_redraw_request());  // the first frame is always due
  EXPECT_FALSE(window.take_redraw_request());

  // The same program and bytes as on the headless context, into the window's back buffer.
  const std::vector<float> rgb = test_frame(64, 32);
  FramePresenter presenter;
  presenter.present(rgb, 64, 32, image::ToneMapping::exponential, {0, fb.width, fb.height});
  expect_presented(Rgba8Target::read_framebuffer(0, fb.width, fb.height), fb.width, fb.height, rgb, 64, 32,
                   letterbox(64, 32, fb.width, fb.height), image::ToneMapping::exponential);
  window.swap_buffers();
  window.poll_events();
  EXPECT_TRUE(window.take_key_events().empty());

  window.request_close();
  EXPECT_TRUE(window.should_close());
}

TEST(WindowContext, TwoWindowsShareGlfwAndMove) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  WindowOptions options;
  options.width = 32;
  options.height = 32;
  options.visible = false;
  std::optional<WindowContext> first(std::in_place, options);
  WindowContext second(options);
  EXPECT_TRUE(second.is_current());
  first.reset();  // GLFW must stay initialised for the second window
  second.make_current();
  EXPECT_TRUE(second.is_current());
  WindowContext moved(std::move(second));
  EXPECT_TRUE(moved.is_current());
  EXPECT_GT(moved.framebuffer_size().width, 0);
  EXPECT_THROW(second.make_current(), std::logic_error);  // NOLINT(bugprone-use-after-move)
}

TEST(WindowContext, TakesTurnsWithAHeadlessContextOnOneThread) {
  // zenith render --window: tables are precomputed on a headless EGL context
  // while the window (GLX) exists. libglvnd allows one current context per
  // thread across the two APIs.
  if (!have_display()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  WindowOptions options;
  options.width = 16;
  options.height = 16;
  options.visible = false;
  WindowContext window(options);  // releases the EGL context current from earlier tests, if any
  ASSERT_TRUE(window.is_current());
  window.release_current();
  EXPECT_FALSE(window.is_current());
  {
    gl::HeadlessContext headless;  // EGL refuses while the GLX context is current
    EXPECT_TRUE(headless.is_current());
    window.make_current();  // replaces the current EGL context
    EXPECT_TRUE(window.is_current());
    EXPECT_FALSE(headless.is_current());
    window.release_current();
    headless.make_current();
    EXPECT_TRUE(headless.is_current());
  }
  window.make_current();
  FramePresenter presenter;  // GL works on the window again
  const std::vector<float> rgb(16 * 16 * 3, 0.25f);
  presenter.present(rgb, 16, 16, image::ToneMapping::clamp, {0, 16, 16});
  const auto bytes = Rgba8Target::read_framebuffer(0, 16, 16);
  EXPECT_NEAR(bytes[0], image::display_byte(0.25f, image::ToneMapping::clamp), 1);
}

}  // namespace
}  // namespace zenith::render::window
