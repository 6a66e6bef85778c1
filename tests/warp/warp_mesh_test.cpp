// PFM reading, warp meshes (interpolation, Paul Bourke .data, PFM warp maps) and
// WarpedProjection.
#include "warp/warp_mesh.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "tests/warp/warp_file_test_support.h"
#include "warp/fisheye_projection.h"
#include "warp/pfm.h"
#include "warp/planar_projection.h"
#include "warp/warped_projection.h"

namespace zenith::warp {
namespace {

using testing::expect_error;
using testing::make_pfm;
using testing::ScratchDir;

const float kNaN = std::numeric_limits<float>::quiet_NaN();

float ramp(int x, int y, int c) { return static_cast<float>(100 * y + 10 * x + c); }

// ---- PFM ---------------------------------------------------------------------

TEST(Pfm, ReadsBothByteOrders) {
  for (const bool little : {true, false}) {
    const PfmImage image = parse_pfm(make_pfm(4, 3, 3, ramp, little, false), "ramp.pfm", PfmRowOrder::bottom_to_top);
    ASSERT_EQ(image.width, 4);
    ASSERT_EQ(image.height, 3);
    ASSERT_EQ(image.channels, 3);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(image.at(x, y, c), ramp(x, y, c)) << little << " " << x << " " << y;
  }
}

TEST(Pfm, RowOrderBottomToTopAndTopToBottom) {
  // The same bytes read either way: the rows come out mirrored.
  const std::string bottom_first = make_pfm(2, 3, 1, ramp, true, false);
  const PfmImage classic = parse_pfm(bottom_first, "a.pfm", PfmRowOrder::bottom_to_top);
  const PfmImage top_first = parse_pfm(bottom_first, "a.pfm", PfmRowOrder::top_to_bottom);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 2; ++x) {
      EXPECT_EQ(classic.at(x, y, 0), ramp(x, y, 0));
      EXPECT_EQ(top_first.at(x, y, 0), ramp(x, 2 - y, 0));
    }
  // A file written top row first (MPCDI) read as such.
  const PfmImage mpcdi = parse_pfm(make_pfm(2, 3, 1, ramp, false, true), "m.pfm", PfmRowOrder::top_to_bottom);
  EXPECT_EQ(mpcdi.at(0, 0, 0), ramp(0, 0, 0));
  EXPECT_EQ(mpcdi.at(1, 2, 0), ramp(1, 2, 0));
}

TEST(Pfm, KeepsNaNAsNoData) {
  const auto value = [](int x, int y, int c) { return x == 1 && y == 1 ? kNaN : ramp(x, y, c); };
  const PfmImage image = parse_pfm(make_pfm(3, 3, 3, value, true, true), "n.pfm", PfmRowOrder::top_to_bottom);
  EXPECT_TRUE(std::isnan(image.at(1, 1, 0)));
  EXPECT_EQ(image.at(2, 1, 0), ramp(2, 1, 0));
}

TEST(Pfm, AcceptsCrLfAfterTheScale) {
  std::string bytes = make_pfm(2, 2, 1, ramp, true, false);
  bytes.insert(bytes.find("-1.0\n") + 4, "\r");
  const PfmImage image = parse_pfm(bytes, "crlf.pfm", PfmRowOrder::bottom_to_top);
  EXPECT_EQ(image.at(1, 1, 0), ramp(1, 1, 0));
}

TEST(Pfm, RejectsTruncatedData) {
  std::string bytes = make_pfm(4, 3, 3, ramp, true, false);
  bytes.resize(bytes.size() - 5);
  expect_error([&] { parse_pfm(bytes, "short.pfm", PfmRowOrder::bottom_to_top); },
               {"short.pfm: PFM: truncated", "139 bytes", "expected 144", "4x3x3"});
  expect_error([&] { parse_pfm("PF\n4 3\n-1.0", "noend.pfm", PfmRowOrder::bottom_to_top); },
               {"noend.pfm: PFM: truncated"});
}

TEST(Pfm, RejectsBadHeaders) {
  const auto parse = [](const std::string& bytes) { parse_pfm(bytes, "bad.pfm", PfmRowOrder::bottom_to_top); };
  expect_error([&] { parse("P6\n4 3\n255\n"); }, {"bad.pfm: PFM: bad header", "expected 'PF'", "'P6'"});
  expect_error([&] { parse("PF\nfour 3\n-1\n"); }, {"bad header: width 'four' is not an integer"});
  expect_error([&] { parse("PF\n4\n"); }, {"bad header", "height"});
  expect_error([&] { parse("PF\n20000 3\n-1\n"); }, {"width 20000 must be in [1, 16384]"});
  expect_error([&] { parse("PF\n4 0\n-1\n"); }, {"height 0 must be in [1, 16384]"});
  expect_error([&] { parse("PF\n4 3\n0\n"); }, {"scale 0 must be a non-zero finite number"});
  expect_error([&] { parse("PF\n4 3\nabc\n"); }, {"scale 'abc' is not a number"});
  std::string longer = make_pfm(2, 2, 1, ramp, true, false) + "xx";
  expect_error([&] { parse(longer); }, {"2 bytes after the sample data"});
}

TEST(Pfm, ReadsFilesAndNamesMissingOnes) {
  ScratchDir dir("pfm");
  const auto file = dir.write("map.pfm", make_pfm(3, 2, 3, ramp, false, false));
  EXPECT_EQ(read_pfm(file).at(2, 1, 2), ramp(2, 1, 2));
  expect_error([&] { read_pfm(dir.path() / "absent.pfm"); }, {"absent.pfm: cannot open"});
}

// ---- WarpMesh interpolation ------------------------------------------------------

WarpMesh mesh_of(int columns, int rows, const std::function<WarpNode(double s, double t)>& node,
                 WarpInterpolation interpolation) {
  std::vector<WarpNode> nodes;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) nodes.push_back(node(double(i) / (columns - 1), double(j) / (rows - 1)));
  return WarpMesh(columns, rows, std::move(nodes), "test", interpolation);
}

