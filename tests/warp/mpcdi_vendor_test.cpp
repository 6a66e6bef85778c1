// MPCDI as vendors write it (warp/mpcdi.h): descriptors not named mpcdi.xml,
// empty elements, E&S offset warps, frustum angles in [0, 360), and archives
// that are not what they should be (no descriptor, truncated). Every archive is
// written here (tests/warp/mpcdi_test_support.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/units.h"
#include "tests/warp/mpcdi_test_support.h"
#include "tests/warp/warp_file_test_support.h"
#include "warp/fisheye_projection.h"
#include "warp/mpcdi.h"
#include "warp/planar_projection.h"
#include "warp/viewport_config.h"

namespace zenith::warp {
namespace {

using nlohmann::json;
using testing::expect_error;
using testing::kXml2d;
using testing::LogCapture;
using testing::make_pfm;
using testing::make_zip;
using testing::Members;
using testing::ScratchDir;
using testing::valid_2d_members;

/// kXml2d with `from` replaced by `to`.
std::string xml_with(const std::string& from, const std::string& to, std::string xml = kXml2d) {
  const std::size_t at = xml.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return xml.replace(at, from.size(), to);
}

/// The 1-based line of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

Members with_descriptor(const std::string& name, const std::string& xml = kXml2d) {
  Members members = valid_2d_members();
  members[0] = {name, xml};
  return members;
}

// ---- the descriptor ------------------------------------------------------------

TEST(MpcdiVendor, ReadsMpacsXmlAndASingleOtherXmlMember) {
  ScratchDir dir("mpcdi_descriptor");
  const MpcdiFile mpacs = load_mpcdi(make_zip(dir, "mpacs.mpcdi", with_descriptor("mpacs.xml")));
  EXPECT_EQ(mpacs.descriptor, "mpacs.xml");
  ASSERT_NE(mpacs.find_region("left"), nullptr);
  EXPECT_TRUE(mpacs.find_region("left")->warp_mesh);

  // Older E&S exports name the descriptor after the show.
  const MpcdiFile es = load_mpcdi(make_zip(dir, "es.mpcdi", with_descriptor("Dome Show 2019.XML")));
  EXPECT_EQ(es.descriptor, "Dome Show 2019.XML");
  EXPECT_EQ(es.buffers[0].regions.size(), 2u);
  EXPECT_NEAR(es.find_region("right")->warp_mesh->sample(1.0, 1.0)->u, 0.85, 1e-6);

  // mpcdi.xml wins over anything else; archiver debris does not count as a second XML.
  Members both = with_descriptor("show.xml");
  both.push_back({"mpcdi.xml", kXml2d});
  both.push_back({"__MACOSX/._show.xml", "resource fork"});
  EXPECT_EQ(load_mpcdi(make_zip(dir, "both.mpcdi", both)).descriptor, "mpcdi.xml");
  Members debris = with_descriptor("show.xml");
  debris.push_back({"__MACOSX/._show.xml", "resource fork"});
  EXPECT_EQ(load_mpcdi(make_zip(dir, "debris.mpcdi", debris)).descriptor, "show.xml");
}

TEST(MpcdiVendor, NoDescriptorNamesTheMembers) {
  ScratchDir dir("mpcdi_members");
  expect_error(
      [&] {
        load_mpcdi(make_zip(dir, "none.mpcdi", {{"readme.txt", "x"}, {"warps/left.pfm", "PF\n"}}));
      },
      {"none.mpcdi: no mpcdi.xml in the archive; its 2 members: 'readme.txt', 'warps/left.pfm' "
       "(no .xml member to read instead)"});
  expect_error(
      [&] {
        load_mpcdi(make_zip(dir, "two.mpcdi", {{"a.xml", kXml2d}, {"b.xml", kXml2d}}));
      },
      {"two.mpcdi: no mpcdi.xml", "'a.xml', 'b.xml'", "2 .xml members: cannot tell which one is the descriptor"});
  Members many;
  for (int k = 0; k < 20; ++k) many.push_back({"file" + std::to_string(k) + ".pfm", "PF\n"});
  expect_error([&] { load_mpcdi(make_zip(dir, "many.mpcdi", many)); },
               {"many.mpcdi: no mpcdi.xml in the archive; its 20 members: 'file0.pfm'", "'file11.pfm' and 8 more"});
}

TEST(MpcdiVendor, ATruncatedArchiveSaysItMayBeTruncated) {
  ScratchDir dir("mpcdi_truncated");
  const auto whole = make_zip(dir, "whole.mpcdi", valid_2d_members());
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 200u);
  const auto cut = dir.write("cut.mpcdi", bytes.substr(0, bytes.size() / 2));
  expect_error([&] { load_mpcdi(cut); }, {"cut.mpcdi: cannot open as a ZIP archive", "may be truncated",
                                          std::to_string(bytes.size() / 2) + " bytes"});
  // The end record cut off, only a few bytes short.
  const auto short_end = dir.write("end.mpcdi", bytes.substr(0, bytes.size() - 10));
  expect_error([&] { load_mpcdi(short_end); }, {"end.mpcdi: cannot open as a ZIP archive", "may be truncated"});
  // Something that never was a ZIP is not called truncated.
  try {
    load_mpcdi(dir.write("text.mpcdi", "<MPCDI profile='2d'/>"));
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("text.mpcdi: cannot open as a ZIP archive"), std::string::npos);
    EXPECT_EQ(std::string(e.what()).find("may be truncated"), std::string::npos) << e.what();
  }
}

