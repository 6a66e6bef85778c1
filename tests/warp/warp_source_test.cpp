// A warp's source image has its own size (the spherical-mirror
// setup): a Bourke mesh's (u, v) address a square fisheye dome master while the
// projector output is 16:9. The rays of a viewport output are compared with an
// independent sampler (output pixel → bilinear in the generated mesh → (u, v)
// → fisheye ray of a square source), the 16:9 output is covered where the mesh
// covers it, and bad "source" sizes are refused naming the key and the range.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/json_reader.h"
#include "core/units.h"
#include "tests/warp/mpcdi_test_support.h"
#include "warp/viewport_config.h"
#include "warp/warped_projection.h"
#include "warp_file_test_support.h"

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
/// the bottom of the projector image, x ∈ [−aspect, aspect]; u and v are
/// bilinear in (x, y), so Catmull–Rom and bilinear interpolation agree with the
/// sampler below exactly. Every used (u, v) lies inside the circle of a square
/// source. The two bottom corner nodes are unused (intensity −1).
std::vector<Node> mirror_mesh(double aspect = kAspect) {
  std::vector<Node> nodes;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const double x = -aspect + 2.0 * aspect * i / (kNx - 1), y = -1.0 + 2.0 * j / (kNy - 1);
      const double up = (y + 1.0) / 2.0;  // 0 at the bottom, 1 at the top
      Node n{x, y, 0.5 + (x / aspect) * (0.3 + 0.05 * up), 0.1 + 0.75 * up, 0.5 + 0.5 * up};
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

/// The ray of source pixel (sx, sy) of a w × h, 180° angular fisheye (the
/// circle's centre (w/2, h/2), radius `radius_px`, min(w, h)/2 when 0; centre
/// → +y, bottom of the rim → −z, right → +x); nothing outside the circle.
std::optional<glm::dvec3> fisheye_ray(double sx, double sy, double w, double h, double radius_px = 0.0) {
  const double radius = radius_px > 0.0 ? radius_px : std::min(w, h) / 2.0;
  const double dx = sx - w / 2.0, dy = h / 2.0 - sy, r = std::hypot(dx, dy);
  if (r > radius) return std::nullopt;
  const double theta = r / radius * zenith::core::kPi / 2.0;
  if (r == 0.0) return glm::dvec3(0, 1, 0);
  // image right → +x, image up → +z (toward the back), axis → +y.
  return glm::dvec3(std::sin(theta) * dx / r, std::cos(theta), std::sin(theta) * dy / r);
}

/// What an output shows of a mesh's (x, y) plane: a width_px × height_px image
/// spanning x ∈ [−half_x, half_x], y ∈ [−half_y, half_y], of a mesh whose nodes
/// span x ∈ [−mesh_aspect, mesh_aspect], y ∈ [−1, 1].
struct Frame {
  int width_px = kWidth, height_px = kHeight;
  double half_x = kAspect, half_y = 1.0, mesh_aspect = kAspect;
};

/// The independent sampler. Output pixel (px, py) of the frame's output →
/// Bourke (x, y) → the node cell → bilinear (u, v) (nothing off the mesh or
/// when a corner is unused) → the source pixel of a side × side dome master
/// (v up → down) → the 180° angular fisheye's ray (centre → +y, bottom of the
/// rim → −z, right → +x).
std::optional<glm::dvec3> expected_ray(const std::vector<Node>& nodes, double px, double py, double side,
                                       const Frame& frame = {}) {
  const double x = frame.half_x * (2.0 * px / frame.width_px - 1.0),
               y = frame.half_y * (1.0 - 2.0 * py / frame.height_px);
  const double a_m = frame.mesh_aspect;
  if (std::abs(x) > a_m || std::abs(y) > 1.0) return std::nullopt;
  const double fi = (x + a_m) / (2.0 * a_m) * (kNx - 1), fj = (y + 1.0) / 2.0 * (kNy - 1);
  const int i = std::min(static_cast<int>(std::floor(fi)), kNx - 2),
            j = std::min(static_cast<int>(std::floor(fj)), kNy - 2);
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
  return fisheye_ray(u * side, (1.0 - v_up) * side, side, side);  // source pixel, y down
}

struct MirrorSetup {
  ScratchDir dir{"warp_source"};
  std::vector<Node> nodes;
  explicit MirrorSetup(double mesh_aspect = kAspect) : nodes(mirror_mesh(mesh_aspect)) {
    dir.write("mirror.data", bourke_file(nodes));
  }

  json config(const json& source = nullptr) const {
    json j = json::parse(R"({"zenith_viewports": 1, "name": "mirror", "outputs": [
      {"name": "p", "size": [160, 90], "projection": {"type": "fisheye", "fov_deg": 180},
       "warp": {"file": "mirror.data", "format": "bourke"}}]})");
    if (!source.is_null()) j["outputs"][0]["warp"]["source"] = source;
    return j;
  }
  /// config() at another output size, with "fit" when given.
  json config_at(int width_px, int height_px, const std::string& fit = "") const {
    json j = config();
    j["outputs"][0]["size"] = json{width_px, height_px};
    if (!fit.empty()) j["outputs"][0]["warp"]["fit"] = fit;
    return j;
  }
  ViewportConfig parse(const json& j) const { return parse_viewport_config(j, "mirror.json", dir.path()); }
};