TEST(WarpMesh, BilinearIsTheBilinearInterpolantOfTheCellsCorners) {
  const auto f = [](double s, double t) {
    return WarpNode{std::sin(3 * s) + t, std::cos(2 * t) * s, 0.5 + 0.4 * s * t, true};
  };
  const WarpMesh mesh = mesh_of(5, 4, f, WarpInterpolation::bilinear);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      for (const double a : {0.0, 0.25, 0.5, 0.9})
        for (const double b : {0.0, 0.3, 0.75}) {
          const double s = (i + a) / 4, t = (j + b) / 3;
          const auto sample = mesh.sample(s, t);
          ASSERT_TRUE(sample);
          const WarpNode n00 = f(i / 4.0, j / 3.0), n10 = f((i + 1) / 4.0, j / 3.0);
          const WarpNode n01 = f(i / 4.0, (j + 1) / 3.0), n11 = f((i + 1) / 4.0, (j + 1) / 3.0);
          const auto lerp2 = [&](double WarpNode::*field) {
            return (1 - a) * (1 - b) * n00.*field + a * (1 - b) * n10.*field + (1 - a) * b * n01.*field +
                   a * b * n11.*field;
          };
          EXPECT_NEAR(sample->u, lerp2(&WarpNode::u), 1e-12);
          EXPECT_NEAR(sample->v, lerp2(&WarpNode::v), 1e-12);
          EXPECT_NEAR(sample->intensity, lerp2(&WarpNode::intensity), 1e-12);
        }
}

TEST(WarpMesh, CatmullRomPassesThroughNodesAndReproducesQuadratics) {
  // Interior cells reproduce a quadratic exactly; linear maps everywhere.
  const auto quadratic = [](double s, double t) {
    return WarpNode{s * s + 0.5 * t, 0.3 * s + t * t - s * t, 1.0, true};
  };
  const WarpMesh mesh = mesh_of(9, 7, quadratic, WarpInterpolation::catmull_rom);
  for (double s = 1.0 / 8; s <= 7.0 / 8 + 1e-12; s += 0.0371)
    for (double t = 1.0 / 6; t <= 5.0 / 6 + 1e-12; t += 0.0413) {
      const auto sample = mesh.sample(s, t);
      ASSERT_TRUE(sample);
      EXPECT_NEAR(sample->u, quadratic(s, t).u, 1e-12) << s << " " << t;
      EXPECT_NEAR(sample->v, quadratic(s, t).v, 1e-12) << s << " " << t;
    }
  const auto linear = [](double s, double t) { return WarpNode{0.2 + 0.6 * s, 0.9 - 0.7 * t + 0.1 * s, 1.0, true}; };
  const WarpMesh flat = mesh_of(4, 3, linear, WarpInterpolation::catmull_rom);
  for (double s = 0; s <= 1.0; s += 0.05)
    for (double t = 0; t <= 1.0; t += 0.05) {
      const auto sample = flat.sample(s, t);
      ASSERT_TRUE(sample);
      EXPECT_NEAR(sample->u, linear(s, t).u, 1e-12);
      EXPECT_NEAR(sample->v, linear(s, t).v, 1e-12);
    }
  // Through the nodes.
  for (int j = 0; j < 7; ++j)
    for (int i = 0; i < 9; ++i) {
      const auto sample = mesh.sample(i / 8.0, j / 6.0);
      ASSERT_TRUE(sample);
      EXPECT_NEAR(sample->u, mesh.node(i, j).u, 1e-12);
    }
}

TEST(WarpMesh, CatmullRomIsSmoothAcrossNodes) {
  // The slope on either side of a node agrees (C1); bilinear has a kink there.
  const auto f = [](double s, double t) { return WarpNode{std::sin(4 * s) * (1 + t), t, 1.0, true}; };
  const WarpMesh cubic = mesh_of(9, 5, f, WarpInterpolation::catmull_rom);
  const WarpMesh linear = mesh_of(9, 5, f, WarpInterpolation::bilinear);
  const double h = 1e-7, t = 0.4;
  for (int i = 2; i <= 6; ++i) {
    const double s = i / 8.0;
    const auto slope = [&](const WarpMesh& mesh, double from, double to) {
      return (mesh.sample(to, t)->u - mesh.sample(from, t)->u) / (to - from);
    };
    EXPECT_NEAR(slope(cubic, s - h, s), slope(cubic, s, s + h), 1e-5) << i;
    EXPECT_GT(std::abs(slope(linear, s - h, s) - slope(linear, s, s + h)), 1e-3) << i;
  }
}

