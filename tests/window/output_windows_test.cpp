// A node's outputs on displays (render/window/output_windows.h), checked as a
// user sees them: on a virtual display (ctest runs this under xvfb-run with a
// 256 × 96 screen, two 128 × 96 "projectors" side by side), the windows are
// opened from "window" configs, a frame is rendered into textures, encoded on
// the GPU and presented, and the screen is captured (XGetImage of the root
// window). Each output's rectangle of the screen must equal the same frame
// rendered through the file path (Renderer::render_image, written as a PNG by
// the PNG writer and read back) within 1/255 per channel. Without a display the
// tests skip (the PresentClock tests always run).
#include "render/window/output_windows.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "image/image_io.h"
#include "image/image_writer.h"
#include "image/tone_mapping.h"
#include "render/display/display_encoder.h"
#include "render/renderer.h"
#include "render/window/monitors.h"
#include "render/window/present_clock.h"
#include "tests/window/screen_capture.h"
#include "warp/planar_projection.h"

namespace zenith::render::window {
namespace {

using testing::capture_screen;
using testing::Screen;

bool have_display() {
  const char* display = std::getenv("DISPLAY");
  return display != nullptr && *display != '\0';
}

/// Whether the display is the 256 × 96 virtual screen these tests place their
/// windows on (window.OutputWindows_under_xvfb starts one); a developer's own
/// desktop, or a suite run under another xvfb-run, skips them instead.
bool have_test_screen() {
  if (!have_display()) return false;
  const std::vector<MonitorInfo> monitors = list_monitors();
  return monitors.size() == 1 && monitors[0].width == 256 && monitors[0].height == 96;
}

glm::dquat look_rotation(const glm::dvec3& forward, const glm::dvec3& up) {
  const glm::dvec3 z = -glm::normalize(forward);
  const glm::dvec3 x = glm::normalize(glm::cross(up, z));
  return glm::quat_cast(glm::dmat3(x, glm::cross(z, x), z));
}

/// A planet without an atmosphere lit by the sun, seen from 2000 km, its limb
/// across the view: no tables needed, values from black space to past 1.
scene::Scene planet_scene(double yaw_deg) {
  scene::Scene s;
  s.name = "window test planet";
  s.wavelengths_nm = {680.0, 550.0, 440.0};
  scene::Body planet;
  planet.name = "planet";
  planet.radius_m = 6.371e6;
  planet.albedo.colour_linear_rgb = {0.5, 0.3, 0.2};
  s.bodies.push_back(planet);
  s.sun.direction = glm::normalize(glm::dvec3(1.0, 0.3, 0.6));
  s.sun.angular_radius_rad = 4.65e-3;
  s.sun.irradiance_W_m2_nm = {1.5, 1.8, 1.9};
  s.camera.position_m = {0.0, 0.0, 6.371e6 + 2.0e6};
  const double yaw = yaw_deg * 3.14159265358979 / 180.0;
  s.camera.orientation = look_rotation({std::cos(yaw), std::sin(yaw), -0.9}, {0, 0, 1});
  s.camera.exposure = 4.0;
  return s;
}

Renderer make_renderer() {
  RenderOptions o;
  o.colour = image::ColourMapping::direct;
  return Renderer(o, [](const atmosphere::AtmosphereModel&) -> atmosphere::lut::LookupTables {
    throw std::logic_error("the test scene has no atmosphere");
  });
}

/// What the file path writes for the frame: Renderer::render_image → PNG
/// (the PNG writer's tone mapping and sRGB bytes) → read back, as bytes.
std::vector<std::uint8_t> file_path_bytes(Renderer& renderer, const scene::Scene& s, const warp::Projection& p,
                                          const std::filesystem::path& file) {
  const std::vector<float> rgb = renderer.render_image(s, p);
  image::write_png(file, p.width(), p.height(), rgb, image::ToneMapping::exponential, {});
  const image::LinearImage png = image::read_image(file);
  std::vector<std::uint8_t> bytes(png.rgb.size());
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<std::uint8_t>(std::lround(255.0f * image::srgb_encode(png.rgb[i])));
  return bytes;
}

/// The largest difference per channel between a screen rectangle (top-left x0, y0) and an image.
int worst_difference(const Screen& screen, int x0, int y0, const std::vector<std::uint8_t>& image, int width,
                     int height) {
  int worst = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::array<int, 3> s = screen.at(x0 + x, y0 + y);
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst,
                         std::abs(s[static_cast<std::size_t>(c)] -
                                  image[(static_cast<std::size_t>(y) * width + x) * 3 + static_cast<std::size_t>(c)]));
    }
  return worst;
}

