// MPCDI's 3d, sl and a3 profiles: archives written here by
// generators (nothing downloaded) whose regions define their rays by a frustum,
// a frustum and a coordinate frame, or a 3D geometry warp of screen points,
// loaded through a viewport config and compared with independent computations:
// the same frustum as a JSON planar output, the standard's rotations written
// out from VESA MPCDI v2.0 §2.2 (not zenith's), and the fisheye a sphere's 3D
// warp was made from. Then the refusals, each naming the file, the region and
// the element.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>

#include "core/units.h"
#include "tests/warp/mpcdi_test_support.h"
#include "tests/warp/projection_test_support.h"
#include "tests/warp/warp_file_test_support.h"
#include "warp/fisheye_projection.h"
#include "warp/mpcdi.h"
#include "warp/mpcdi_projection.h"
#include "warp/planar_projection.h"
#include "warp/viewport_config.h"
#include "warp/warped_projection.h"

namespace zenith::warp {
namespace {

using core::kDeg;
using nlohmann::json;
using testing::angle_between;
using testing::expect_config_error;
using testing::expect_error;
using testing::make_grey_png;
using testing::make_pfm;
using testing::make_zip;
using testing::Members;
using testing::ScratchDir;

// ---- generators ---------------------------------------------------------------

std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

struct Frustum {
  double yaw = 0, pitch = 0, roll = 0, left = -30, right = 30, up = 20, down = -20;
};

PlanarFrustum planar_of(const Frustum& f) { return {f.left, f.right, f.down, f.up, f.yaw, f.pitch, f.roll}; }

/// The same frustum as a viewport config's "projection" object (a planar output).
json planar_projection(const Frustum& f) {
  return {{"type", "planar"}, {"left_deg", f.left}, {"right_deg", f.right}, {"down_deg", f.down},
          {"up_deg", f.up},   {"yaw_deg", f.yaw},   {"pitch_deg", f.pitch}, {"roll_deg", f.roll}};
}

std::string frustum_xml(const Frustum& f) {
  return "<frustum><yaw>" + num(f.yaw) + "</yaw><pitch>" + num(f.pitch) + "</pitch><roll>" + num(f.roll) +
         "</roll><rightAngle>" + num(f.right) + "</rightAngle><leftAngle>" + num(f.left) + "</leftAngle><upAngle>" +
         num(f.up) + "</upAngle><downAngle>" + num(f.down) + "</downAngle></frustum>\n";
}

/// A <coordinateFrame>: the projector's position and its yaw (down), pitch
/// (right) and roll (forward) unit vectors in the display's frame.
struct Frame {
  glm::dvec3 position{0.0}, yaw{0.0, -1.0, 0.0}, pitch{-1.0, 0.0, 0.0}, roll{0.0, 0.0, 1.0};
};

std::string frame_xml(const Frame& f) {
  std::string xml = "<coordinateFrame>";
  const auto vec = [&](const char* stem, const glm::dvec3& v) {
    for (int k = 0; k < 3; ++k) {
      const std::string tag = std::string(stem) + "xyz"[k];
      xml += "<" + tag + ">" + num(v[k]) + "</" + tag + ">";
    }
  };
  vec("pos", f.position);
  vec("yaw", f.yaw);
  vec("pitch", f.pitch);
  vec("roll", f.roll);
  return xml + "</coordinateFrame>\n";
}

/// mpcdi.xml of one buffer with one region "p1" of xres × yres px;
/// `region_inner` goes inside <region>, `fileset_inner` inside its fileset.
std::string descriptor(const std::string& profile, const std::string& region_inner, const std::string& fileset_inner,
                       int xres = 64, int yres = 48) {
  const std::string res = "xResolution=\"" + std::to_string(xres) + "\" yResolution=\"" + std::to_string(yres) + "\"";
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<MPCDI profile=\"" + profile +
         "\" geometry=\"2\" color=\"3\" version=\"2.0\">\n<display>\n<buffer id=\"b\" " + res +
         ">\n<region id=\"p1\" x=\"0\" y=\"0\" xsize=\"1\" ysize=\"1\" " + res + ">\n" + region_inner +
         "<color><decode type=\"gamma\" gamma=\"2.2\"></decode><encode type=\"gamma\" gamma=\"2.2\"></encode></color>\n"
         "</region>\n</buffer>\n</display>\n<files>\n<fileset region=\"p1\">\n" +
         fileset_inner + "</fileset>\n</files>\n</MPCDI>\n";
}

const char* const kAlphaBeta =
    "<alphaMap><path>alpha.png</path><componentDepth>1</componentDepth><bitDepth>8</bitDepth>"
    "<gammaEmbedded>2.2</gammaEmbedded></alphaMap>\n"
    "<betaMap><path>beta.png</path><componentDepth>1</componentDepth><bitDepth>8</bitDepth></betaMap>\n";

/// The archive: mpcdi.xml plus 4 × 3 alpha and beta maps and `extra` members.
std::filesystem::path archive(const ScratchDir& dir, const std::string& name, const std::string& xml,
                              Members extra = {}) {
  Members members = {{"mpcdi.xml", xml},
                     {"alpha.png", make_grey_png(4, 3, testing::kAlpha)},
                     {"beta.png", make_grey_png(4, 3, std::vector<unsigned char>(12, 9))}};
  for (auto& m : extra) members.push_back(std::move(m));
  return make_zip(dir, name, members);
}

/// A viewport config of one output "o" of w × h px.
ViewportConfig viewport(const ScratchDir& dir, const json& output_keys, int w = 64, int h = 48) {
  json output = output_keys;
  output["name"] = "o";
  output["size"] = {w, h};
  return parse_viewport_config(json{{"zenith_viewports", 1}, {"name", "t"}, {"outputs", json::array({output})}},
                               "t.json", dir.path());
}

json mpcdi_warp(const std::string& file, const json& extra = json::object()) {
  json warp = {{"file", file}, {"format", "mpcdi"}, {"region", "p1"}};
  warp.update(extra);
  return {{"warp", warp}};
}

/// The largest angle between the rays of two projections at every pixel
/// centre; both must have a ray at each.
double max_ray_angle(const Projection& a, const Projection& b) {
  double worst = 0.0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const auto ra = a.ray(x + 0.5, y + 0.5), rb = b.ray(x + 0.5, y + 0.5);
      EXPECT_TRUE(ra && rb) << x << ", " << y;
      if (ra && rb) worst = std::max(worst, angle_between(*ra, *rb));
    }
  return worst;
}

// ---- the standard's rotations, written out independently ----------------------

// Right-handed turns about the axes of the viewer frame S (X right, Y down,
// Z forward), glm's column-major constructor (columns listed).
glm::dmat3 rot_x(double a) { return glm::dmat3(1, 0, 0, 0, std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a)); }
glm::dmat3 rot_y(double a) { return glm::dmat3(std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a)); }
glm::dmat3 rot_z(double a) { return glm::dmat3(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1); }