TEST(WarpMesh, InvalidCornersLeaveTheirCellsWithoutData) {
  const auto f = [](double s, double t) {
    const bool hole = std::abs(s - 0.5) < 1e-9 && std::abs(t - 0.5) < 1e-9;
    return WarpNode{s, t, 1.0, !hole};
  };
  const WarpMesh mesh = mesh_of(5, 5, f, WarpInterpolation::catmull_rom);
  EXPECT_EQ(mesh.valid_node_count(), 24);
  EXPECT_FALSE(mesh.sample(0.4, 0.4));  // the four cells around the hole
  EXPECT_FALSE(mesh.sample(0.6, 0.55));
  EXPECT_FALSE(mesh.sample(0.5, 0.5));
  const auto near = mesh.sample(0.2, 0.6);  // a neighbouring cell: bilinear fallback, still exact for linear data
  ASSERT_TRUE(near);
  EXPECT_NEAR(near->u, 0.2, 1e-12);
  EXPECT_NEAR(near->v, 0.6, 1e-12);
  EXPECT_FALSE(mesh.sample(-0.01, 0.5));  // outside the extent
  EXPECT_FALSE(mesh.sample(0.5, 1.01));
  EXPECT_FALSE(mesh.sample(std::nan(""), 0.5));
}

TEST(WarpMesh, RejectsMeshesWithoutAValidNodeAndBadShapes) {
  expect_error([] { WarpMesh(2, 2, std::vector<WarpNode>(4), "empty.pfm"); }, {"empty.pfm", "NaN-only mesh"});
  expect_error([] { WarpMesh(1, 2, std::vector<WarpNode>(2, WarpNode{0, 0, 1, true}), "thin"); }, {"[2, 16384]"});
  expect_error([] { WarpMesh(2, 2, std::vector<WarpNode>(3, WarpNode{0, 0, 1, true}), "few"); }, {"given 3 nodes"});
  expect_error(
      [] {
        WarpMesh(2, 2, std::vector<WarpNode>(4, WarpNode{0, 0, 1.5, true}), "bright");
      },
      {"intensity in [0, 1]"});
}

// ---- PFM warp maps ---------------------------------------------------------------

TEST(PfmWarpMesh, NodesSpanTheImageEdgeToEdgeAndNaNHasNoData) {
  const auto value = [](int x, int y, int c) {
    if (x == 3 && y == 2) return kNaN;
    return c == 0 ? 0.1f + 0.2f * x : c == 1 ? 0.05f + 0.3f * y : 0.0f;
  };
  ScratchDir dir("pfm_mesh");
  const auto file = dir.write("warp.pfm", make_pfm(4, 3, 3, value, true, false));
  const WarpMesh mesh = load_pfm_warp_mesh(file, PfmRowOrder::bottom_to_top, WarpInterpolation::bilinear);
  EXPECT_EQ(mesh.columns(), 4);
  EXPECT_EQ(mesh.rows(), 3);
  EXPECT_EQ(mesh.valid_node_count(), 11);
  const auto corner = mesh.sample(0.0, 0.0);  // top-left corner = first node
  ASSERT_TRUE(corner);
  EXPECT_NEAR(corner->u, 0.1, 1e-6);
  EXPECT_NEAR(corner->v, 0.05, 1e-6);
  const auto middle = mesh.sample(0.5 / 3, 0.25);
  ASSERT_TRUE(middle);
  EXPECT_NEAR(middle->u, 0.2, 1e-6);
  EXPECT_NEAR(middle->v, 0.2, 1e-6);
  EXPECT_FALSE(mesh.sample(0.9, 0.9));  // next to the NaN node (3, 2)
}

TEST(PfmWarpMesh, RejectsNaNOnlyAndOneChannelMaps) {
  ScratchDir dir("pfm_nan");
  const auto nan_file = dir.write("nan.pfm", make_pfm(
                                                 3, 3, 3, [](int, int, int) { return kNaN; }, true, false));
  expect_error([&] { load_pfm_warp_mesh(nan_file); }, {"nan.pfm", "NaN-only mesh"});
  const auto grey = dir.write("grey.pfm", make_pfm(3, 3, 1, ramp, true, false));
  expect_error([&] { load_pfm_warp_mesh(grey); }, {"grey.pfm", "needs 3 channels"});
  const auto line = dir.write("line.pfm", make_pfm(3, 1, 3, ramp, true, false));
  expect_error([&] { load_pfm_warp_mesh(line); }, {"line.pfm", "at least 2x2"});
}

// ---- Paul Bourke .data -------------------------------------------------------------

