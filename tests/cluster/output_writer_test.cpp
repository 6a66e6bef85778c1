// A node's frame files without a renderer (cluster/node/output_writer.h):
// partial files renamed on Present, presented.log, the two layouts.
#include "cluster/node/output_writer.h"

#include "core/files.h"
#include "image/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace zenith::cluster {
namespace {

namespace fs = std::filesystem;

warp::ViewportConfig two_outputs() {
  warp::ViewportConfig viewports;
  viewports.name = "test";
  viewports.source = "test.json";
  for (const char* name : {"left", "right"}) {
    warp::OutputConfig o;
    o.name = name;
    o.width_px = 2;
    o.height_px = 2;
    viewports.outputs.push_back(o);
  }
  return viewports;
}

using core::read_text;

class OutputWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root = fs::temp_directory_path() /
           ("zenith-output-writer-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root);
  }
  void TearDown() override { fs::remove_all(root); }

  fs::path root;
  const warp::ViewportConfig viewports = two_outputs();
  const std::vector<float> grey = std::vector<float>(2 * 2 * 3, 0.5f);
};

TEST_F(OutputWriterTest, FramePathsFollowTheLayout) {
  const OutputWriter per_node(viewports, FrameFileLayout::per_node, root, root / "a", "png");
  EXPECT_EQ(per_node.frame_path(viewports.outputs[0], 42), root / "a" / "left" / "frame-000042.png");
  const OutputWriter offline(viewports, FrameFileLayout::offline, root, root / "nodes" / "a", "exr");
  EXPECT_EQ(offline.frame_path(viewports.outputs[1], 7), root / "right" / "right.000007.exr");
}

TEST_F(OutputWriterTest, PresentRenamesThePartialFilesAndLogsTheFrame) {
  OutputWriter writer(viewports, FrameFileLayout::per_node, root, root / "a", "png");
  writer.write(0, 3, grey, {});
  writer.write(1, 3, grey, {});
  const fs::path left = writer.frame_path(viewports.outputs[0], 3);
  EXPECT_TRUE(fs::exists(fs::path(left.string() + ".partial")));
  EXPECT_FALSE(fs::exists(left));
  writer.finish_frame({3, "abcd", "Earth=0123456789abcdef", 0.1, {}});

  EXPECT_FALSE(writer.present(2)) << "not the rendered frame";
  EXPECT_FALSE(fs::exists(left));
  EXPECT_TRUE(writer.present(3));
  EXPECT_TRUE(fs::exists(left));
  EXPECT_TRUE(fs::exists(writer.frame_path(viewports.outputs[1], 3)));
  EXPECT_FALSE(fs::exists(fs::path(left.string() + ".partial")));
  EXPECT_FALSE(fs::exists(root / "a" / "presented.log")) << "the act before the bookkeeping";
  writer.log_presented();
  EXPECT_EQ(read_text(root / "a" / "presented.log"),
            "frame 3 state abcd tables Earth=0123456789abcdef show_time_s 0.1\n");
  EXPECT_FALSE(writer.present(3)) << "presented once";
  writer.log_presented();
  EXPECT_EQ(read_text(root / "a" / "presented.log"),
            "frame 3 state abcd tables Earth=0123456789abcdef show_time_s 0.1\n")
      << "logged once";
}

TEST_F(OutputWriterTest, AnUnfinishedFrameIsNotPresented) {
  OutputWriter writer(viewports, FrameFileLayout::per_node, root, root / "a", "png");
  writer.write(0, 5, grey, {});
  EXPECT_FALSE(writer.present(5));
  EXPECT_FALSE(fs::exists(writer.frame_path(viewports.outputs[0], 5)));
}

TEST_F(OutputWriterTest, DiscardRemovesThePartialFiles) {
  OutputWriter writer(viewports, FrameFileLayout::per_node, root, root / "a", "png");
  writer.write(0, 1, grey, {});
  writer.finish_frame({1, "d", "-", 0.0, {}});
  writer.discard();
  EXPECT_FALSE(fs::exists(fs::path(writer.frame_path(viewports.outputs[0], 1).string() + ".partial")));
  EXPECT_FALSE(writer.present(1));
  writer.log_presented();
  EXPECT_FALSE(fs::exists(root / "a" / "presented.log"));
}

TEST_F(OutputWriterTest, TheDisplayImageIsToneMapped) {
  const OutputWriter writer(viewports, FrameFileLayout::per_node, root, root / "a", "png");
  const std::vector<float> display = writer.display_image(0, grey);
  ASSERT_EQ(display.size(), grey.size());
  for (const float v : display) EXPECT_NEAR(v, 1.0 - std::exp(-0.5), 1e-6);  // no blend: the tone map only
  // The frame's fade after the tone map: a quarter of the way to red.
  const std::vector<float> faded = writer.display_image(0, grey, {0.25, glm::dvec3(1.0, 0.0, 0.0)});
  const double t = 1.0 - std::exp(-0.5);
  for (std::size_t i = 0; i < faded.size(); ++i) EXPECT_NEAR(faded[i], 0.75 * t + (i % 3 == 0 ? 0.25 : 0.0), 1e-6) << i;
}

TEST_F(OutputWriterTest, TheLogNamesAFrameFade) {
  OutputWriter writer(viewports, FrameFileLayout::per_node, root, root / "a", "png");
  writer.write(0, 4, grey, {}, {1.0, glm::dvec3(0.0)});
  writer.finish_frame({4, "ef", "-", 0.5, {1.0, glm::dvec3(0.0)}});
  EXPECT_TRUE(writer.present(4));
  writer.log_presented();
  EXPECT_EQ(read_text(root / "a" / "presented.log"), "frame 4 state ef tables - show_time_s 0.5 fade 1 0,0,0\n");
  // A blackout is black in the file (tone map, then the fade).
  const image::LinearImage black = image::read_image(writer.frame_path(viewports.outputs[0], 4));
  for (const float v : black.rgb) EXPECT_EQ(v, 0.0f);
}

}  // namespace
}  // namespace zenith::cluster