/// VESA MPCDI v2.0 §2.2: the ray of pixel position (x, y) of a w × h image of
/// frustum `f` held in frame `frame`, in zenith's camera frame: the tangents in
/// S (y down), turned by yaw (about Y), then pitch (about X), then roll (about
/// Z) in the frame's axes B = [pitch | yaw | roll], then from the display's
/// frame (X left, Y up, Z forward) to the camera's (x right, y up, −z forward).
glm::dvec3 standard_ray(const Frustum& f, const Frame& frame, double x, double y, int w, int h) {
  const double tl = std::tan(f.left * kDeg), tr = std::tan(f.right * kDeg);
  const double tu = std::tan(f.up * kDeg), td = std::tan(f.down * kDeg);
  const glm::dvec3 s(tl + x / w * (tr - tl), -(tu + y / h * (td - tu)), 1.0);
  const glm::dmat3 b(frame.pitch, frame.yaw, frame.roll);
  const glm::dvec3 world = b * (rot_y(f.yaw * kDeg) * (rot_x(f.pitch * kDeg) * (rot_z(f.roll * kDeg) * s)));
  return glm::normalize(glm::dvec3(-world.x, world.y, -world.z));
}

// ---- frusta --------------------------------------------------------------------

TEST(MpcdiProfiles, AFrustumRegionHasTheRaysOfTheSameFrustumAsAJsonPlanarOutput) {
  ScratchDir dir("mpcdi_frustum_json");
  const Frustum f{326.7, 12.5, 350.0, -35.0, 28.0, 22.0, -18.0};
  archive(dir, "3d.mpcdi", descriptor("3d", frustum_xml(f), kAlphaBeta));
  archive(dir, "sl.mpcdi", descriptor("sl", frustum_xml(f) + frame_xml(Frame{}), kAlphaBeta));
  const json planar = {{"projection", planar_projection(f)}};
  const ViewportConfig json_planar = viewport(dir, planar);
  const ViewportConfig three_d = viewport(dir, mpcdi_warp("3d.mpcdi"));
  const ViewportConfig shader_lamp = viewport(dir, mpcdi_warp("sl.mpcdi"));
  ASSERT_NE(dynamic_cast<const PlanarProjection*>(three_d.outputs[0].projection.get()), nullptr);
  ASSERT_NE(dynamic_cast<const PlanarProjection*>(shader_lamp.outputs[0].projection.get()), nullptr);
  const double d3 = max_ray_angle(*three_d.outputs[0].projection, *json_planar.outputs[0].projection);
  const double dsl = max_ray_angle(*shader_lamp.outputs[0].projection, *json_planar.outputs[0].projection);
  std::printf("  3d region vs JSON planar: %.3g rad; sl region (the base frame) vs JSON planar: %.3g rad\n", d3, dsl);
  EXPECT_LT(d3, 1e-9);
  EXPECT_LT(dsl, 1e-9);
  // The standard's own arithmetic agrees as well.
  double worst = 0.0;
  for (int y = 0; y < 48; y += 5)
    for (int x = 0; x < 64; x += 5)
      worst = std::max(worst, angle_between(*three_d.outputs[0].projection->ray(x + 0.5, y + 0.5),
                                            standard_ray(f, Frame{}, x + 0.5, y + 0.5, 64, 48)));
  EXPECT_LT(worst, 1e-12);
  // The exported configs' "projection" of the region: the same frustum.
  EXPECT_EQ(three_d.outputs[0].projection_spec["type"], "planar");
  EXPECT_NEAR(three_d.outputs[0].projection_spec["yaw_deg"].get<double>(), 326.7 - 360.0, 1e-12);
}

