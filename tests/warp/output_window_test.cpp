// The "window" key of a viewport config's output (warp/output_window.h): the
// forms a planetarium uses (a monitor by name or index, fullscreen; a placed,
// undecorated window; outputs sharing a window at their rectangles; a gamma
// display), and every malformed value rejected with the file, the key and the
// allowed values.
#include "warp/output_window.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/json_reader.h"
#include "warp/viewport_config.h"
#include "warp_file_test_support.h"

namespace zenith::warp {
namespace {

using nlohmann::json;
using testing::expect_error;

ViewportConfig with_window(const json& window) {
  json j = json::parse(R"({"zenith_viewports": 1, "name": "t", "outputs": [
    {"name": "p1", "size": [64, 40], "projection": {"type": "planar", "fov_deg": 60}}]})");
  j["outputs"][0]["window"] = window;
  return parse_viewport_config(j, "t.json", ".");
}

TEST(OutputWindow, AnOutputWithoutTheKeyHasNoWindow) {
  json j = json::parse(R"({"zenith_viewports": 1, "name": "t", "outputs": [
    {"name": "p1", "size": [64, 40], "projection": {"type": "planar", "fov_deg": 60}}]})");
  EXPECT_FALSE(parse_viewport_config(j, "t.json", ".").outputs[0].window.has_value());
}

TEST(OutputWindow, FullscreenOnAMonitorByNameOrIndex) {
  const OutputWindow named = *with_window({{"monitor", "DP-1"}, {"fullscreen", true}}).outputs[0].window;
  EXPECT_EQ(named.name, "p1");  // its own window unless named
  EXPECT_EQ(named.monitor_name, "DP-1");
  EXPECT_FALSE(named.monitor_index.has_value());
  EXPECT_TRUE(named.fullscreen);
  EXPECT_FALSE(named.decorated);  // fullscreen: no decoration
  EXPECT_TRUE(named.vsync);
  EXPECT_EQ(named.gamma, 0.0);  // sRGB
  EXPECT_EQ(named.describe_monitor(), "monitor 'DP-1'");
  const OutputWindow indexed = *with_window({{"monitor", 1}, {"fullscreen", true}}).outputs[0].window;
  EXPECT_EQ(indexed.monitor_index, 1);
  EXPECT_EQ(indexed.describe_monitor(), "monitor 1");
}

TEST(OutputWindow, APlacedUndecoratedWindowAndASharedOne) {
  const OutputWindow placed =
      *with_window({{"position", {1920, 0}}, {"size", {1920, 1200}}, {"decorated", false}, {"vsync", false}})
           .outputs[0]
           .window;
  EXPECT_EQ(placed.position, (std::array<int, 2>{1920, 0}));
  EXPECT_EQ(placed.size, (std::array<int, 2>{1920, 1200}));
  EXPECT_FALSE(placed.decorated);
  EXPECT_FALSE(placed.vsync);
  EXPECT_FALSE(placed.fullscreen);
  const OutputWindow shared = *with_window({{"name", "mosaic"},
                                            {"monitor", 0},
                                            {"fullscreen", true},
                                            {"rect", {1920, 0, 1920, 1200}},
                                            {"encoding", {{"gamma", 2.4}}}})
                                   .outputs[0]
                                   .window;
  EXPECT_EQ(shared.name, "mosaic");
  EXPECT_EQ(shared.rect, (std::array<int, 4>{1920, 0, 1920, 1200}));
  EXPECT_EQ(shared.gamma, 2.4);
}

TEST(OutputWindow, RefusesWhatCannotBeShown) {
  expect_error([] { with_window(3); }, {"t.json", "/outputs/0/window", "must be an object"});
  expect_error([] { with_window({{"monitor", -1}}); }, {"/outputs/0/window/monitor", "monitor's name", "[0, 63]"});
  expect_error([] { with_window({{"monitor", ""}}); }, {"/outputs/0/window/monitor", "zenith displays"});
  expect_error([] { with_window({{"fullscreen", "yes"}}); }, {"/outputs/0/window/fullscreen", "true or false"});
  expect_error(
      [] {
        with_window({{"fullscreen", true}, {"size", {800, 600}}});
      },
      {"/outputs/0/window/size", "not allowed with \"fullscreen\": true"});
  expect_error(
      [] {
        with_window({{"fullscreen", true}, {"position", {0, 0}}});
      },
      {"/outputs/0/window/position", "not allowed with \"fullscreen\": true"});
  expect_error(
      [] {
        with_window({{"fullscreen", true}, {"decorated", true}});
      },
      {"/outputs/0/window/decorated", "no decoration"});
  expect_error([] { with_window({{"size", {0, 600}}}); }, {"/outputs/0/window/size", "[1, 65536]"});
  expect_error([] { with_window({{"position", {1, 2, 3}}}); }, {"/outputs/0/window/position", "[x, y]"});
  expect_error([] { with_window({{"rect", {0, 0, 0, 10}}}); }, {"/outputs/0/window/rect", "≥ 1"});
  expect_error([] { with_window({{"encoding", "pq"}}); }, {"/outputs/0/window/encoding", "\"srgb\" or {\"gamma\""});
  expect_error([] { with_window({{"encoding", {{"gamma", 5}}}}); }, {"/outputs/0/window/encoding/gamma", "[1, 3]"});
  expect_error([] { with_window({{"monitr", 0}}); }, {"/outputs/0/window", "monitr"});
}

}  // namespace
}  // namespace zenith::warp