/// A Bourke mesh of nx × ny nodes on the regular grid x ∈ [−aspect, aspect],
/// y ∈ [−1, 1], rows from the bottom; `node` returns "u v intensity" for (x, y).
std::string bourke_text(int nx, int ny, double aspect,
                        const std::function<std::string(double x, double y, int i, int j)>& node,
                        const std::string& eol = "\n") {
  std::ostringstream text;
  text.precision(17);
  text << 2 << eol << nx << " " << ny << eol;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = -aspect + 2.0 * aspect * i / (nx - 1), y = -1.0 + 2.0 * j / (ny - 1);
      text << x << " " << y << " " << node(x, y, i, j) << eol;
    }
  return text.str();
}

std::string identity_node(double x, double y, double aspect) {
  std::ostringstream text;
  text.precision(17);
  text << (x + aspect) / (2 * aspect) << " " << (y + 1) / 2 << " " << 1;
  return text.str();
}

TEST(BourkeMesh, IdentityMeshWarpsAFisheyeIntoItself) {
  ScratchDir dir("bourke");
  const auto file = dir.write(
      "identity.data", bourke_text(17, 17, 1.0, [](double x, double y, int, int) { return identity_node(x, y, 1.0); }));
  const WarpMesh mesh = load_bourke_mesh(file);
  EXPECT_EQ(mesh.columns(), 17);
  EXPECT_EQ(mesh.valid_node_count(), 17 * 17);
  auto fisheye = std::make_shared<FisheyeProjection>(512, 512);
  const WarpedProjection warped(512, 512, mesh, fisheye);
  int compared = 0;
  for (double y = 0.5; y < 512; y += 7.3)
    for (double x = 0.25; x < 512; x += 6.1) {
      const auto expected = fisheye->ray(x, y);
      const auto actual = warped.ray(x, y);
      ASSERT_EQ(expected.has_value(), actual.has_value()) << x << " " << y;
      if (!expected) continue;
      EXPECT_LT(glm::length(*expected - *actual), 1e-6) << x << " " << y;
      EXPECT_NEAR(warped.intensity(x, y), 1.0, 1e-12);
      // The numerical inverse agrees with the fisheye's.
      const auto back = warped.pixel(*expected);
      ASSERT_TRUE(back) << x << " " << y;
      EXPECT_NEAR(back->x, x, 1e-6);
      EXPECT_NEAR(back->y, y, 1e-6);
      ++compared;
    }
  EXPECT_GT(compared, 3000);
  EXPECT_NEAR(warped.max_pixel_angle_rad(), fisheye->max_pixel_angle_rad() * 1.25, 1e-9);
  EXPECT_NE(warped.describe().find("warped 512\u00d7512 (mesh 17\u00d717 catmull-rom from identity.data) over fisheye"),
            std::string::npos)
      << warped.describe();
}

TEST(BourkeMesh, WideProjectorAndFlippedV) {
  // aspect 16:9; v runs up in the file: the top row of the projector (y = +1) shows v = 1, i.e. the source's top.
  const double aspect = 16.0 / 9.0;
  ScratchDir dir("bourke_wide");
  const auto file =
      dir.write("wide.data",
                bourke_text(
                    5, 4, aspect, [&](double x, double y, int, int) { return identity_node(x, y, aspect); }, "\r\n"));
  const WarpMesh mesh = load_bourke_mesh(file);
  const auto top_left = mesh.sample(0.0, 0.0);
  ASSERT_TRUE(top_left);
  EXPECT_NEAR(top_left->u, 0.0, 1e-12);
  EXPECT_NEAR(top_left->v, 0.0, 1e-12);
  const auto point = mesh.sample(0.3, 0.8);
  ASSERT_TRUE(point);
  EXPECT_NEAR(point->u, 0.3, 1e-12);
  EXPECT_NEAR(point->v, 0.8, 1e-12);
}

TEST(BourkeMesh, UnusedNodesHaveNoData) {
  ScratchDir dir("bourke_unused");
  // Node (1, 1) from the bottom-left has a negative intensity, node (3, 2) a u past 1.
  const auto file = dir.write("holes.data", bourke_text(5, 5, 1.0, [](double x, double y, int i, int j) {
                                if (i == 1 && j == 1) return std::string("0.25 0.25 -1");
                                if (i == 3 && j == 2) return std::string("1.5 0.5 1");
                                return identity_node(x, y, 1.0);
                              }));
  const WarpMesh mesh = load_bourke_mesh(file);
  EXPECT_EQ(mesh.valid_node_count(), 23);
  // (1, 1) from the bottom is s = 0.25, t = 0.75.
  EXPECT_FALSE(mesh.sample(0.2, 0.7));
  EXPECT_FALSE(mesh.sample(0.3, 0.8));
  // (3, 2) from the bottom is s = 0.75, t = 0.5.
  EXPECT_FALSE(mesh.sample(0.7, 0.45));
  const auto fine = mesh.sample(0.1, 0.1);
  ASSERT_TRUE(fine);
  EXPECT_NEAR(fine->u, 0.1, 1e-12);
}

