// A warp's source image has its own size (issue 14, the spherical-mirror
// setup): a Bourke mesh's (u, v) address a square fisheye dome master while the
// projector output is 16:9. The rays of a viewport output are compared with an
// independent sampler (output pixel → bilinear in the generated mesh → (u, v)
// → fisheye ray of a square source), the 16:9 output is covered where the mesh
// covers it, and bad "source" sizes are refused naming the key and the range.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/json_reader.h"
#include "warp/viewport_config.h"
#include "warp/warped_projection.h"
#include "warp_file_test_support.h"
#include "core/units.h"

namespace zenith::warp {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ScratchDir;

constexpr int kWidth = 160, kHeight = 90;  // a 16:9 projector
constexpr double kAspect = 16.0 / 9.0;
constexpr int kNx = 33, kNy = 19;

/// A node of the generated mesh, in Bourke's own convention (x right in
/// [−aspect, aspect], y up in [−1, 1], v up).
struct Node {
  double x, y, u, v, intensity;
};

/// A spherical-mirror-like fan over the dome master's circle, narrower toward
/// the bottom of the projector image; u and v are bilinear in (x, y), so
/// Catmull–Rom and bilinear interpolation agree with the sampler below exactly.
/// Every used (u, v) lies inside the circle of a square source. The two bottom
/// corner nodes are unused (intensity −1).
std::vector<Node> mirror_mesh() {
  std::vector<Node> nodes;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const double x = -kAspect + 2.0 * kAspect * i / (kNx - 1), y = -1.0 + 2.0 * j / (kNy - 1);
      const double up = (y + 1.0) / 2.0;  // 0 at the bottom, 1 at the top
      Node n{x, y, 0.5 + (x / kAspect) * (0.3 + 0.05 * up), 0.1 + 0.75 * up, 0.5 + 0.5 * up};
      if (j == 0 && (i == 0 || i == kNx - 1)) n.intensity = -1.0;
      nodes.push_back(n);
    }
  return nodes;
}

std::string bourke_file(const std::vector<Node>& nodes) {
  std::ostringstream text;
  text.precision(17);
  text << "2\n" << kNx << " " << kNy << "\n";
  for (const Node& n : nodes) text << n.x << " " << n.y << " " << n.u << " " << n.v << " " << n.intensity << "\n";
  return text.str();
}

/// The independent sampler. Output pixel (px, py) of a W × H output → Bourke
/// (x, y) → the node cell → bilinear (u, v) (nothing when a corner is unused)
/// → the source pixel of a side × side dome master (v up → down) → the 180°
/// angular fisheye's ray (centre → +y, bottom of the rim → −z, right → +x).
std::optional<glm::dvec3> expected_ray(const std::vector<Node>& nodes, double px, double py, double side) {
  const double x = -kAspect + 2.0 * kAspect * px / kWidth, y = 1.0 - 2.0 * py / kHeight;
  const double fi = (x + kAspect) / (2.0 * kAspect) * (kNx - 1), fj = (y + 1.0) / 2.0 * (kNy - 1);
  const int i = std::min(static_cast<int>(std::floor(fi)), kNx - 2), j = std::min(static_cast<int>(std::floor(fj)), kNy - 2);
  const double a = fi - i, b = fj - j;
  const Node& n00 = nodes[static_cast<std::size_t>(j * kNx + i)];
  const Node& n10 = nodes[static_cast<std::size_t>(j * kNx + i + 1)];
  const Node& n01 = nodes[static_cast<std::size_t>((j + 1) * kNx + i)];
  const Node& n11 = nodes[static_cast<std::size_t>((j + 1) * kNx + i + 1)];
  for (const Node* n : {&n00, &n10, &n01, &n11})
    if (n->intensity < 0.0) return std::nullopt;
  const auto lerp2 = [&](double Node::*field) {
    return (1 - a) * (1 - b) * n00.*field + a * (1 - b) * n10.*field + (1 - a) * b * n01.*field + a * b * n11.*field;
  };
  const double u = lerp2(&Node::u), v_up = lerp2(&Node::v);
  const double sx = u * side, sy = (1.0 - v_up) * side;  // source pixel, y down
  const double radius = side / 2.0;
  const double dx = sx - radius, dy = radius - sy, r = std::hypot(dx, dy);
  if (r > radius) return std::nullopt;
  const double theta = r / radius * zenith::core::kPi / 2.0;
  if (r == 0.0) return glm::dvec3(0, 1, 0);
  // image right → +x, image up → +z (toward the back), axis → +y.
  return glm::dvec3(std::sin(theta) * dx / r, std::cos(theta), std::sin(theta) * dy / r);
}