const WarpedProjection& warped_of(const ViewportConfig& c) {
  const auto* w = dynamic_cast<const WarpedProjection*>(c.outputs.at(0).projection.get());
  if (w == nullptr) throw std::logic_error("not a warped projection");
  return *w;
}

/// The warped projection of the config's first output, kept alive past the config.
std::shared_ptr<const WarpedProjection> warped_output(const ViewportConfig& c) {
  auto w = std::dynamic_pointer_cast<const WarpedProjection>(c.outputs.at(0).projection);
  if (!w) throw std::logic_error("not a warped projection");
  return w;
}

/// Pixels of `warped` compared with an independent sampler (within 1e-6), and
/// those without a ray in both; a pixel with a ray in one and not the other fails.
struct Agreement {
  int compared = 0, without_ray = 0;
};
Agreement compare_rays(const Projection& warped,
                       const std::function<std::optional<glm::dvec3>(double x_px, double y_px)>& sampler) {
  Agreement agreement;
  for (int py = 0; py < warped.height(); ++py)
    for (int px = 0; px < warped.width(); ++px) {
      const double x = px + 0.5, y = py + 0.5;
      const auto expected = sampler(x, y);
      const auto actual = warped.ray(x, y);
      EXPECT_EQ(expected.has_value(), actual.has_value()) << x << " " << y;
      if (expected.has_value() != actual.has_value()) return agreement;
      if (!expected) {
        ++agreement.without_ray;
        continue;
      }
      EXPECT_LT(glm::length(*expected - *actual), 1e-6) << x << " " << y;
      ++agreement.compared;
    }
  return agreement;
}
/// compare_rays() with the Bourke sampler of `nodes` seen through `frame`.
Agreement compare_with_sampler(const WarpedProjection& warped, const std::vector<Node>& nodes, const Frame& frame) {
  return compare_rays(warped,
                      [&](double x, double y) { return expected_ray(nodes, x, y, warped.base().height(), frame); });
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

  const Agreement agreement = compare_with_sampler(warped, setup.nodes, Frame{});
  EXPECT_GT(agreement.compared, kWidth * kHeight * 9 / 10);
  EXPECT_GT(agreement.without_ray, 0);  // the unused corner cells
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
      {json{{"aspect", 1}, {"size_px", {90, 90}}}, "/outputs/0/warp/source/aspect",
       "either size_px or aspect, not both"},
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

// ---- "fit": a mesh made for another aspect ratio ---------------------------------

/// Counts the rows of column `px` without a ray, and the columns of row `py`.
int rows_without_ray(const WarpedProjection& w, int px) {
  int n = 0;
  for (int py = 0; py < w.height(); ++py) n += !w.ray(px + 0.5, py + 0.5).has_value();
  return n;
}
int columns_without_ray(const WarpedProjection& w, int py) {
  int n = 0;
  for (int px = 0; px < w.width(); ++px) n += !w.ray(px + 0.5, py + 0.5).has_value();
  return n;
}

TEST(WarpFit, ASixteenByNineMeshAtFourByThreeIsCroppedAtTheSidesByDefault) {
  // Bourke's tools and SGCT put y ∈ [−1, 1] across the output's height and x
  // in the same units (x / aspect of the window), so a 16:9 mesh at a 4:3
  // output loses its sides: a 120 × 90 output shows x ∈ [−4/3, 4/3], the
  // middle 120 columns of the same mesh at 160 × 90, pixel for pixel.
  const MirrorSetup setup;
  const ViewportConfig wide = setup.parse(setup.config());
  const ViewportConfig narrow = setup.parse(setup.config_at(120, 90));
  ASSERT_EQ(narrow.outputs[0].warp->fit, MeshFit::height);
  const WarpedProjection& w = warped_of(wide);
  const WarpedProjection& n = warped_of(narrow);
  EXPECT_EQ(n.base().width(), 90);  // the square dome master, as at 16:9
  const Agreement agreement = compare_with_sampler(n, setup.nodes, {120, 90, 4.0 / 3.0, 1.0, kAspect});
  EXPECT_EQ(agreement.compared + agreement.without_ray, 120 * 90);
  EXPECT_GT(agreement.compared, 120 * 90 * 95 / 100);
  int same = 0;
  for (int py = 0; py < 90; ++py)
    for (int px = 0; px < 120; ++px) {
      const auto a = n.ray(px + 0.5, py + 0.5), b = w.ray(px + 20.5, py + 0.5);
      ASSERT_EQ(a.has_value(), b.has_value()) << px << " " << py;
      if (!a) continue;
      ASSERT_LT(glm::length(*a - *b), 1e-9) << px << " " << py;
      ++same;
    }
  EXPECT_EQ(same, agreement.compared);
  // Every column has its rays down to the mesh's bottom: nothing is squeezed
  // off, nothing is black at the sides.
  EXPECT_EQ(rows_without_ray(n, 0), 0);
  EXPECT_EQ(rows_without_ray(n, 119), 0);
  // "crop" is the same for a mesh wider than the output.
  const ViewportConfig crop = setup.parse(setup.config_at(120, 90, "crop"));
  const Agreement cropped = compare_with_sampler(warped_of(crop), setup.nodes, {120, 90, 4.0 / 3.0, 1.0, kAspect});
  EXPECT_EQ(cropped.compared, agreement.compared);
}

TEST(WarpFit, StretchSqueezesTheMeshIntoTheOutputAsBefore) {
  // What zenith did before "fit": the mesh's x ∈ [−16/9, 16/9] across the 4:3
  // output's width, squeezing the dome by 0.75 across.
  const MirrorSetup setup;
  const auto s_output = warped_output(setup.parse(setup.config_at(120, 90, "stretch")));
  const WarpedProjection& s = *s_output;
  const Agreement agreement = compare_with_sampler(s, setup.nodes, {120, 90, kAspect, 1.0, kAspect});
  EXPECT_GT(agreement.compared, 120 * 90 * 9 / 10);
  // Its left column shows the mesh's left edge, which height cuts off: at mid
  // height the stretched output's column 0 and the 16:9 output's column 0
  // have the same ray (x = −16/9 · 119/120 and −16/9 · 159/160 are 0.0037
  // apart: within 0.6° of each other).
  const auto w_output = warped_output(setup.parse(setup.config()));
  const WarpedProjection& w = *w_output;
  const auto a = s.ray(0.5, 45.5), b = w.ray(0.5, 45.5);
  ASSERT_TRUE(a && b);
  EXPECT_LT(std::acos(std::min(1.0, glm::dot(*a, *b))), 0.6 * zenith::core::kDeg);
}

TEST(WarpFit, WidthAndLetterboxShowTheWholeWideMeshWithBarsTopAndBottom) {
  // x ∈ [−16/9, 16/9] across 120 px: y ∈ [−4/3, 4/3] down 90 px, so a bar of
  // 90 · (1 − 3/4) / 2 = 11.25 rows above and below the mesh.
  const MirrorSetup setup;
  for (const char* fit : {"width", "letterbox"}) {
    SCOPED_TRACE(fit);
    const auto l_output = warped_output(setup.parse(setup.config_at(120, 90, fit)));
    const WarpedProjection& l = *l_output;
    const Agreement agreement = compare_with_sampler(l, setup.nodes, {120, 90, kAspect, 4.0 / 3.0, kAspect});
    EXPECT_GT(agreement.compared, 120 * 90 * 7 / 10);
    EXPECT_EQ(rows_without_ray(l, 60), 2 * 11);  // rows 0–10 and 79–89 (centres 0.5 … 10.5, 79.5 … 89.5)
    EXPECT_FALSE(l.ray(60.5, 10.5));
    EXPECT_TRUE(l.ray(60.5, 11.5));
    EXPECT_TRUE(l.ray(60.5, 78.5));
    EXPECT_FALSE(l.ray(60.5, 79.5));
    EXPECT_EQ(columns_without_ray(l, 45), 0);  // the full width
  }
}

TEST(WarpFit, ANarrowerMeshGetsBarsAtTheSidesByDefaultAndIsCroppedTopAndBottomByCrop) {
  // A 4:3 mesh at the 16:9 output (160 × 90): height shows x ∈ [−16/9, 16/9],
  // the mesh's x ∈ [−4/3, 4/3] in the middle 120 columns, 20 black columns on
  // each side (SGCT's behaviour); crop (= width for a narrower mesh) fills the
  // width and cuts y to ±3/4; letterbox = height; stretch spans it edge to edge.
  const MirrorSetup setup(4.0 / 3.0);
  const auto h_output = warped_output(setup.parse(setup.config()));
  const WarpedProjection& h = *h_output;
  compare_with_sampler(h, setup.nodes, {160, 90, kAspect, 1.0, 4.0 / 3.0});
  EXPECT_EQ(columns_without_ray(h, 45), 40);
  EXPECT_FALSE(h.ray(19.5, 45.5));
  EXPECT_TRUE(h.ray(20.5, 45.5));
  EXPECT_TRUE(h.ray(139.5, 45.5));
  EXPECT_FALSE(h.ray(140.5, 45.5));
  const auto l_output = warped_output(setup.parse(setup.config_at(160, 90, "letterbox")));
  const WarpedProjection& l = *l_output;
  EXPECT_EQ(compare_with_sampler(l, setup.nodes, {160, 90, kAspect, 1.0, 4.0 / 3.0}).compared,
            compare_with_sampler(h, setup.nodes, {160, 90, kAspect, 1.0, 4.0 / 3.0}).compared);

  const auto c_output = warped_output(setup.parse(setup.config_at(160, 90, "crop")));
  const WarpedProjection& c = *c_output;
  const Agreement cropped = compare_with_sampler(c, setup.nodes, {160, 90, 4.0 / 3.0, 0.75, 4.0 / 3.0});
  EXPECT_EQ(cropped.without_ray, 0);  // the mesh's unused bottom corners lie below the output
  EXPECT_EQ(columns_without_ray(c, 0), 0);
  EXPECT_EQ(columns_without_ray(c, 89), 0);

  const auto s_output = warped_output(setup.parse(setup.config_at(160, 90, "stretch")));
  const WarpedProjection& s = *s_output;
  compare_with_sampler(s, setup.nodes, {160, 90, 4.0 / 3.0, 1.0, 4.0 / 3.0});
  EXPECT_EQ(columns_without_ray(s, 45), 0);
}

TEST(WarpFit, ABadFitIsRefusedNamingTheKeyAndTheValues) {
  const MirrorSetup setup;
  testing::expect_config_error(
      [&] { setup.parse(setup.config_at(160, 90, "squeeze")); }, "mirror.json", "/outputs/0/warp/fit",
      "= \"squeeze\": must be one of \"height\", \"width\", \"crop\", \"letterbox\", \"stretch\"");
  json number = setup.config();
  number["outputs"][0]["warp"]["fit"] = 1;
  testing::expect_config_error([&] { setup.parse(number); }, "mirror.json", "/outputs/0/warp/fit", "must be a string");
  // A PFM or MPCDI map spans its output edge to edge by definition.
  setup.dir.write("map.pfm", testing::make_pfm(
                                 2, 2, 3,
                                 [](int x, int y, int c) {
                                   return c == 0 ? static_cast<float>(x) : c == 1 ? static_cast<float>(y) : 0.0f;
                                 },
                                 true, false));
  json pfm = setup.config_at(160, 90, "crop");
  pfm["outputs"][0]["warp"]["file"] = "map.pfm";
  pfm["outputs"][0]["warp"]["format"] = "pfm";
  testing::expect_config_error([&] { setup.parse(pfm); }, "mirror.json", "/outputs/0/warp/fit",
                               "applies to \"format\": \"bourke\" only (format is \"pfm\")");
}

TEST(WarpFit, FramesOfEachFit) {
  // bourke_frame(fit, mesh aspect, output aspect): the half-extents shown.
  const auto expect_frame = [](MeshFit fit, double mesh, double output, double half_x, double half_y) {
    const BourkeFrame f = bourke_frame(fit, mesh, output);
    EXPECT_DOUBLE_EQ(f.half_x, half_x) << to_string(fit);
    EXPECT_DOUBLE_EQ(f.half_y, half_y) << to_string(fit);
  };
  const double wide = 16.0 / 9.0, narrow = 4.0 / 3.0;
  expect_frame(MeshFit::height, wide, narrow, narrow, 1.0);
  expect_frame(MeshFit::width, wide, narrow, wide, wide / narrow);
  expect_frame(MeshFit::crop, wide, narrow, narrow, 1.0);
  expect_frame(MeshFit::letterbox, wide, narrow, wide, wide / narrow);
  expect_frame(MeshFit::stretch, wide, narrow, wide, 1.0);
  expect_frame(MeshFit::crop, narrow, wide, narrow, narrow / wide);
  expect_frame(MeshFit::letterbox, narrow, wide, wide, 1.0);
  for (const MeshFit fit : {MeshFit::height, MeshFit::width, MeshFit::crop, MeshFit::letterbox, MeshFit::stretch})
    expect_frame(fit, wide, wide, wide, 1.0);  // equal aspects: every fit is the same
  EXPECT_THROW(bourke_frame(MeshFit::height, 0.0, 1.0), std::invalid_argument);
}

// ---- MPCDI: the region's resolution is the source ------------------------------

/// A one-region archive of `profile` ("2d", or "3d" with a frustum of ±40° ×
/// ±25°): region "r" of x_res × y_res px spanning its buffer, its 5 × 4
/// geometry warp (linear) (x, y) = (0.05 + 0.9 s, 0.1 + 0.8 t), s, t ∈ [0, 1]
/// across the projector.
void region_archive(const ScratchDir& dir, const std::string& name, const std::string& profile, int x_res, int y_res) {
  const std::string resolution =
      "xResolution=\"" + std::to_string(x_res) + "\" yResolution=\"" + std::to_string(y_res) + "\"";
  const std::string frustum = profile == "3d" ? "<frustum><yaw>0</yaw><pitch>0</pitch><roll>0</roll>"
                                                "<leftAngle>-40</leftAngle><rightAngle>40</rightAngle>"
                                                "<upAngle>25</upAngle><downAngle>-25</downAngle></frustum>"
                                              : "";
  const std::string xml = "<?xml version=\"1.0\"?>\n<MPCDI profile=\"" + profile +
                          "\" geometry=\"1\" version=\"2.0\">\n"
                          "<display><buffer id=\"b\" " +
                          resolution +
                          ">\n"
                          "<region id=\"r\" x=\"0\" y=\"0\" xsize=\"1\" ysize=\"1\" " +
                          resolution + ">" + frustum +
                          "</region>\n</buffer></display>\n"
                          "<files><fileset region=\"r\"><geometryWarpFile><path>r.pfm</path>"
                          "<interpolation>linear</interpolation></geometryWarpFile></fileset></files>\n</MPCDI>\n";
  const auto warp = [](int x, int y, int c) {
    return c == 0   ? 0.05f + 0.9f * static_cast<float>(x) / 4.0f
           : c == 1 ? 0.1f + 0.8f * static_cast<float>(y) / 3.0f
                    : 0.0f;
  };
  testing::make_zip(dir, name, {{"mpcdi.xml", xml}, {"r.pfm", testing::make_pfm(5, 4, 3, warp, true, true)}});
}

/// The region's warp at output pixel (x, y) of a w × h output: (x, y) normalized in the region's image.
glm::dvec2 region_point(double x_px, double y_px, int w, int h) {
  // The stored samples are binary32: the sampler uses the same rounded ends.
  const double x0 = 0.05f, x1 = 0.05f + 0.9f, y0 = 0.1f, y1 = 0.1f + 0.8f;
  return {x0 + (x1 - x0) * x_px / w, y0 + (y1 - y0) * y_px / h};
}

TEST(WarpSource, AnMpcdiRegionsResolutionIsTheSourceUnlessTheConfigGivesOne) {
  // A 2d region of 640 × 400 px shown by an 80 × 60 projector through a 180°
  // fisheye source: the source is the region's 16:10 image (the circle of
  // radius 200 px in its middle), not the square fisheye default (60 × 60).
  ScratchDir dir("warp_source_mpcdi");
  region_archive(dir, "show.mpcdi", "2d", 640, 400);
  json j = json::parse(R"({"zenith_viewports": 1, "name": "show", "outputs": [
    {"name": "r", "size": [80, 60], "projection": {"type": "fisheye", "fov_deg": 180},
     "warp": {"file": "show.mpcdi", "format": "mpcdi", "region": "r"}}]})");
  const ViewportConfig region_sized = parse_viewport_config(j, "show.json", dir.path());
  ASSERT_TRUE(region_sized.outputs[0].warp);
  EXPECT_EQ(region_sized.outputs[0].warp->source_width_px, 640);
  EXPECT_EQ(region_sized.outputs[0].warp->source_height_px, 400);
  EXPECT_FALSE(region_sized.outputs[0].warp->source_size_given);
  const auto w = warped_output(region_sized);
  EXPECT_EQ(w->base().width(), 640);
  EXPECT_EQ(w->base().height(), 400);
  const Agreement a = compare_rays(*w, [](double x, double y) {
    const glm::dvec2 p = region_point(x, y, 80, 60);
    return fisheye_ray(640.0 * p.x, 400.0 * p.y, 640.0, 400.0);
  });
  // The circle spans x ∈ [0.1875, 0.8125] of the region, x = 0.05 + 0.9 s:
  // the projector's columns from 12.2 to 67.8 px (at mid height).
  EXPECT_GT(a.compared, 0);
  EXPECT_GT(a.without_ray, 0);
  EXPECT_FALSE(w->ray(11.5, 30.5));
  EXPECT_TRUE(w->ray(12.5, 30.5));
  EXPECT_TRUE(w->ray(67.5, 30.5));
  EXPECT_FALSE(w->ray(68.5, 30.5));

  // The config's "source" wins: the square the fisheye default would give.
  j["outputs"][0]["warp"]["source"] = json{{"size_px", {60, 60}}};
  const ViewportConfig given = parse_viewport_config(j, "show.json", dir.path());
  EXPECT_TRUE(given.outputs[0].warp->source_size_given);
  const auto g = warped_output(given);
  EXPECT_EQ(g->base().width(), 60);
  EXPECT_EQ(g->base().height(), 60);
  const Agreement b = compare_rays(*g, [](double x, double y) {
    const glm::dvec2 p = region_point(x, y, 80, 60);
    return fisheye_ray(60.0 * p.x, 60.0 * p.y, 60.0, 60.0);
  });
  EXPECT_GT(b.compared, a.compared);  // the square's circle covers more of the warp
  j["outputs"][0]["warp"]["source"] = json{{"aspect", 2.0}};
  EXPECT_EQ(warped_output(parse_viewport_config(j, "show.json", dir.path()))->base().width(), 120);

  // The fisheye's pixel keys count in the region's pixels.
  j["outputs"][0]["warp"].erase("source");
  j["outputs"][0]["projection"]["radius_px"] = 150;
  const auto r = warped_output(parse_viewport_config(j, "show.json", dir.path()));
  const Agreement c = compare_rays(*r, [](double x, double y) {
    const glm::dvec2 p = region_point(x, y, 80, 60);
    return fisheye_ray(640.0 * p.x, 400.0 * p.y, 640.0, 400.0, 150.0);
  });
  EXPECT_LT(c.compared, a.compared);

  // A 3d region: its frustum renders the image the region's warp addresses
  // (the config gives no projection), at the region's resolution (its rays do
  // not depend on it; its pixel size does).
  region_archive(dir, "show3d.mpcdi", "3d", 1280, 800);
  json k = json::parse(R"({"zenith_viewports": 1, "name": "show", "outputs": [
    {"name": "r", "size": [80, 60], "warp": {"file": "show3d.mpcdi", "format": "mpcdi", "region": "r"}}]})");
  const ViewportConfig frustum_config = parse_viewport_config(k, "show.json", dir.path());
  const auto f = warped_output(frustum_config);
  EXPECT_EQ(f->base().width(), 1280);
  EXPECT_EQ(f->base().height(), 800);
  EXPECT_EQ(frustum_config.outputs[0].warp->source_width_px, 1280);
  EXPECT_EQ(frustum_config.outputs[0].projection_spec,
            json::parse(R"({"type": "planar", "left_deg": -40, "right_deg": 40, "down_deg": -25, "up_deg": 25,
                            "yaw_deg": 0, "pitch_deg": 0, "roll_deg": 0})"));
  const double t_lr = std::tan(40.0 * zenith::core::kDeg), t_ud = std::tan(25.0 * zenith::core::kDeg);
  compare_rays(*f, [&](double x, double y) -> std::optional<glm::dvec3> {
    const glm::dvec2 p = region_point(x, y, 80, 60);
    return glm::normalize(glm::dvec3(-t_lr + 2.0 * t_lr * p.x, t_ud - 2.0 * t_ud * p.y, -1.0));
  });
}

}  // namespace
}  // namespace zenith::warp