TEST(BourkeMesh, IntensityIsInterpolated) {
  ScratchDir dir("bourke_intensity");
  const auto file = dir.write("fade.data", bourke_text(3, 3, 1.0, [](double x, double y, int i, int) {
                                std::ostringstream text;
                                text << (x + 1) / 2 << " " << (y + 1) / 2 << " " << (i == 0 ? 0.0 : i == 1 ? 0.5 : 1.0);
                                return text.str();
                              }));
  const WarpedProjection warped(200, 100, load_bourke_mesh(file), std::make_shared<FisheyeProjection>(100, 100));
  EXPECT_NEAR(warped.intensity(50, 50), 0.25, 1e-12);
  EXPECT_NEAR(warped.intensity(150, 10), 0.75, 1e-12);
  EXPECT_EQ(warped.intensity(-5, 10), 0.0);  // outside the mesh
}

TEST(BourkeMesh, WarpInTheNodePositionsIsResampled) {
  // x positions bunched toward the left (x = −1 + 2 (i / 8)²), u regular: u(s) ≈ sqrt(s).
  const int n = 9;
  std::ostringstream text;
  text.precision(17);
  text << "2\n" << n << " " << n << "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = double(i) / (n - 1);
      text << -1.0 + 2.0 * a * a << " " << -1.0 + 2.0 * j / (n - 1) << " " << a << " " << double(j) / (n - 1) << " 1\n";
    }
  ScratchDir dir("bourke_xy");
  const WarpMesh mesh = load_bourke_mesh(dir.write("xy.data", text.str()));
  EXPECT_EQ(mesh.columns(), 33);
  // The file's map is piecewise linear between the nodes (s_i = (i / 8)², u_i = i / 8).
  const auto reference_u = [&](double s) {
    int i = 0;
    while (i < n - 2 && s > std::pow((i + 1.0) / (n - 1), 2)) ++i;
    const double s0 = std::pow(double(i) / (n - 1), 2), s1 = std::pow((i + 1.0) / (n - 1), 2);
    return (i + (s - s0) / (s1 - s0)) / (n - 1);
  };
  for (const double s : {0.1, 0.25, 0.5, 0.81, 0.97}) {
    const auto sample = mesh.sample(s, 0.5);
    ASSERT_TRUE(sample) << s;
    EXPECT_NEAR(sample->u, reference_u(s), 0.005) << s;
    EXPECT_NEAR(sample->v, 0.5, 1e-9) << s;
  }
}

TEST(BourkeMesh, RejectsBadHeaders) {
  ScratchDir dir("bourke_header");
  expect_error([&] { load_bourke_mesh(dir.write("t.data", "3\n2 2\n")); }, {"t.data:1: mesh type 3", "must be 2"});
  expect_error([&] { load_bourke_mesh(dir.write("p.data", "1\n2 2\n")); }, {"p.data:1:", "polar", "not supported"});
  expect_error([&] { load_bourke_mesh(dir.write("w.data", "two\n2 2\n")); },
               {"w.data:1: field 'mesh type' = 'two' is not an integer"});
  expect_error([&] { load_bourke_mesh(dir.write("c.data", "2\n10\n")); },
               {"c.data:2: expected 2 fields (nx ny), found 1"});
  expect_error([&] { load_bourke_mesh(dir.write("n.data", "2\n10 x\n")); },
               {"n.data:2: field 'ny' = 'x' is not an integer"});
  expect_error([&] { load_bourke_mesh(dir.write("s.data", "2\n1 5\n")); },
               {"s.data:2: field 'nx' = 1: must be in [2, 16384]"});
  expect_error([&] { load_bourke_mesh(dir.write("e.data", "")); }, {"e.data: truncated"});
  expect_error([&] { load_bourke_mesh(dir.path() / "missing.data"); }, {"missing.data: cannot open"});
}

TEST(BourkeMesh, RejectsWrongCountsAndTruncation) {
  ScratchDir dir("bourke_counts");
  const std::string full =
      bourke_text(3, 3, 1.0, [](double x, double y, int, int) { return identity_node(x, y, 1.0); });
  // One node too many: line 12 (2 header lines + 9 nodes + 1).
  expect_error([&] { load_bourke_mesh(dir.write("many.data", full + "0 0 0.5 0.5 1\n")); },
               {"many.data:12: more than nx x ny = 3 x 3 = 9 nodes"});
  // Two nodes missing.
  std::string cut = full;
  for (int k = 0; k < 2; ++k) cut.erase(cut.find_last_of('\n', cut.size() - 2) + 1);
  expect_error([&] { load_bourke_mesh(dir.write("short.data", cut)); },
               {"short.data: truncated: 7 of nx x ny = 3 x 3 = 9 nodes", "last at line 9"});
  // Trailing blank lines are fine.
  EXPECT_NO_THROW(load_bourke_mesh(dir.write("blank.data", full + "\n\n  \n")));
}