/// A projector aimed at the zenith, as exports of a Z-forward, Y-up display
/// write it: it looks up (roll = the display's +Y), its right is the
/// display's −Z (backward), its down −X (right, X being left); and a frustum
/// turned in that frame by yaw 20, pitch −15, roll 30.
Frame zenith_frame() {
  Frame frame;
  frame.position = {1.5, -2.0, 3.0};
  frame.pitch = {0.0, 0.0, -1.0};
  frame.yaw = {-1.0, 0.0, 0.0};
  frame.roll = {0.0, 1.0, 0.0};
  return frame;
}
constexpr Frustum kZenithFrustum{20.0, -15.0, 30.0, -25.0, 35.0, 15.0, -20.0};

TEST(MpcdiProfiles, AFrameWithSwappedAndNegatedAxesLandsWhereTheStandardPutsIt) {
  ScratchDir dir("mpcdi_frame");
  const Frustum f = kZenithFrustum;
  const Frame frame = zenith_frame();
  archive(dir, "sl.mpcdi", descriptor("sl", frustum_xml(f) + frame_xml(frame), kAlphaBeta));
  const ViewportConfig config = viewport(dir, mpcdi_warp("sl.mpcdi"));
  const Projection& p = *config.outputs[0].projection;
  double worst = 0.0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      worst =
          std::max(worst, angle_between(*p.ray(x + 0.5, y + 0.5), standard_ray(f, frame, x + 0.5, y + 0.5, 64, 48)));
  std::printf("  swapped and negated frame: max %.3g rad from the standard's rotations\n", worst);
  EXPECT_LT(worst, 1e-12);

  // Unturned in that frame, the image's centre looks up and its top edge
  // toward the display's +X, the camera's left: landmarks of the frame alone.
  const Frustum straight{0.0, 0.0, 0.0, -30.0, 30.0, 20.0, -20.0};
  archive(dir, "up.mpcdi", descriptor("sl", frustum_xml(straight) + frame_xml(frame), ""));
  const auto up = viewport(dir, mpcdi_warp("up.mpcdi")).outputs[0].projection;
  EXPECT_LT(angle_between(*up->ray(32.0, 24.0), {0.0, 1.0, 0.0}), 1e-12);
  const glm::dvec3 top = *up->ray(32.0, 0.0);
  EXPECT_LT(angle_between(top, {-std::sin(20.0 * kDeg), std::cos(20.0 * kDeg), 0.0}), 1e-12);

  // The worked example of docs/warp-meshes.md: in that frame a frustum
  // pitched −60° looks 30° above the horizon to the right, its top up and
  // left: yaw 90°, pitch 30°, roll 0°. With yaw 20, pitch −15, roll 30 the
  // composition is yaw 141.92374937322128°, pitch 65.18578309540773°, roll
  // 84.58338724440884°, as a separate computation of W · B · Ry · Rx · Rz · C
  // (a few lines of Python, plain lists) gives.
  MpcdiRegion up_region;
  up_region.coordinate_frame = MpcdiCoordinateFrame{frame.position, frame.yaw, frame.pitch, frame.roll, 0};
  up_region.frustum = MpcdiFrustum{0.0, -60.0, 0.0, -30.0, 30.0, 20.0, -20.0, 0};
  PlanarFrustum composed = mpcdi_planar_frustum(up_region);
  EXPECT_NEAR(composed.yaw_deg, 90.0, 1e-12);
  EXPECT_NEAR(composed.pitch_deg, 30.0, 1e-12);
  EXPECT_NEAR(composed.roll_deg, 0.0, 1e-12);
  up_region.frustum = MpcdiFrustum{20.0, -15.0, 30.0, -30.0, 30.0, 20.0, -20.0, 0};
  composed = mpcdi_planar_frustum(up_region);
  EXPECT_NEAR(composed.yaw_deg, 141.92374937322128, 1e-11);
  EXPECT_NEAR(composed.pitch_deg, 65.18578309540773, 1e-11);
  EXPECT_NEAR(composed.roll_deg, 84.58338724440884, 1e-11);

  // The frame's turn alone is a yaw of −90° for a frame looking left; the
  // frustum's own yaw adds.
  Frame left;
  left.pitch = {0.0, 0.0, 1.0};
  left.yaw = {0.0, -1.0, 0.0};
  left.roll = {1.0, 0.0, 0.0};
  MpcdiRegion region;
  region.frustum = MpcdiFrustum{30.0, 10.0, 5.0, -30.0, 30.0, 20.0, -20.0, 0};
  region.coordinate_frame = MpcdiCoordinateFrame{left.position, left.yaw, left.pitch, left.roll, 0};
  composed = mpcdi_planar_frustum(region);
  EXPECT_NEAR(composed.yaw_deg, -60.0, 1e-12);
  EXPECT_NEAR(composed.pitch_deg, 10.0, 1e-12);
  EXPECT_NEAR(composed.roll_deg, 5.0, 1e-12);
}