struct MirrorSetup {
  ScratchDir dir{"warp_source"};
  std::vector<Node> nodes = mirror_mesh();
  MirrorSetup() { dir.write("mirror.data", bourke_file(nodes)); }

  json config(const json& source = nullptr) const {
    json j = json::parse(R"({"zenith_viewports": 1, "name": "mirror", "outputs": [
      {"name": "p", "size": [160, 90], "projection": {"type": "fisheye", "fov_deg": 180},
       "warp": {"file": "mirror.data", "format": "bourke"}}]})");
    if (!source.is_null()) j["outputs"][0]["warp"]["source"] = source;
    return j;
  }
  ViewportConfig parse(const json& j) const { return parse_viewport_config(j, "mirror.json", dir.path()); }
};

const WarpedProjection& warped_of(const ViewportConfig& c) {
  const auto* w = dynamic_cast<const WarpedProjection*>(c.outputs.at(0).projection.get());
  if (w == nullptr) throw std::logic_error("not a warped projection");
  return *w;
}

TEST(WarpSource, FisheyeSourceIsSquareByDefaultAndMatchesTheIndependentSampler) {
  const MirrorSetup setup;
  const ViewportConfig c = setup.parse(setup.config());
  const WarpedProjection& warped = warped_of(c);
  EXPECT_EQ(warped.width(), kWidth);
  EXPECT_EQ(warped.height(), kHeight);
  // The default source: a square dome master, side = the output's height.
  EXPECT_EQ(warped.base().width(), kHeight);
  EXPECT_EQ(warped.base().height(), kHeight);
  ASSERT_TRUE(c.outputs[0].warp);
  EXPECT_EQ(c.outputs[0].warp->source_width_px, kHeight);
  EXPECT_EQ(c.outputs[0].warp->source_height_px, kHeight);

  int compared = 0, agree_no_ray = 0;
  for (int py = 0; py < kHeight; ++py)
    for (int px = 0; px < kWidth; ++px) {
      const double x = px + 0.5, y = py + 0.5;
      const auto expected = expected_ray(setup.nodes, x, y, kHeight);
      const auto actual = warped.ray(x, y);
      ASSERT_EQ(expected.has_value(), actual.has_value()) << x << " " << y;
      if (!expected) {
        ++agree_no_ray;
        continue;
      }
      ASSERT_LT(glm::length(*expected - *actual), 1e-6) << x << " " << y;
      ++compared;
    }
  EXPECT_GT(compared, kWidth * kHeight * 9 / 10);
  EXPECT_GT(agree_no_ray, 0);  // the unused corner cells
}

TEST(WarpSource, SixteenByNineOutputIsCoveredWhereTheMeshCovers) {
  const MirrorSetup setup;
  // Where the mesh has data the output has a ray (its (u, v) all lie on the
  // square dome master's circle): every pixel outside the two unused bottom
  // corner cells.
  const ViewportConfig config = setup.parse(setup.config());
  const WarpedProjection& warped = warped_of(config);
  const double cell_w = static_cast<double>(kWidth) / (kNx - 1), cell_h = static_cast<double>(kHeight) / (kNy - 1);
  int covered = 0, meshed = 0;
  for (int py = 0; py < kHeight; ++py)
    for (int px = 0; px < kWidth; ++px) {
      const double x = px + 0.5, y = py + 0.5;
      const bool corner_cell = y > kHeight - cell_h && (x < cell_w || x > kWidth - cell_w);
      if (corner_cell) continue;
      ++meshed;
      covered += warped.ray(x, y).has_value();
    }
  EXPECT_EQ(covered, meshed);
  // Both side edges and the whole top row reach the dome: the mesh's x range
  // spans the full output width.
  for (int py = 0; py < kHeight - static_cast<int>(std::ceil(cell_h)); ++py) {
    EXPECT_TRUE(warped.ray(0.5, py + 0.5)) << py;
    EXPECT_TRUE(warped.ray(kWidth - 0.5, py + 0.5)) << py;
  }

  // The old behaviour (the source forced to the output's 16:9 size) leaves
  // much of the output black: the fisheye's circle covers only its middle.
  const ViewportConfig forced_config = setup.parse(setup.config(json{{"size_px", {kWidth, kHeight}}}));
  const WarpedProjection& forced = warped_of(forced_config);
  int forced_covered = 0;
  for (int py = 0; py < kHeight; ++py)
    for (int px = 0; px < kWidth; ++px) forced_covered += forced.ray(px + 0.5, py + 0.5).has_value();
  EXPECT_LT(forced_covered, covered * 85 / 100);
}

