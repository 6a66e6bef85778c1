// The dome preview from node thumbnails (cluster/node/thumbnail.h,
// cluster/operator/dome_preview.h; docs/operator.md, "Dome preview"): a node's
// box-filtered sRGB thumbnail, tiles of a dome master placed by their
// viewport, other outputs in a grid, thumbnails of another node's output
// refused.
#include "cluster/operator/dome_preview.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "cluster/node/thumbnail.h"
#include "image/tone_mapping.h"

namespace zenith::cluster {
namespace {

using nlohmann::json;

TEST(Thumbnail, IsTheBoxFilteredOutputInSrgbAtMostEdgePixelsOnItsLongerSide) {
  // 4 × 2 pixels, left half 0.25 (display-linear), right half 1.0 except one NaN and one above 1.
  std::vector<float> rgb(4 * 2 * 3, 0.25f);
  for (int y = 0; y < 2; ++y)
    for (int x = 2; x < 4; ++x)
      for (int c = 0; c < 3; ++c) rgb[static_cast<std::size_t>((y * 4 + x) * 3 + c)] = 1.0f;
  const Thumbnail half = make_thumbnail(7, "left", rgb, 4, 2, 2);
  EXPECT_EQ(half.frame, 7u);
  EXPECT_EQ(half.output, "left");
  EXPECT_EQ(half.width_px, 2);
  EXPECT_EQ(half.height_px, 1);
  ASSERT_EQ(half.rgb.size(), 6u);
  EXPECT_EQ(half.rgb[0], image::display_byte(0.25f, image::ToneMapping::clamp));
  EXPECT_EQ(half.rgb[3], 255);
  rgb[3 * 3] = std::numeric_limits<float>::quiet_NaN();  // counts as 0
  rgb[7 * 3] = 7.0f;                                     // clamped to 1
  const Thumbnail odd = make_thumbnail(7, "left", rgb, 4, 2, 2);
  EXPECT_EQ(odd.rgb[3], image::display_byte(0.75f, image::ToneMapping::clamp));
  EXPECT_EQ(odd.rgb[4], 255);
  // Never larger than the output, and the aspect kept.
  const Thumbnail same = make_thumbnail(1, "o", rgb, 4, 2, 64);
  EXPECT_EQ(same.width_px, 4);
  EXPECT_EQ(same.height_px, 2);
  const std::vector<float> tall(30 * 300 * 3, 0.5f);
  const Thumbnail narrow = make_thumbnail(1, "o", tall, 30, 300, 64);
  EXPECT_EQ(narrow.height_px, 64);
  EXPECT_EQ(narrow.width_px, 6);
  EXPECT_THROW(make_thumbnail(1, "o", rgb, 4, 2, 65), std::invalid_argument);
  EXPECT_THROW(make_thumbnail(1, "o", rgb, 5, 2, 8), std::invalid_argument);
}

/// A cluster of nodes a (top-left, top-right), b (bottom-left), c (bottom-right) over `viewports`.
ClusterConfig cluster_of_three() {
  ClusterConfig config;
  config.name = "test";
  config.nodes = {{"a", "127.0.0.1", {"top-left", "top-right"}},
                  {"b", "127.0.0.1", {"bottom-left"}},
                  {"c", "127.0.0.1", {"bottom-right"}}};
  return config;
}

/// Four 128² quadrants of one 256² fisheye dome master (as configs/viewports/dome-quadrants.json).
warp::ViewportConfig quadrants() {
  json outputs = json::array();
  const char* names[4] = {"top-left", "top-right", "bottom-left", "bottom-right"};
  for (int i = 0; i < 4; ++i)
    outputs.push_back({{"name", names[i]},
                       {"size", {128, 128}},
                       {"projection",
                        {{"type", "fisheye"},
                         {"fov_deg", 180},
                         {"radius_px", 128},
                         {"centre_x_px", i % 2 == 0 ? 128 : 0},
                         {"centre_y_px", i < 2 ? 128 : 0}}}});
  return warp::parse_viewport_config({{"zenith_viewports", 1}, {"name", "q"}, {"outputs", outputs}}, "q.json", ".");
}

/// A 1×1 thumbnail of one grey value.
Thumbnail grey(std::uint64_t frame, const std::string& output, std::uint8_t value) {
  return Thumbnail{frame, output, 1, 1, {value, value, value}};
}

TEST(DomePreviewTest, TilesOfADomeMasterArePlacedByTheirViewport) {
  DomePreview preview(cluster_of_three(), quadrants());
  EXPECT_EQ(preview.layout(), DomePreview::Layout::dome);
  EXPECT_EQ(preview.width_px(), 128) << "the largest output side becomes 64 px";
  EXPECT_EQ(preview.height_px(), 128);
  EXPECT_TRUE(preview.empty());
  EXPECT_FALSE(preview.newest_frame());
  preview.add("a", grey(10, "top-left", 10));
  preview.add("a", grey(10, "top-right", 20));
  preview.add("c", grey(9, "bottom-right", 40));
  EXPECT_EQ(preview.newest_frame(), 10u);
  EXPECT_EQ(preview.tiles(), 3u);
  EXPECT_EQ(preview.outputs(), 4u);
  EXPECT_EQ(preview.oldest_frame(), 9u);
  const DomePreview::Picture p = preview.compose();
  ASSERT_EQ(p.rgb.size(), 128u * 128u * 3u);
  const auto at = [&](int x, int y) { return p.rgb[static_cast<std::size_t>((y * 128 + x) * 3)]; };
  EXPECT_EQ(at(0, 0), 10);
  EXPECT_EQ(at(63, 63), 10);
  EXPECT_EQ(at(64, 0), 20);
  EXPECT_EQ(at(127, 63), 20);
  EXPECT_EQ(at(0, 64), 0) << "bottom-left: no thumbnail yet";
  EXPECT_EQ(at(127, 127), 40);
  // A newer thumbnail replaces the output's.
  preview.add("b", Thumbnail{11, "bottom-left", 2, 1, {50, 50, 50, 60, 60, 60}});
  const DomePreview::Picture q = preview.compose();
  EXPECT_EQ(q.rgb[static_cast<std::size_t>((64 * 128 + 0) * 3)], 50);
  EXPECT_EQ(q.rgb[static_cast<std::size_t>((127 * 128 + 63) * 3)], 60);
  preview.clear();
  EXPECT_TRUE(preview.empty());
}

TEST(DomePreviewTest, AThumbnailOfAnotherNodesOutputIsRefused) {
  DomePreview preview(cluster_of_three(), quadrants());
  EXPECT_THROW(preview.add("b", grey(1, "top-left", 1)), std::invalid_argument);
  EXPECT_THROW(preview.add("b", grey(1, "nowhere", 1)), std::invalid_argument);
  EXPECT_THROW(preview.add("b", Thumbnail{1, "bottom-left", 2, 2, {1, 2, 3}}), std::invalid_argument);
  EXPECT_TRUE(preview.empty());
}

TEST(DomePreviewTest, OtherOutputsGoSideBySideInAGrid) {
  // Three planar projectors: a grid of 2 × 2 cells of 64 px with 2 px between them.
  json outputs = json::array();
  for (const char* name : {"p1", "p2", "p3"})
    outputs.push_back({{"name", name}, {"size", {320, 160}}, {"projection", {{"type", "planar"}, {"fov_deg", 60}}}});
  const warp::ViewportConfig planar =
      warp::parse_viewport_config({{"zenith_viewports", 1}, {"name", "p"}, {"outputs", outputs}}, "p.json", ".");
  ClusterConfig config;
  config.nodes = {{"a", "127.0.0.1", {"p1", "p2"}}, {"b", "127.0.0.1", {"p3"}}};
  DomePreview preview(config, planar);
  EXPECT_EQ(preview.layout(), DomePreview::Layout::grid);
  EXPECT_EQ(preview.width_px(), 130);
  EXPECT_EQ(preview.height_px(), 130);
  Thumbnail wide{3, "p3", 64, 32, std::vector<std::uint8_t>(64 * 32 * 3, 200)};
  preview.add("b", wide);
  const DomePreview::Picture p = preview.compose();
  const auto at = [&](int x, int y) { return p.rgb[static_cast<std::size_t>((y * 130 + x) * 3)]; };
  EXPECT_EQ(at(64, 10), 48) << "grey between cells";
  EXPECT_EQ(at(0, 66 + 15), 0) << "above the thumbnail, centred in its cell";
  EXPECT_EQ(at(0, 66 + 16), 200);
  EXPECT_EQ(at(63, 66 + 47), 200);
  EXPECT_EQ(at(0, 66 + 48), 0);
}

}  // namespace
}  // namespace zenith::cluster