// ---- empty elements ------------------------------------------------------------

TEST(MpcdiVendor, EmptyElementsAreIgnoredWithAWarning) {
  const std::string alpha_block =
      std::string(kXml2d).substr(std::string(kXml2d).find("<alphaMap>"),
                                 std::string(kXml2d).find("</alphaMap>") + 11 - std::string(kXml2d).find("<alphaMap>"));
  std::string xml = xml_with(alpha_block, "<alphaMap />");
  xml = xml_with("<path>left_beta.png</path>", "<path> </path>", xml);
  xml = xml_with("<geometryWarpFile><path>right_warp.pfm</path></geometryWarpFile>",
                 "<geometryWarpFile></geometryWarpFile>", xml);
  ScratchDir dir("mpcdi_empty");
  LogCapture log;
  const MpcdiFile file = load_mpcdi(make_zip(dir, "empty.mpcdi", with_descriptor("mpcdi.xml", xml)));
  const MpcdiRegion* left = file.find_region("left");
  const MpcdiRegion* right = file.find_region("right");
  EXPECT_TRUE(left->warp_mesh);
  EXPECT_FALSE(left->alpha_map);
  EXPECT_FALSE(left->beta_map);
  EXPECT_FALSE(right->geometry_warp);
  EXPECT_FALSE(right->warp_mesh);
  log.expect_warning({"empty.mpcdi:mpcdi.xml:" + std::to_string(line_of(xml, "<alphaMap />")) +
                      ": region 'left': <alphaMap> names no file (an empty element): ignored"});
  log.expect_warning({"empty.mpcdi:mpcdi.xml:" + std::to_string(line_of(xml, "<betaMap>")) +
                      ": region 'left': <betaMap> names no file (an empty <path>): ignored"});
  log.expect_warning({"empty.mpcdi:mpcdi.xml:" + std::to_string(line_of(xml, "<geometryWarpFile></")) +
                      ": region 'right': <geometryWarpFile> names no file (an empty element): ignored"});
  EXPECT_EQ(log.warnings().size(), 3u);

  // An element with content but no <path> is still an error, with its line.
  const std::string no_path = xml_with(alpha_block, "<alphaMap>\n<bitDepth>8</bitDepth></alphaMap>");
  expect_error(
      [&] { load_mpcdi(make_zip(dir, "nopath.mpcdi", with_descriptor("mpcdi.xml", no_path))); },
      {"nopath.mpcdi:mpcdi.xml:" + std::to_string(line_of(no_path, "<alphaMap>")) + ": <alphaMap> has no <path>"});
}