TEST(BourkeMesh, RejectsBadFieldsWithLineAndFieldName) {
  ScratchDir dir("bourke_fields");
  const auto with_line_5 = [](const std::string& line) {
    return "2\n2 2\n-1 -1 0 0 1\n1 -1 1 0 1\n" + line + "\n1 1 1 1 1\n";
  };
  expect_error([&] { load_bourke_mesh(dir.write("u.data", with_line_5("-1 1 abc 1 1"))); },
               {"u.data:5: field 'u' = 'abc' is not a number"});
  expect_error([&] { load_bourke_mesh(dir.write("i.data", with_line_5("-1 1 0 1 0.5x"))); },
               {"i.data:5: field 'intensity' = '0.5x' is not a number"});
  expect_error([&] { load_bourke_mesh(dir.write("f.data", with_line_5("-1 1 0 1"))); },
               {"f.data:5: expected 5 fields (x y u v intensity), found 4"});
  expect_error([&] { load_bourke_mesh(dir.write("x.data", with_line_5("nan 1 0 1 1"))); },
               {"x.data:5: field 'x' = 'nan' must be finite"});
  EXPECT_NO_THROW(load_bourke_mesh(dir.write("ok.data", with_line_5("-1 +1 0 1 1"))));
}

TEST(BourkeMesh, RejectsAMeshWithoutUsedNodes) {
  ScratchDir dir("bourke_unused_all");
  const auto file = dir.write(
      "none.data", bourke_text(3, 3, 1.0, [](double, double, int, int) { return std::string("0.5 0.5 -1"); }));
  expect_error([&] { load_bourke_mesh(file); }, {"none.data", "NaN-only mesh"});
}

// ---- WarpedProjection ------------------------------------------------------------------

TEST(WarpedProjection, RaysFollowTheInterpolatedSourcePoints) {
  // A bilinear mesh over a planar base: between nodes the source point is the
  // bilinear interpolant, and the ray is the base's ray there.
  const auto f = [](double s, double t) {
    return WarpNode{0.1 + 0.8 * s + 0.05 * t * t, 0.2 + 0.6 * t + 0.1 * s * s, 1.0, true};
  };
  const WarpMesh mesh = mesh_of(3, 3, f, WarpInterpolation::bilinear);
  auto base = std::make_shared<PlanarProjection>(PlanarProjection::symmetric(800, 600, 90.0));
  const WarpedProjection warped(400, 300, mesh, base);
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{100, 75}, {50, 200}, {333, 12}, {399, 299}}) {
    const double s = x / 400, t = y / 300;
    const int i = std::min(1, int(s * 2)), j = std::min(1, int(t * 2));
    const double a = s * 2 - i, b = t * 2 - j;
    const auto corner = [&](int di, int dj) { return f((i + di) / 2.0, (j + dj) / 2.0); };
    const double u = (1 - a) * (1 - b) * corner(0, 0).u + a * (1 - b) * corner(1, 0).u + (1 - a) * b * corner(0, 1).u +
                     a * b * corner(1, 1).u;
    const double v = (1 - a) * (1 - b) * corner(0, 0).v + a * (1 - b) * corner(1, 0).v + (1 - a) * b * corner(0, 1).v +
                     a * b * corner(1, 1).v;
    const auto source = warped.source_pixel(x, y);
    ASSERT_TRUE(source);
    EXPECT_NEAR(source->x, u * 800, 1e-9);
    EXPECT_NEAR(source->y, v * 600, 1e-9);
    const auto ray = warped.ray(x, y);
    ASSERT_TRUE(ray);
    EXPECT_LT(glm::length(*ray - *base->ray(u * 800, v * 600)), 1e-12);
    const auto back = warped.pixel(*ray);
    ASSERT_TRUE(back);
    EXPECT_NEAR(back->x, x, 1e-5);
    EXPECT_NEAR(back->y, y, 1e-5);
  }
  // A direction the mesh never shows (behind the planar base) has no pixel.
  EXPECT_FALSE(warped.pixel({0.0, 0.0, 1.0}));
  EXPECT_GT(warped.max_pixel_angle_rad(), base->max_pixel_angle_rad());
}

TEST(WarpedProjection, IsTabulatedOnTheGpuAndNeedsABase) {
  const WarpMesh mesh = mesh_of(
      2, 2,
      [](double s, double t) {
        return WarpNode{s, t, 1.0, true};
      },
      WarpInterpolation::bilinear);
  const WarpedProjection warped(64, 64, mesh, std::make_shared<FisheyeProjection>(64, 64));
  EXPECT_EQ(warped.gpu().kind, ProjectionKind::ray_table);
  expect_error([&] { WarpedProjection(64, 64, mesh, nullptr); }, {"base projection is null"});
  expect_error([&] { WarpedProjection(0, 64, mesh, std::make_shared<FisheyeProjection>(64, 64)); }, {"width_px"});
}

// ---------------------------------------------------------------- local pixel footprint (not the mesh's worst case)