TEST(MpcdiProfiles, YawPitchRollOfARotationInvertsPlanarFrustum) {
  for (const double pitch : {-90.0, -89.999, -45.0, 0.0, 12.5, 89.9999, 90.0})
    for (const double yaw : {-179.0, -90.0, 0.0, 33.3, 180.0})
      for (const double roll : {-135.0, 0.0, 7.0, 180.0}) {
        const glm::dmat3 r = PlanarProjection(1, 1, PlanarFrustum{-1, 1, -1, 1, yaw, pitch, roll}).rotation();
        const YawPitchRollDeg back = yaw_pitch_roll_of(r);
        const glm::dmat3 again =
            PlanarProjection(1, 1, PlanarFrustum{-1, 1, -1, 1, back.yaw_deg, back.pitch_deg, back.roll_deg}).rotation();
        for (int c = 0; c < 3; ++c)
          EXPECT_LT(glm::length(again[c] - r[c]), 1e-13) << yaw << " " << pitch << " " << roll;
        if (std::abs(pitch) < 89.0) {
          EXPECT_NEAR(back.pitch_deg, pitch, 1e-11);
          EXPECT_NEAR(std::remainder(back.yaw_deg - yaw, 360.0), 0.0, 1e-11);
          EXPECT_NEAR(std::remainder(back.roll_deg - roll, 360.0), 0.0, 1e-11);
        }
      }
}