// ---- E&S offset warps --------------------------------------------------------------

// A 5 × 4 warp in the region's image: the offset from the regular grid, and the absolute twin.
double offset_x(int x, int y) { return 0.02 * std::cos(0.7 * x) - 0.01 * y; }
double offset_y(int x, int y) { return 0.015 * x * (y - 1.5) / 4.0; }

Members offset_show(bool offsets) {
  const auto value = [offsets](int x, int y, int c) {
    const double grid = c == 0 ? x / 4.0 : y / 3.0;
    const double offset = c == 0 ? offset_x(x, y) : offset_y(x, y);
    return static_cast<float>(c == 2 ? 0.0 : (offsets ? 0.0 : grid) + offset);
  };
  std::string xml = xml_with("xResolution=\"4\" yResolution=\"3\"/>", "xResolution=\"5\" yResolution=\"4\"/>");
  Members members = with_descriptor("mpcdi.xml", xml);
  members[1].second = make_pfm(5, 4, 3, value, true, true);
  members[2].second = make_pfm(
      5, 4, 3, [](int, int, int) { return 0.0f; }, true, true);  // right: all zeros
  return members;
}

TEST(MpcdiVendor, OffsetWarpsMatchTheirAbsoluteTwin) {
  ScratchDir dir("mpcdi_offsets");
  const MpcdiFile absolute = load_mpcdi(make_zip(dir, "absolute.mpcdi", offset_show(false)));  // right: zeros, warned
  LogCapture log;
  const MpcdiFile offsets =
      load_mpcdi(make_zip(dir, "es.mpcdi", offset_show(true)), MpcdiLoadOptions{WarpValues::offsets});
  const WarpMesh& a = *absolute.find_region("left")->warp_mesh;
  const WarpMesh& b = *offsets.find_region("left")->warp_mesh;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) {
      EXPECT_NEAR(b.node(x, y).u, x / 4.0 + offset_x(x, y), 1e-6);
      EXPECT_NEAR(b.node(x, y).v, y / 3.0 + offset_y(x, y), 1e-6);
      EXPECT_NEAR(a.node(x, y).u, b.node(x, y).u, 1e-6);
      EXPECT_NEAR(a.node(x, y).v, b.node(x, y).v, 1e-6);
    }
  for (const double s : {0.05, 0.4, 0.93})
    for (const double t : {0.1, 0.5, 0.88}) {
      EXPECT_NEAR(a.sample(s, t)->u, b.sample(s, t)->u, 1e-6);
      EXPECT_NEAR(a.sample(s, t)->v, b.sample(s, t)->v, 1e-6);
    }
  // All zeros as offsets: no distortion.
  const WarpMesh& identity = *offsets.find_region("right")->warp_mesh;
  EXPECT_NEAR(identity.sample(0.3, 0.6)->u, 0.3, 1e-12);
  EXPECT_NEAR(identity.sample(0.3, 0.6)->v, 0.6, 1e-12);
  EXPECT_TRUE(log.warnings().empty());

  // The same archive read as VESA's absolute positions: both warps are warned about.
  load_mpcdi(make_zip(dir, "es2.mpcdi", offset_show(true)));
  log.expect_warning({"es2.mpcdi:left_warp.pfm: the values look like offsets", "\"values\": \"offsets\""});
  log.expect_warning({"es2.mpcdi:right_warp.pfm: every valid sample (20) maps to one point (u, v) = (0, 0)"});
}