/// A mesh whose source pixel is affine in the projector pixel: source px =
/// c + J (x − w/2, y − h/2) for a w × h projector over a base of size (wb, hb),
/// so σ_max(J) is the closed-form local stretch everywhere.
WarpMesh affine_mesh(int w, int h, int wb, int hb, const std::array<double, 4>& jacobian,
                     WarpInterpolation interpolation,
                     const std::function<std::optional<WarpNode>(int i, int j)>& override_node = {}) {
  const int n = 9;
  std::vector<WarpNode> nodes;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (override_node)
        if (const auto o = override_node(i, j)) {
          nodes.push_back(*o);
          continue;
        }
      const double dx = (double(i) / (n - 1) - 0.5) * w, dy = (double(j) / (n - 1) - 0.5) * h;
      const double u_px = 0.5 * wb + jacobian[0] * dx + jacobian[1] * dy;
      const double v_px = 0.5 * hb + jacobian[2] * dx + jacobian[3] * dy;
      nodes.push_back({u_px / wb, v_px / hb, 1.0, true});
    }
  return WarpMesh(n, n, std::move(nodes), "affine", interpolation);
}

/// σ_max of [[a, b], [c, d]] by the eigenvalues of JᵀJ written out for the test.
double largest_singular_value(const std::array<double, 4>& j) {
  const double p = j[0] * j[0] + j[2] * j[2], q = j[0] * j[1] + j[2] * j[3], r = j[1] * j[1] + j[3] * j[3];
  return std::sqrt(0.5 * (p + r) + std::sqrt(0.25 * (p - r) * (p - r) + q * q));
}

TEST(WarpedProjectionFootprint, IsTheBaseFootprintTimesTheLocalStretch) {
  const auto fisheye = std::make_shared<FisheyeProjection>(400, 400);
  const double base = fisheye->max_pixel_angle_rad();
  // A projection without a warp answers its bound everywhere.
  EXPECT_EQ(fisheye->pixel_angle_rad_at({0.3, 0.2, -1.0}), base);
  const double c = std::cos(0.6), s = std::sin(0.6);
  for (const auto& [name, jacobian] : std::vector<std::pair<std::string, std::array<double, 4>>>{
           {"axis-aligned 0.4 × 1.2", {0.4, 0.0, 0.0, 1.2}},
           {"rotated, scaled 1.5", {1.5 * c, -1.5 * s, 1.5 * s, 1.5 * c}},
           {"sheared", {0.5, 0.7, 0.1, 0.9}},
           {"shrunk 0.3", {0.3, 0.0, 0.0, 0.3}}}) {
    const WarpedProjection warped(200, 160, affine_mesh(200, 160, 400, 400, jacobian, WarpInterpolation::bilinear),
                                  fisheye);
    const double expected = base * largest_singular_value(jacobian);
    for (const auto& [x, y] :
         std::vector<std::pair<double, double>>{{100, 80}, {37.5, 20.5}, {180.2, 150.9}, {5, 155}}) {
      const auto ray = warped.ray(x, y);
      ASSERT_TRUE(ray) << name;
      EXPECT_NEAR(warped.pixel_angle_rad_at(*ray), expected, 1e-7 * expected) << name << " at " << x << ", " << y;
    }
  }
}

TEST(WarpedProjectionFootprint, ParkedNodesDoNotInflateIt) {
  // Bourke's meshes park unused projector nodes at (0, 0) with a faint but
  // valid intensity: the worst-case bound sees the jump to (0, 0) as a stretch,
  // the footprint where something lands does not.
  const auto fisheye = std::make_shared<FisheyeProjection>(400, 400);
  const double base = fisheye->max_pixel_angle_rad();
  const std::array<double, 4> jacobian{0.8, 0.0, 0.0, 0.8};
  for (const WarpInterpolation interpolation : {WarpInterpolation::bilinear, WarpInterpolation::catmull_rom}) {
    const WarpedProjection warped(200, 200,
                                  affine_mesh(200, 200, 400, 400, jacobian, interpolation,
                                              [](int i, int j) -> std::optional<WarpNode> {
                                                if ((i == 0 || i == 8) && j == 0) return WarpNode{0.0, 0.0, 0.02, true};
                                                return std::nullopt;
                                              }),
                                  fisheye);
    // The node next to a parked one is 184 base px from (0, 0), 25 projector px away: k = 7.4.
    EXPECT_GT(warped.max_pixel_angle_rad(), 8.0 * base * 0.8) << "the bound keeps the worst case, for culling";
    // Directions in the middle of the image, and one the projector never shows
    // (beyond its frame, still in the dome): the local stretch, 0.8.
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{{100, 100}, {60, 140}, {150, 120}}) {
      const auto ray = warped.ray(x, y);
      ASSERT_TRUE(ray);
      EXPECT_NEAR(warped.pixel_angle_rad_at(*ray), 0.8 * base, 1e-7 * base) << x << ", " << y;
    }
    const auto off_frame = fisheye->ray(200 + 0.8 * 160, 200 + 0.8 * 60);  // the projector's x = 260 px: off its frame
    ASSERT_TRUE(off_frame);
    ASSERT_FALSE(warped.pixel(*off_frame));
    EXPECT_NEAR(warped.pixel_angle_rad_at(*off_frame), 0.8 * base, 1e-7 * base);
  }
}