TEST(MpcdiProfiles, A2dWarpOfA3dRegionAndAnSlDistortionMapWarpTheFrustumsImage) {
  // The same 5 × 4 warp as a 3d region's geometry warp, an sl region's lens
  // distortion map, and a plain PFM over the same frustum in JSON.
  ScratchDir dir("mpcdi_frustum_warp");
  const Frustum f{10.0, -5.0, 2.0, -40.0, 40.0, 25.0, -25.0};
  const auto warp = [](int x, int y, int c) {
    return c == 0   ? 0.05f + 0.22f * static_cast<float>(x) + 0.01f * static_cast<float>(y)
           : c == 1 ? 0.1f + 0.27f * static_cast<float>(y) - 0.02f * static_cast<float>(x)
                    : 0.0f;
  };
  const std::string pfm = make_pfm(5, 4, 3, warp, true, true);
  archive(dir, "3d.mpcdi",
          descriptor("3d", frustum_xml(f), "<geometryWarpFile><path>w.pfm</path></geometryWarpFile>\n", 320, 200),
          {{"w.pfm", pfm}});
  archive(dir, "sl.mpcdi",
          descriptor("sl", frustum_xml(f) + frame_xml(Frame{}), "<distortionMap><path>w.pfm</path></distortionMap>\n",
                     320, 200),
          {{"w.pfm", pfm}});
  dir.write("w.pfm", pfm);
  const json plain = {
      {"projection", planar_projection(f)},
      {"warp",
       {{"file", "w.pfm"}, {"format", "pfm"}, {"row_order", "top_to_bottom"}, {"source", {{"size_px", {320, 200}}}}}}};
  ViewportConfig reference = viewport(dir, plain, 40, 30);
  const auto* ref = dynamic_cast<const WarpedProjection*>(reference.outputs[0].projection.get());
  ASSERT_NE(ref, nullptr);
  // The plain PFM is read with Catmull–Rom; MPCDI's default is linear: compare at the nodes' cells' bilinear.
  WarpedProjection bilinear_ref(
      40, 30,
      WarpMesh(ref->mesh().columns(), ref->mesh().rows(), ref->mesh().nodes(), "ref", WarpInterpolation::bilinear),
      std::make_shared<PlanarProjection>(320, 200, planar_of(f)));
  for (const char* file : {"3d.mpcdi", "sl.mpcdi"}) {
    const ViewportConfig c = viewport(dir, mpcdi_warp(file), 40, 30);
    const auto* w = dynamic_cast<const WarpedProjection*>(c.outputs[0].projection.get());
    ASSERT_NE(w, nullptr) << file;
    EXPECT_EQ(w->base().width(), 320);
    EXPECT_EQ(w->base().height(), 200);
    EXPECT_LT(max_ray_angle(*w, bilinear_ref), 1e-9) << file;
  }
}

// ---- 3D geometry warps -----------------------------------------------------------

/// The screen point a ray from `eye` (display frame) meets on the sphere of
/// radius `radius` around `centre`, the eye inside it.
glm::dvec3 on_sphere(const glm::dvec3& eye, const glm::dvec3& direction, const glm::dvec3& centre, double radius) {
  const glm::dvec3 d = glm::normalize(direction), o = eye - centre;
  const double b = glm::dot(o, d), c = glm::dot(o, o) - radius * radius;
  return eye + (-b + std::sqrt(b * b - c)) * d;
}