TEST(MpcdiVendor, ViewportValuesOffsetsGivesTheAbsoluteTwinsRays) {
  ScratchDir dir("mpcdi_offsets_viewport");
  make_zip(dir, "absolute.mpcdi", offset_show(false));
  make_zip(dir, "es.mpcdi", offset_show(true));
  const auto config = [&](const std::string& file, bool offsets) {
    json j = json::parse(R"({"zenith_viewports": 1, "name": "t", "outputs": [
      {"name": "left", "size": [80, 60], "projection": {"type": "fisheye"}}]})");
    j["outputs"][0]["warp"] = json{{"file", file}, {"format", "mpcdi"}, {"region", "left"}};
    if (offsets) j["outputs"][0]["warp"]["values"] = "offsets";
    return parse_viewport_config(j, "v.json", dir.path());
  };
  const ViewportConfig a = config("absolute.mpcdi", false), b = config("es.mpcdi", true);
  EXPECT_EQ(b.outputs[0].warp->conventions.values, WarpValues::offsets);
  int compared = 0;
  for (double y = 0.5; y < 60; y += 3.1)
    for (double x = 0.5; x < 80; x += 2.9) {
      const auto ra = a.outputs[0].projection->ray(x, y), rb = b.outputs[0].projection->ray(x, y);
      ASSERT_EQ(ra.has_value(), rb.has_value());
      if (!ra) continue;
      EXPECT_LT(glm::length(*ra - *rb), 1e-6);
      ++compared;
    }
  EXPECT_GT(compared, 300);
  expect_error(
      [&] {
        json j = json::parse(R"({"zenith_viewports": 1, "name": "t", "outputs": [
      {"name": "left", "size": [80, 60], "projection": {"type": "fisheye"},
       "warp": {"file": "es.mpcdi", "format": "mpcdi", "region": "left", "v_direction": "up"}}]})");
        parse_viewport_config(j, "v.json", dir.path());
      },
      {"v.json: /outputs/0/warp/v_direction", "applies to \"format\": \"pfm\" only (format is \"mpcdi\")"});
}

// ---- frustum angles ----------------------------------------------------------------

std::string frustum_xml(double yaw, double pitch, double roll) {
  std::ostringstream frustum;
  frustum << "xResolution=\"4\" yResolution=\"3\">\n        <frustum><yaw>" << yaw << "</yaw><pitch>" << pitch
          << "</pitch><roll>" << roll << "</roll>\n"
          << "          <leftAngle>-30</leftAngle><rightAngle>35</rightAngle><upAngle>20</upAngle>"
             "<downAngle>-25</downAngle></frustum>\n      </region>";
  std::string xml = xml_with("profile=\"2d\"", "profile=\"3d\"");
  xml = xml_with("xResolution=\"4\" yResolution=\"3\"/>", frustum.str(), xml);
  return xml_with("xResolution=\"4\" yResolution=\"3\"></region>",
                  "xResolution=\"4\" yResolution=\"3\"><frustum><yaw>0</yaw><pitch>0</pitch><roll>0</roll>"
                  "<leftAngle>-30</leftAngle><rightAngle>30</rightAngle><upAngle>20</upAngle>"
                  "<downAngle>-20</downAngle></frustum></region>",
                  xml);
}

MpcdiFrustum load_frustum(const ScratchDir& dir, double yaw, double pitch, double roll) {
  std::ostringstream name;
  name << "f_" << yaw << "_" << pitch << "_" << roll << ".mpcdi";
  const MpcdiFile file =
      load_mpcdi(make_zip(dir, name.str(), with_descriptor("mpcdi.xml", frustum_xml(yaw, pitch, roll))));
  return *file.find_region("left")->frustum;
}

/// Right-handed rotation of v about the unit `axis` by `angle_deg` (Rodrigues).
glm::dvec3 rotated(const glm::dvec3& v, const glm::dvec3& axis, double angle_deg) {
  const double a = angle_deg * zenith::core::kPi / 180.0;
  return v * std::cos(a) + glm::cross(axis, v) * std::sin(a) + axis * glm::dot(axis, v) * (1.0 - std::cos(a));
}

/// The frustum frame → camera frame rotation of docs/projections.md applied to
/// v, written out independently: roll about −z, then pitch about +x, then yaw
/// about +y with positive yaw turning toward +x.
glm::dvec3 turned(const glm::dvec3& v, double yaw, double pitch, double roll) {
  return rotated(rotated(rotated(v, {0, 0, -1}, roll), {1, 0, 0}, pitch), {0, 1, 0}, -yaw);
}