warp::OutputWindow placed(const std::string& name, int x, int y, int w, int h) {
  warp::OutputWindow window;
  window.name = name;
  window.position = std::array<int, 2>{x, y};
  window.size = std::array<int, 2>{w, h};
  window.decorated = false;
  return window;
}

/// Renders both outputs on the GPU path, presents them, and compares the
/// screen's rectangles (top-left corners `corners`) with the file path.
/// How the test renders the frames on the GPU path.
enum class GpuPath {
  texture,  ///< Renderer::render_to_texture, then DisplayEncoder::encode
  bands,    ///< Renderer::render_on_gpu with DisplayEncoder::encode_band (a node's steady frame)
};

void expect_screen_shows_the_file_frames(const std::vector<ShownOutput>& shown,
                                         const std::vector<std::array<int, 2>>& corners, std::size_t window_count,
                                         GpuPath path, const std::string& tag) {
  OutputWindows windows(shown, "zenith test");
  EXPECT_EQ(windows.window_count(), window_count);
  Renderer renderer = make_renderer();
  display::DisplayEncoder encoder;
  std::vector<gl::Texture> radiance, encoded;
  std::vector<std::vector<std::uint8_t>> expected;
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("zenith-output-windows-" + tag);
  std::filesystem::create_directories(dir);
  for (std::size_t k = 0; k < shown.size(); ++k) {
    const warp::PlanarProjection p = warp::PlanarProjection::symmetric(shown[k].width_px, shown[k].height_px, 70.0);
    const scene::Scene s = planet_scene(40.0 * static_cast<double>(k));  // a different view per output
    radiance.push_back(gl::Texture::create_2d(gl::TextureFormat::rgba32f, p.width(), p.height()));
    encoded.push_back(gl::Texture::create_2d(gl::TextureFormat::rgba8, p.width(), p.height()));
    if (path == GpuPath::texture) {
      renderer.render_to_texture(s, p, radiance.back());
      encoder.encode(radiance.back(), {}, encoded.back());
    } else {
      gl::Texture& target = encoded.back();
      renderer.render_on_gpu(s, p, [&](const GpuBand& band) { encoder.encode_band(band, {}, target); });
    }
    expected.push_back(file_path_bytes(renderer, s, p, dir / ("output-" + std::to_string(k) + ".png")));
  }
  std::vector<const gl::Texture*> displays;
  for (const gl::Texture& t : encoded) displays.push_back(&t);
  // Present until the window system has mapped the windows (a few round trips on Xvfb).
  Screen screen;
  std::vector<int> worst(shown.size(), 255);
  for (int attempt = 0; attempt < 40; ++attempt) {
    windows.present(displays, PresentClock::Clock::now());
    windows.poll_close_request();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    screen = capture_screen();
    bool all = true;
    for (std::size_t k = 0; k < shown.size(); ++k) {
      worst[k] =
          worst_difference(screen, corners[k][0], corners[k][1], expected[k], shown[k].width_px, shown[k].height_px);
      all = all && worst[k] <= 1;
    }
    if (all) break;
  }
  for (std::size_t k = 0; k < shown.size(); ++k)
    EXPECT_LE(worst[k], 1) << "output " << k << " at (" << corners[k][0] << ", " << corners[k][1] << ")";
  // The frames are not trivial: the planet, its lit limb and black space.
  std::size_t black = 0, bright = 0;
  for (const std::uint8_t v : expected[0]) {
    black += v == 0;
    bright += v > 200;
  }
  EXPECT_GT(black, 100u);
  EXPECT_GT(bright, 10u);
  std::filesystem::remove_all(dir);
}