TEST(MpcdiProfiles, A3dWarpOfASphereGivesTheRaysOfTheFisheyeItWasMadeFrom) {
  // A dome (a sphere of radius 8 m) and an eye off its centre; a 48 × 36
  // projector showing what a tilted 200° fisheye sees. The warp has a sample
  // at every pixel centre and corner ((2W + 1) × (2H + 1)): the screen point
  // the fisheye's ray meets, in the display's frame (camera → display:
  // diag(−1, 1, −1)); NaN outside the fisheye's circle.
  constexpr int kW = 48, kH = 36;
  const FisheyeProjection fisheye(kW, kH, {.fov_deg = 200.0, .tilt_deg = 20.0, .rotation_deg = 15.0});
  const glm::dvec3 centre(0.3, -0.2, 0.5), eye(0.1, 1.2, -0.4);
  const auto sample = [&](const glm::dvec3& origin, int i, int j, int c) {
    const auto ray = fisheye.ray(0.5 * i, 0.5 * j);
    if (!ray) return std::numeric_limits<float>::quiet_NaN();
    const glm::dvec3 p = on_sphere(eye, {-ray->x, ray->y, -ray->z}, centre, 8.0) - origin;
    return static_cast<float>(p[c]);
  };
  const auto xml = [](const std::string& profile, const std::string& origin, const std::string& region) {
    return descriptor(profile, region,
                      "<geometryWarpFile><path>dome.pfm</path><interpolation>linear</interpolation>"
                      "<geometricUnit>m</geometricUnit><originOf3DData>" +
                          origin + "</originOf3DData></geometryWarpFile>\n" + kAlphaBeta,
                      kW, kH);
  };
  ScratchDir dir("mpcdi_sphere");
  // a3: the data's origin is the floor's centre; the config gives the eye.
  archive(dir, "a3.mpcdi", xml("a3", "floorCenter", ""),
          {{"dome.pfm", make_pfm(
                            2 * kW + 1, 2 * kH + 1, 3,
                            [&](int i, int j, int c) { return sample(glm::dvec3(0.0), i, j, c); }, true, true)}});
  // a3 again with the eye as the origin (no "eye" needed), and sl (the 3D
  // warp, not the projector's frustum, gives the audience's rays).
  const Members at_eye = {{"dome.pfm", make_pfm(
                                           2 * kW + 1, 2 * kH + 1, 3,
                                           [&](int i, int j, int c) { return sample(eye, i, j, c); }, true, true)}};
  archive(dir, "a3-eye.mpcdi", xml("a3", "idealEyePoint", ""), at_eye);
  archive(dir, "sl.mpcdi", xml("sl", "centerOfMass", frustum_xml(Frustum{}) + frame_xml(Frame{})),
          {{"dome.pfm", make_pfm(
                            2 * kW + 1, 2 * kH + 1, 3,
                            [&](int i, int j, int c) { return sample(glm::dvec3(0.0), i, j, c); }, true, true)}});
  const json eye_json = {eye.x, eye.y, eye.z};
  const std::vector<std::pair<std::string, ViewportConfig>> configs = {
      {"a3, eye given", viewport(dir, mpcdi_warp("a3.mpcdi", {{"eye", eye_json}}), kW, kH)},
      {"a3, idealEyePoint", viewport(dir, mpcdi_warp("a3-eye.mpcdi"), kW, kH)},
      {"sl, eye given", viewport(dir, mpcdi_warp("sl.mpcdi", {{"eye", eye_json}}), kW, kH)}};
  for (const auto& [what, config] : configs) {
    const Projection& p = *config.outputs[0].projection;
    ASSERT_NE(dynamic_cast<const WarpedProjection*>(&p), nullptr) << what;
    // binary32 points ~8 m from the eye: each coordinate within 2^-24 · 9 m,
    // the ray within about √3 · 5.4e-7 m / 6.5 m = 1.4e-7 rad.
    double worst = 0.0;
    int compared = 0, rim = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const auto got = p.ray(x + 0.5, y + 0.5), want = fisheye.ray(x + 0.5, y + 0.5);
        if (got) {
          ASSERT_TRUE(want) << what << " " << x << ", " << y;
          worst = std::max(worst, angle_between(*got, *want));
          ++compared;
        } else if (want) {
          // Only at the circle's rim: a corner of the pixel lies outside it, so
          // the warp's cells around the centre have a NaN corner.
          bool corner_outside = false;
          for (const double dx : {0.0, 1.0})
            for (const double dy : {0.0, 1.0}) corner_outside |= !fisheye.ray(x + dx, y + dy);
          EXPECT_TRUE(corner_outside) << what << " " << x << ", " << y;
          ++rim;
        }
      }
    std::printf("  %-18s %d pixel centres, max %.3g rad from the fisheye; %d at the rim without a ray\n", what.c_str(),
                compared, worst, rim);
    EXPECT_GT(compared, kW * kH / 2);
    EXPECT_LT(worst, 3e-7) << what;
  }
  // The alpha and beta maps and their encoding load as for a 2d region.
  const MpcdiFile file = load_mpcdi(dir.path() / "sl.mpcdi");
  const MpcdiRegion& region = *file.find_region("p1");
  ASSERT_TRUE(region.alpha_map && region.beta_map);
  EXPECT_EQ(region.alpha_map->gamma_embedded, 2.2);
  EXPECT_NEAR(region.alpha_map->linear(1, 0), std::pow(64.0 / 255.0, 2.2), 1e-7);
  EXPECT_NEAR(region.beta_map->linear(3, 2), 9.0 / 255.0, 1e-7);
  EXPECT_EQ(region.geometry_warp->geometric_unit, "m");
  EXPECT_EQ(region.geometry_warp->origin_of_3d_data, "centerOfMass");
  EXPECT_TRUE(region.geometry_warp->points_3d);
}