TEST(WarpSource, SizeAndAspectSetTheSourceImage) {
  const MirrorSetup setup;
  // A larger square source shows the same rays (the fisheye scales with it).
  const ViewportConfig square_config = setup.parse(setup.config());
  const WarpedProjection& square = warped_of(square_config);
  const ViewportConfig big = setup.parse(setup.config(json{{"size_px", {512, 512}}}));
  const WarpedProjection& large = warped_of(big);
  EXPECT_EQ(large.base().width(), 512);
  EXPECT_EQ(large.base().height(), 512);
  for (double y = 0.5; y < kHeight; y += 3.7)
    for (double x = 0.5; x < kWidth; x += 4.3) {
      const auto a = square.ray(x, y), b = large.ray(x, y);
      ASSERT_EQ(a.has_value(), b.has_value());
      if (a) {
        EXPECT_LT(glm::length(*a - *b), 1e-9);
      }
    }
  // "aspect": the output's height, aspect · height wide.
  const ViewportConfig wide = setup.parse(setup.config(json{{"aspect", 1.5}}));
  EXPECT_EQ(warped_of(wide).base().width(), 135);
  EXPECT_EQ(warped_of(wide).base().height(), kHeight);
  EXPECT_EQ(wide.outputs[0].warp->source_width_px, 135);

  // A non-fisheye source keeps the output's size unless told.
  json planar = setup.config();
  planar["outputs"][0]["projection"] = json::parse(R"({"type": "planar", "fov_deg": 90})");
  EXPECT_EQ(warped_of(setup.parse(planar)).base().width(), kWidth);
  EXPECT_EQ(warped_of(setup.parse(planar)).base().height(), kHeight);
  planar["outputs"][0]["warp"]["source"] = json{{"size_px", {100, 100}}};
  EXPECT_EQ(warped_of(setup.parse(planar)).base().width(), 100);
}

TEST(WarpSource, BadSourcesAreRefusedNamingTheKeyAndRange) {
  const MirrorSetup setup;
  struct Bad {
    json source;
    std::string pointer, reason;
  };
  const std::vector<Bad> cases = {
      {json{{"size_px", {0, 90}}}, "/outputs/0/warp/source/size_px/0", "= 0: must be in [1, 16384] px"},
      {json{{"size_px", {90, 20000}}}, "/outputs/0/warp/source/size_px/1", "= 20000: must be in [1, 16384] px"},
      {json{{"size_px", {90.5, 90}}}, "/outputs/0/warp/source/size_px/0", "must be an integer in [1, 16384] px"},
      {json{{"size_px", {90}}}, "/outputs/0/warp/source/size_px", "must be [width, height] in pixels"},
      {json{{"size_px", "square"}}, "/outputs/0/warp/source/size_px", "must be [width, height] in pixels"},
      {json{{"aspect", 0}}, "/outputs/0/warp/source/aspect", "= 0: must be in [0.1, 10] (width / height)"},
      {json{{"aspect", 11}}, "/outputs/0/warp/source/aspect", "must be in [0.1, 10]"},
      {json{{"aspect", "16:9"}}, "/outputs/0/warp/source/aspect", "must be a number"},
      {json{{"aspect", 1}, {"size_px", {90, 90}}}, "/outputs/0/warp/source/aspect", "either size_px or aspect, not both"},
      {json{{"width", 90}}, "/outputs/0/warp/source/width", "unknown key"},
      {json::object(), "/outputs/0/warp/source", "give size_px ([width, height] px) or aspect"},
      {json(1080), "/outputs/0/warp/source", "must be an object"},
  };
  for (const Bad& bad : cases) {
    SCOPED_TRACE(bad.source.dump());
    testing::expect_config_error([&] { setup.parse(setup.config(bad.source)); }, "mirror.json", bad.pointer,
                                 bad.reason);
  }
  // An aspect whose width would pass the largest side.
  json tall = setup.config(json{{"aspect", 9}});
  tall["outputs"][0]["size"] = json{100, 2000};
  testing::expect_error([&] { setup.parse(tall); },
                        {"mirror.json: /outputs/0/warp/source/aspect", "18000 px wide", "more than 16384"});
}

}  // namespace
}  // namespace zenith::warp