TEST(OutputWindows, TwoUndecoratedWindowsShowTheirOutputsAtTheirRectangles) {
  if (!have_test_screen()) GTEST_SKIP() << "needs the 256x96 virtual screen of window.OutputWindows_under_xvfb";
  const std::vector<MonitorInfo> monitors = list_monitors();
  ASSERT_EQ(monitors.size(), 1u);
  std::vector<ShownOutput> shown = {{"left", 128, 96, placed("left", 0, 0, 128, 96)},
                                    {"right", 128, 96, placed("right", 128, 0, 128, 96)}};
  expect_screen_shows_the_file_frames(shown, {{0, 0}, {128, 0}}, 2, GpuPath::bands, "two");
}

TEST(OutputWindows, TwoOutputsInOneWindowAppearAtTheirRectangles) {
  // A Mosaic desktop: one undecorated window over the whole screen, each output in its rect.
  if (!have_test_screen()) GTEST_SKIP() << "needs the 256x96 virtual screen of window.OutputWindows_under_xvfb";
  warp::OutputWindow left = placed("mosaic", 0, 0, 256, 96), right = left;
  // Swapped on purpose: the first output on the right half.
  left.rect = std::array<int, 4>{128, 0, 128, 96};
  right.rect = std::array<int, 4>{0, 0, 128, 96};
  std::vector<ShownOutput> shown = {{"a", 128, 96, left}, {"b", 128, 96, right}};
  expect_screen_shows_the_file_frames(shown, {{128, 0}, {0, 0}}, 1, GpuPath::texture, "mosaic");
}

TEST(OutputWindows, FullscreenFillsTheMonitorExactly) {
  if (!have_test_screen()) GTEST_SKIP() << "needs the 256x96 virtual screen of window.OutputWindows_under_xvfb";
  const std::vector<MonitorInfo> monitors = list_monitors();
  ASSERT_FALSE(monitors.empty());
  warp::OutputWindow full;
  full.name = "dome";
  full.monitor_index = 0;
  full.fullscreen = true;
  full.decorated = false;
  OutputWindows windows({{"dome", 64, 32, full}}, "zenith test");
  const FramebufferSize fb = windows.primary().framebuffer_size();
  EXPECT_EQ(fb.width, monitors[0].width);
  EXPECT_EQ(fb.height, monitors[0].height);
  EXPECT_EQ(windows.output_rect(0), (FramebufferRect{0, 0, monitors[0].width, monitors[0].height}));
  // A uniform grey frame: every pixel of the screen must show it.
  const std::vector<float> grey(64 * 32 * 4, 0.5f);
  const gl::Texture radiance = gl::Texture::create_2d(gl::TextureFormat::rgba32f, 64, 32, grey);
  gl::Texture encoded = gl::Texture::create_2d(gl::TextureFormat::rgba8, 64, 32);
  display::DisplayEncoder encoder;
  encoder.encode(radiance, {}, encoded);
  const int code = image::display_byte(0.5f, image::ToneMapping::exponential);
  const std::vector<const gl::Texture*> displays = {&encoded};
  std::size_t off = 0;
  for (int attempt = 0; attempt < 40; ++attempt) {
    windows.present(displays, PresentClock::Clock::now());
    windows.poll_close_request();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const Screen screen = capture_screen();
    off = 0;
    for (int y = 0; y < screen.height; ++y)
      for (int x = 0; x < screen.width; ++x)
        for (const int v : screen.at(x, y)) off += std::abs(v - code) > 1;
    if (off == 0) break;
  }
  EXPECT_EQ(off, 0u) << "screen pixels not showing the frame's code " << code;
}