TEST(MpcdiProfiles, AnSlRegionsEyeAtItsProjectorGivesThePinholesRays) {
  // An sl region's 3D warp of a sphere lit through its own frustum and frame;
  // with the eye at the frame's position the warp's rays are the pinhole's.
  constexpr int kW = 40, kH = 30;
  const Frustum f = kZenithFrustum;
  const Frame frame = zenith_frame();
  const auto point = [&](int i, int j, int c) {
    const glm::dvec3 cam = standard_ray(f, frame, 0.5 * i, 0.5 * j, kW, kH);
    return static_cast<float>(on_sphere(frame.position, {-cam.x, cam.y, -cam.z}, {0.0, 0.0, 0.0}, 10.0)[c]);
  };
  ScratchDir dir("mpcdi_sl_eye");
  archive(dir, "pinhole.mpcdi", descriptor("sl", frustum_xml(f) + frame_xml(frame), "", kW, kH));
  archive(dir, "screen.mpcdi",
          descriptor("sl", frustum_xml(f) + frame_xml(frame),
                     "<geometryWarpFile><path>s.pfm</path><geometricUnit>m</geometricUnit>"
                     "<originOf3DData>centerOfMass</originOf3DData></geometryWarpFile>\n",
                     kW, kH),
          {{"s.pfm", make_pfm(2 * kW + 1, 2 * kH + 1, 3, point, true, true)}});
  const auto pinhole = viewport(dir, mpcdi_warp("pinhole.mpcdi"), kW, kH).outputs[0].projection;
  const auto screen =
      viewport(dir, mpcdi_warp("screen.mpcdi", {{"eye", {1.5, -2.0, 3.0}}}), kW, kH).outputs[0].projection;
  const double worst = max_ray_angle(*screen, *pinhole);
  std::printf("  sl 3D warp seen from the projector vs its pinhole: max %.3g rad\n", worst);
  EXPECT_LT(worst, 3e-7);  // binary32 points ~10 m away
}

// ---- refusals --------------------------------------------------------------------