// ---------------------------------------------------------------- culling bound per tile (not the mesh's worst case)

TEST(WarpedProjectionCulling, ARectanglesBoundComesFromTheNodesThatReachIt) {
  // A 200 × 200 projector, 9 × 9 nodes (cells of 25 px), source px = 1.5 ×
  // projector px over a 400² fisheye; in the parked mesh node (0, 0) is parked
  // at (0, 0) with intensity 0.02, as Bourke's meshes do. A 16 px tile's bound
  // comes from the nodes of its cells' 4 × 4 stencils: the parked node reaches
  // cells 0 and 1 (pixels [0, 50)) in each direction, so the tiles starting
  // there take the large bound and every other tile has the bound of the mesh
  // without it, base · 1.5 · 1.25.
  const auto fisheye = std::make_shared<FisheyeProjection>(400, 400);
  const double base = fisheye->max_pixel_angle_rad();
  const std::array<double, 4> jacobian{1.5, 0.0, 0.0, 1.5};
  const auto park = [](int i, int j) -> std::optional<WarpNode> {
    if (i == 0 && j == 0) return WarpNode{0.0, 0.0, 0.02, true};
    return std::nullopt;
  };
  for (const WarpInterpolation interpolation : {WarpInterpolation::bilinear, WarpInterpolation::catmull_rom}) {
    const WarpedProjection clean(200, 200, affine_mesh(200, 200, 400, 400, jacobian, interpolation), fisheye);
    const WarpedProjection parked(200, 200, affine_mesh(200, 200, 400, 400, jacobian, interpolation, park), fisheye);
    EXPECT_NEAR(clean.max_pixel_angle_rad(), base * 1.5 * 1.25, 1e-12);
    EXPECT_GT(parked.max_pixel_angle_rad(), 2.0 * clean.max_pixel_angle_rad()) << "the worst case, as before";
    EXPECT_EQ(parked.max_pixel_angle_rad_within(0, 0, 200, 200), parked.max_pixel_angle_rad());
    int same = 0, widened = 0;
    for (int y0 = 0; y0 < 200; y0 += 16)
      for (int x0 = 0; x0 < 200; x0 += 16) {
        const int x1 = std::min(x0 + 16, 200), y1 = std::min(y0 + 16, 200);
        const double p = parked.max_pixel_angle_rad_within(x0, y0, x1, y1);
        const double c = clean.max_pixel_angle_rad_within(x0, y0, x1, y1);
        EXPECT_NEAR(c, clean.max_pixel_angle_rad(), 1e-12);
        EXPECT_LE(p, parked.max_pixel_angle_rad());
        if (x0 < 50 && y0 < 50) {
          EXPECT_GT(p, 2.0 * c) << x0 << ", " << y0;
          ++widened;
        } else {
          EXPECT_EQ(p, c) << x0 << ", " << y0;
          ++same;
        }
        // Conservative: neighbouring pixel centres of the tile (across, down,
        // diagonally) are never farther apart than the tile's bound.
        for (const WarpedProjection* w : {&parked, &clean}) {
          const double bound = w->max_pixel_angle_rad_within(x0, y0, x1, y1);
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
              const auto r = w->ray(x + 0.5, y + 0.5);
              if (!r) continue;
              for (const auto& [dx, dy] : std::vector<std::pair<int, int>>{{1, 0}, {0, 1}, {1, 1}, {1, -1}}) {
                if (x + dx >= x1 || y + dy < y0 || y + dy >= y1) continue;
                const auto q = w->ray(x + dx + 0.5, y + dy + 0.5);
                if (!q) continue;
                ASSERT_LE(std::acos(std::min(1.0, glm::dot(*r, *q))), bound)
                    << x << ", " << y << " +" << dx << "," << dy;
              }
            }
        }
      }
    EXPECT_EQ(widened, 16);  // tiles starting at 0, 16, 32, 48 in each direction
    EXPECT_EQ(same, 13 * 13 - 16);
    // A rectangle off the image: nothing there has a ray.
    EXPECT_EQ(parked.max_pixel_angle_rad_within(300, 300, 316, 316), base * 1.25);
    // A mesh running past the image (a Bourke mesh fitted to a narrower
    // output): over s ∈ [−0.5, 1.5] the parked node's cells end at the image's
    // left edge, so no pixel shows them and even the worst case leaves them out.
    const WarpMesh::Extent wide{-0.5, 1.5, 0.0, 1.0};
    const WarpedProjection wide_clean(200, 200, WarpMesh(9, 9, clean.mesh().nodes(), "wide", interpolation, wide),
                                      fisheye);
    const WarpedProjection wide_parked(200, 200, WarpMesh(9, 9, parked.mesh().nodes(), "wide", interpolation, wide),
                                       fisheye);
    EXPECT_EQ(wide_parked.max_pixel_angle_rad(), wide_clean.max_pixel_angle_rad());
  }
}

}  // namespace
}  // namespace zenith::warp