TEST(OutputWindows, AMissingMonitorNamesTheMonitorsThatExist) {
  if (!have_test_screen()) GTEST_SKIP() << "needs the 256x96 virtual screen of window.OutputWindows_under_xvfb";
  const std::vector<MonitorInfo> monitors = list_monitors();
  ASSERT_FALSE(monitors.empty());
  warp::OutputWindow missing;
  missing.name = "p1";
  missing.monitor_name = "DP-7";
  missing.fullscreen = true;
  missing.decorated = false;
  try {
    OutputWindows windows({{"p1", 32, 32, missing}}, "zenith test");
    FAIL() << "no error for a monitor that does not exist";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("output 'p1'"), std::string::npos) << what;
    EXPECT_NE(what.find("monitor 'DP-7', which does not exist"), std::string::npos) << what;
    const MonitorInfo& m = monitors[0];
    EXPECT_NE(what.find(m.name + " " + std::to_string(m.width) + "x" + std::to_string(m.height) + " at (" +
                        std::to_string(m.x) + ", " + std::to_string(m.y) + ")"),
              std::string::npos)
        << what;
  }
  warp::OutputWindow by_index = missing;
  by_index.monitor_name.reset();
  by_index.monitor_index = static_cast<int>(monitors.size());
  EXPECT_THROW(OutputWindows({{"p1", 32, 32, by_index}}, "zenith test"), std::invalid_argument);
}

TEST(OutputWindows, OutputsSharingAWindowMustDescribeItAlike) {
  if (!have_test_screen()) GTEST_SKIP() << "needs the 256x96 virtual screen of window.OutputWindows_under_xvfb";
  warp::OutputWindow a = placed("wall", 0, 0, 256, 96), b = placed("wall", 10, 0, 256, 96);
  try {
    OutputWindows windows({{"p1", 32, 32, a}, {"p2", 32, 32, b}}, "zenith test");
    FAIL() << "no error for outputs describing one window differently";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("outputs 'p1' and 'p2' share window 'wall'"), std::string::npos) << e.what();
  }
}

TEST(PresentClock, CountsASwapLaterThanOneRefreshAsLate) {
  using namespace std::chrono;
  PresentClock clock(60.0);  // 16.7 ms; late past 1.25 × that = 20.8 ms
  const auto t0 = PresentClock::Clock::now();
  EXPECT_FALSE(clock.record(t0, t0 + milliseconds(5)));
  EXPECT_FALSE(clock.record(t0, t0 + milliseconds(20)));
  EXPECT_TRUE(clock.record(t0, t0 + milliseconds(22)));
  EXPECT_TRUE(clock.record(t0, t0 + milliseconds(40)));
  EXPECT_EQ(clock.presented(), 4u);
  EXPECT_EQ(clock.late(), 2u);
  EXPECT_NEAR(clock.worst_ms(), 40.0, 1e-9);
  PresentClock unknown(0.0);  // no vsync or no refresh rate: never late
  EXPECT_FALSE(unknown.record(t0, t0 + seconds(1)));
  EXPECT_EQ(unknown.late(), 0u);
}

TEST(PresentClock, CountsFromTheVblankCounterWhereTheDisplayHasOne) {
  using namespace std::chrono;
  PresentClock clock(60.0);
  const auto t0 = PresentClock::Clock::now();
  // GLX_OML_sync_control: one vblank from the start of the present to the swap is on time,
  // whatever the wall clock says (a scheduler hiccup after the swap); two or more missed one.
  EXPECT_FALSE(clock.record(t0, t0 + milliseconds(30), std::int64_t{1}));
  EXPECT_FALSE(clock.record(t0, t0 + milliseconds(2), std::int64_t{0}));
  EXPECT_TRUE(clock.record(t0, t0 + milliseconds(18), std::int64_t{2}));
  EXPECT_EQ(clock.presented(), 3u);
  EXPECT_EQ(clock.late(), 1u);
  EXPECT_NEAR(clock.last_ms(), 18.0, 1e-9);
  EXPECT_NEAR(clock.worst_ms(), 30.0, 1e-9);
  // Without a refresh rate the counter still decides.
  PresentClock unknown(0.0);
  EXPECT_TRUE(unknown.record(t0, t0 + milliseconds(40), std::int64_t{3}));
  EXPECT_EQ(unknown.late(), 1u);
}

}  // namespace
}  // namespace zenith::render::window