TEST(MpcdiProfiles, EveryRefusalNamesTheFileTheRegionAndTheElement) {
  ScratchDir dir("mpcdi_refusals");
  const Frustum f;
  const auto load = [&](const std::string& name, const std::string& xml, Members extra = {}) {
    return [&dir, name, xml, extra] { load_mpcdi(archive(dir, name, xml, extra)); };
  };
  expect_error(load("a.mpcdi", descriptor("sl", frustum_xml(f), "")),
               {"a.mpcdi:mpcdi.xml:5:", "'p1'", "<coordinateFrame>", "required by the sl profile"});
  expect_error(load("b.mpcdi", descriptor("sl", frame_xml(Frame{}), "")),
               {"b.mpcdi:mpcdi.xml:5:", "'p1'", "has no <frustum> (required by the sl profile)"});
  std::string partial = frame_xml(Frame{});
  partial.erase(partial.find("<rollz>"), std::string("<rollz>1</rollz>").size());
  expect_error(load("c.mpcdi", descriptor("sl", frustum_xml(f) + partial, "")),
               {"c.mpcdi:mpcdi.xml:7:", "region 'p1': <coordinateFrame> has no <rollz>"});
  Frame stretched;
  stretched.yaw = {0.0, -2.0, 0.0};
  expect_error(load("d.mpcdi", descriptor("sl", frustum_xml(f) + frame_xml(stretched), "")),
               {"d.mpcdi:mpcdi.xml:7:", "region 'p1': <coordinateFrame> <yawx>..<yawz> = (0, -2, 0) has length 2"});
  Frame skew;
  skew.yaw = glm::normalize(glm::dvec3(0.1, -1.0, 0.0));
  expect_error(load("e.mpcdi", descriptor("3d", frustum_xml(f) + frame_xml(skew), "")),
               {"e.mpcdi:mpcdi.xml:7:", "region 'p1': <coordinateFrame>", "not orthogonal"});
  Frame mirrored;
  mirrored.pitch = {1.0, 0.0, 0.0};
  expect_error(load("f.mpcdi", descriptor("sl", frustum_xml(f) + frame_xml(mirrored), "")),
               {"f.mpcdi:mpcdi.xml:7:", "region 'p1': <coordinateFrame>", "left-handed"});
  expect_error(load("g.mpcdi", descriptor("3d", frustum_xml(Frustum{0, 0, 0, 30, 10, 20, -20}), "")),
               {"g.mpcdi:mpcdi.xml:6:", "region 'p1': <frustum> <leftAngle> = 30 must be less than <rightAngle> = 10"});
  expect_error(load("h.mpcdi", descriptor("3d", frustum_xml(Frustum{0, 0, 0, -30, 30, 95, -20}), "")),
               {"h.mpcdi:mpcdi.xml:6:", "region 'p1': <frustum> <upAngle> = 95: must be in (-90, 90) degrees"});
  expect_error(load("i.mpcdi",
                    descriptor("a3", "",
                               "<geometryWarpFile><path>s.pfm</path><geometricUnit>furlong"
                               "</geometricUnit></geometryWarpFile>\n"),
                    {{"s.pfm", make_pfm(
                                   2, 2, 3, [](int, int, int) { return 1.0f; }, true, true)}}),
               {"i.mpcdi:mpcdi.xml:", "region 'p1': <geometricUnit> 'furlong': must be one of mm, cm, dm, m, in, ft"});
  expect_error(load("j.mpcdi", descriptor("a3", "", "<geometryWarpFile><path>s.pfm</path></geometryWarpFile>\n"),
                    {{"s.pfm", make_pfm(
                                   3, 2, 3, [](int, int, int) { return std::nanf(""); }, true, true)}}),
               {"j.mpcdi:mpcdi.xml:", "region 'p1': 3D geometry warp 's.pfm' has no valid point"});
  expect_error(load("k.mpcdi", descriptor("sl", frustum_xml(f) + frame_xml(Frame{}),
                                          "<distortionMap><path>lens.pfm</path></distortionMap>\n")),
               {"k.mpcdi:mpcdi.xml:", "region 'p1': distortion map 'lens.pfm' is not in the archive"});
  expect_error(load("l.mpcdi", descriptor("3d", frustum_xml(Frustum{400, 0, 0}), "")),
               {"l.mpcdi:mpcdi.xml:", "region 'p1': <frustum> <yaw> = 400: must be in [-360, 360] degrees"});

  // Through a viewport config: the pointer, then the file, region and element.
  const Members points = {
      {"s.pfm",
       make_pfm(
           3, 2, 3, [](int x, int y, int c) { return c == 2 ? 5.0f : static_cast<float>(x + y) - 1.0f; }, true, true)}};
  archive(dir, "floor.mpcdi",
          descriptor("a3", "",
                     "<geometryWarpFile><path>s.pfm</path><originOf3DData>floorCenter</originOf3DData>"
                     "</geometryWarpFile>\n"),
          points);
  expect_config_error([&] { viewport(dir, mpcdi_warp("floor.mpcdi")); }, "t.json", "/outputs/0/warp/file",
                      "floor.mpcdi:mpcdi.xml:12: region 'p1': <geometryWarpFile> 's.pfm' holds 3D points of the screen "
                      "with <originOf3DData> floorCenter, not idealEyePoint: give the eye");
  archive(dir, "none.mpcdi", descriptor("a3", "", ""));
  expect_config_error([&] { viewport(dir, mpcdi_warp("none.mpcdi")); }, "t.json", "/outputs/0/warp/file",
                      "none.mpcdi:mpcdi.xml:5: region 'p1': profile a3: the region has no 3D geometry warp");
  archive(dir, "wide.mpcdi", descriptor("3d", frustum_xml(Frustum{0, 0, 0, -89.5, 30, 20, -20}), ""));
  expect_config_error([&] { viewport(dir, mpcdi_warp("wide.mpcdi")); }, "t.json", "/outputs/0/warp/file",
                      "wide.mpcdi:mpcdi.xml:6: region 'p1': <frustum>: PlanarProjection: left_deg = -89.5");
  archive(dir, "plain.mpcdi", descriptor("3d", frustum_xml(f), ""));
  json with_projection = mpcdi_warp("plain.mpcdi");
  with_projection["projection"] = {{"type", "planar"}, {"fov_deg", 60}};
  expect_config_error([&] { viewport(dir, with_projection); }, "t.json", "/outputs/0/projection",
                      "the MPCDI region \"p1\" (profile 3d) defines the output's rays");
  expect_config_error(
      [&] {
        viewport(dir, mpcdi_warp("plain.mpcdi", {{"eye", {0, 0, 0}}}));
      },
      "t.json", "/outputs/0/warp/eye", "applies to a region with a 3D geometry warp");
  expect_config_error(
      [&] {
        viewport(dir, mpcdi_warp("floor.mpcdi", {{"eye", {0, "up", 0}}}));
      },
      "t.json", "/outputs/0/warp/eye", "must be [x, y, z], finite numbers");
  // Only an MPCDI warp may go without a projection (a format of the wrong type included).
  expect_config_error(
      [&] {
        viewport(dir, json{{"warp", {{"file", "plain.mpcdi"}, {"format", 3}}}});
      },
      "t.json", "/outputs/0/projection", "missing required key");
  // A 2d region still needs the projection its warp addresses.
  Members two_d = testing::valid_2d_members();
  make_zip(dir, "2d.mpcdi", two_d);
  json no_projection = mpcdi_warp("2d.mpcdi");
  no_projection["warp"]["region"] = "left";
  expect_config_error([&] { viewport(dir, no_projection); }, "t.json", "/outputs/0/projection",
                      "missing: the MPCDI region \"left\" (profile 2d) maps the output into a source image");
}

}  // namespace
}  // namespace zenith::warp