TEST(MpcdiVendor, FrustumAnglesIn0To360AreNormalized) {
  ScratchDir dir("mpcdi_frustum");
  const MpcdiFrustum wrapped = load_frustum(dir, 350, 340, 270);
  const MpcdiFrustum negative = load_frustum(dir, -10, -20, -90);
  EXPECT_NEAR(wrapped.yaw_deg, -10.0, 1e-12);
  EXPECT_NEAR(wrapped.pitch_deg, -20.0, 1e-12);
  EXPECT_NEAR(wrapped.roll_deg, -90.0, 1e-12);
  EXPECT_NEAR(wrapped.yaw_deg, negative.yaw_deg, 1e-12);
  EXPECT_NEAR(wrapped.pitch_deg, negative.pitch_deg, 1e-12);
  EXPECT_NEAR(wrapped.roll_deg, negative.roll_deg, 1e-12);
  EXPECT_EQ(wrapped.left_deg, -30.0);
  EXPECT_EQ(wrapped.right_deg, 35.0);
  const PlanarProjection a(64, 48, wrapped.planar()), b(64, 48, negative.planar());
  for (double y = 0.5; y < 48; y += 11)
    for (double x = 0.5; x < 64; x += 13) EXPECT_LT(glm::length(*a.ray(x, y) - *b.ray(x, y)), 1e-12);

  // Every normalized orientation is the rotation the file wrote, checked against
  // the rays of the unrotated frustum turned by an independent rotation.
  struct Case {
    double yaw, pitch, roll;
  };
  for (const Case c : {Case{350, 340, 270}, Case{30, 120, 0}, Case{200, 250, 10}, Case{359.5, 180, 90}, Case{0, 90, 0},
                       Case{-300, -100, -200}}) {
    SCOPED_TRACE(::testing::PrintToString(std::vector<double>{c.yaw, c.pitch, c.roll}));
    const MpcdiFrustum f = load_frustum(dir, c.yaw, c.pitch, c.roll);
    EXPECT_GT(f.yaw_deg, -180.0);
    EXPECT_LE(f.yaw_deg, 180.0);
    EXPECT_GE(f.pitch_deg, -90.0);
    EXPECT_LE(f.pitch_deg, 90.0);
    EXPECT_GT(f.roll_deg, -180.0);
    EXPECT_LE(f.roll_deg, 180.0);
    const PlanarProjection rotated_projection(64, 48, f.planar());
    PlanarFrustum straight = f.planar();
    straight.yaw_deg = straight.pitch_deg = straight.roll_deg = 0.0;
    const PlanarProjection straight_projection(64, 48, straight);
    for (double y = 0.5; y < 48; y += 11)
      for (double x = 0.5; x < 64; x += 13) {
        const glm::dvec3 expected = turned(*straight_projection.ray(x, y), c.yaw, c.pitch, c.roll);
        EXPECT_LT(glm::length(*rotated_projection.ray(x, y) - expected), 1e-12) << x << ", " << y;
      }
  }
}

TEST(MpcdiVendor, FrustumAnglesBeyond360AreRefusedWithTheirLine) {
  ScratchDir dir("mpcdi_frustum_range");
  const std::string xml = frustum_xml(400, 0, 0);
  expect_error([&] { load_mpcdi(make_zip(dir, "far.mpcdi", with_descriptor("mpcdi.xml", xml))); },
               {"far.mpcdi:mpcdi.xml:" + std::to_string(line_of(xml, "<yaw>400")) +
                ": region 'left': <frustum> <yaw> = 400: must be in [-360, 360] degrees"});
  const std::string low = frustum_xml(0, 0, -361);
  expect_error([&] { load_mpcdi(make_zip(dir, "low.mpcdi", with_descriptor("mpcdi.xml", low))); },
               {"low.mpcdi:mpcdi.xml:", "<frustum> <roll> = -361: must be in [-360, 360] degrees"});
}

}  // namespace
}  // namespace zenith::warp
