// MPCDI archives (hand-written mpcdi.xml, PFM warps and PNG maps zipped here
// with libzip) and the XML reader underneath.
#include "warp/mpcdi.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "tests/warp/mpcdi_test_support.h"
#include "tests/warp/warp_file_test_support.h"
#include "warp/xml_reader.h"

namespace zenith::warp {
namespace {

using testing::expect_error;
using testing::kAlpha;
using testing::kXml2d;
using testing::make_grey_png;
using testing::make_pfm;
using testing::make_zip;
using testing::Members;
using testing::ScratchDir;
using testing::valid_2d_members;
using testing::warp_value;

TEST(Mpcdi, ReadsAHandWritten2dProfile) {
  ScratchDir dir("mpcdi");
  const MpcdiFile file = load_mpcdi(make_zip(dir, "show.mpcdi", valid_2d_members()));
  EXPECT_EQ(file.profile, MpcdiProfile::media_2d);
  EXPECT_STREQ(to_string(file.profile), "2d");
  EXPECT_EQ(file.version, "2.0");
  ASSERT_EQ(file.buffers.size(), 1u);
  const MpcdiBuffer& buffer = file.buffers[0];
  EXPECT_EQ(buffer.id, "main");
  EXPECT_EQ(buffer.x_resolution_px, 1920);
  EXPECT_EQ(buffer.y_resolution_px, 1080);
  ASSERT_EQ(buffer.regions.size(), 2u);

  const MpcdiRegion* left = file.find_region("left");
  ASSERT_NE(left, nullptr);
  EXPECT_EQ(left->x, 0.0);
  EXPECT_EQ(left->xsize, 0.5);
  EXPECT_EQ(left->ysize, 1.0);
  EXPECT_EQ(left->x_resolution_px, 4);
  EXPECT_EQ(left->y_resolution_px, 3);
  EXPECT_FALSE(left->frustum);
  ASSERT_TRUE(left->geometry_warp);
  EXPECT_EQ(left->geometry_warp->path, "left_warp.pfm");
  EXPECT_EQ(left->geometry_warp->interpolation, "linear");
  EXPECT_EQ(left->geometry_warp->component_depth, 2);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(left->geometry_warp->map.at(x, y, 0), warp_value(x, y, 0));

  // The samples span the region edge to edge from the top-left; "linear" is bilinear.
  ASSERT_TRUE(left->warp_mesh);
  EXPECT_EQ(left->warp_mesh->interpolation(), WarpInterpolation::bilinear);
  const auto top_left = left->warp_mesh->sample(0.0, 0.0);
  const auto bottom_right = left->warp_mesh->sample(1.0, 1.0);
  const auto between = left->warp_mesh->sample(0.5 / 3, 0.25);
  ASSERT_TRUE(top_left && bottom_right && between);
  EXPECT_NEAR(top_left->u, 0.1, 1e-6);
  EXPECT_NEAR(top_left->v, 0.2, 1e-6);
  EXPECT_NEAR(bottom_right->u, 0.85, 1e-6);
  EXPECT_NEAR(bottom_right->v, 0.8, 1e-6);
  EXPECT_NEAR(between->u, 0.225, 1e-6);
  EXPECT_NEAR(between->v, 0.35, 1e-6);

  // Alpha: raw 8-bit values, gamma 2.2 to linear.
  ASSERT_TRUE(left->alpha_map);
  EXPECT_EQ(left->alpha_map->image.width, 4);
  EXPECT_EQ(left->alpha_map->image.channels, 1);
  EXPECT_EQ(left->alpha_map->image.bit_depth, 8);
  EXPECT_DOUBLE_EQ(left->alpha_map->gamma_embedded, 2.2);
  EXPECT_FLOAT_EQ(left->alpha_map->image.at(2, 0, 0), 128.0f / 255.0f);
  EXPECT_FLOAT_EQ(left->alpha_map->image.at(3, 2, 0), 1.0f / 255.0f);
  EXPECT_NEAR(left->alpha_map->linear(1, 0), std::pow(64.0 / 255.0, 2.2), 1e-6);
  ASSERT_TRUE(left->beta_map);
  EXPECT_FLOAT_EQ(left->beta_map->image.at(0, 0, 0), 7.0f / 255.0f);
  EXPECT_DOUBLE_EQ(left->beta_map->gamma_embedded, 1.0);

  // The big-endian twin reads the same; its interpolation defaults to linear.
  const MpcdiRegion* right = file.find_region("right");
  ASSERT_NE(right, nullptr);
  ASSERT_TRUE(right->warp_mesh);
  EXPECT_EQ(right->geometry_warp->map.samples, left->geometry_warp->map.samples);
  EXPECT_FALSE(right->alpha_map);
  EXPECT_EQ(file.find_region("nowhere"), nullptr);
}

TEST(Mpcdi, NamesAreCaseInsensitiveAndPathsRelativeToTheXml) {
  const char* xml = R"(<?XML version="1.0"?>
<mpcdi PROFILE="3D" Version="2.0">
  <DISPLAY>
    <Buffer ID="b">
      <REGION Id="r1" X="0" Y="0" XSize="1" YSize="1" XRESOLUTION="4" yresolution="3">
        <Frustum>
          <YAW>10</YAW><Pitch>-5.5</Pitch><roll>1</roll>
          <LeftAngle>-30</LeftAngle><RIGHTANGLE>32</RIGHTANGLE><upangle>20</upangle><DownAngle>-18</DownAngle>
        </Frustum>
        <coordinateFrame><posx>1</posx><posy>0</posy><posz>0</posz><yawx>0</yawx><yawy>-1</yawy><yawz>0</yawz>
          <pitchx>-1</pitchx><pitchy>0</pitchy><pitchz>0</pitchz><rollx>0</rollx><rolly>0</rolly><rollz>1</rollz>
        </coordinateFrame>
      </REGION>
    </Buffer>
  </DISPLAY>
  <FILES>
    <FileSet Region="r1">
      <GEOMETRYWARPFILE><PATH> warps\r1.pfm </PATH><Interpolation>Linear</Interpolation></GEOMETRYWARPFILE>
    </FileSet>
  </FILES>
  <extensionSet><extension Name="x"/></extensionSet>
</mpcdi>
)";
  ScratchDir dir("mpcdi_case");
  const MpcdiFile file = load_mpcdi(make_zip(
      dir, "case.mpcdi", {{"show/MPCDI.XML", xml}, {"show/warps/r1.pfm", make_pfm(4, 3, 3, warp_value, true, true)}}));
  EXPECT_EQ(file.profile, MpcdiProfile::simulation_3d);
  EXPECT_EQ(file.buffers[0].x_resolution_px, 0);  // not given
  const MpcdiRegion* region = file.find_region("r1");
  ASSERT_NE(region, nullptr);
  ASSERT_TRUE(region->frustum);
  const PlanarFrustum planar = region->frustum->planar();
  EXPECT_EQ(planar.yaw_deg, 10.0);
  EXPECT_EQ(planar.pitch_deg, -5.5);
  EXPECT_EQ(planar.roll_deg, 1.0);
  EXPECT_EQ(planar.left_deg, -30.0);
  EXPECT_EQ(planar.right_deg, 32.0);
  EXPECT_EQ(planar.up_deg, 20.0);
  EXPECT_EQ(planar.down_deg, -18.0);
  ASSERT_TRUE(region->warp_mesh);
  EXPECT_EQ(region->geometry_warp->path, "warps\\r1.pfm");
}

TEST(Mpcdi, RejectsAnArchiveWithoutMpcdiXml) {
  ScratchDir dir("mpcdi_noxml");
  const auto path = make_zip(dir, "empty.mpcdi", {{"readme.txt", "no xml here"}, {"warp.pfm", "PF\n"}});
  expect_error([&] { load_mpcdi(path); }, {"empty.mpcdi: no mpcdi.xml in the archive"});
  expect_error([&] { load_mpcdi(dir.write("plain.mpcdi", "not a zip at all")); },
               {"plain.mpcdi: cannot open as a ZIP archive"});
  expect_error([&] { load_mpcdi(dir.path() / "absent.mpcdi"); }, {"absent.mpcdi: cannot open as a ZIP archive"});
}

TEST(Mpcdi, RejectsAMissingWarpFile) {
  ScratchDir dir("mpcdi_nowarp");
  Members members = valid_2d_members();
  members.erase(members.begin() + 2);  // right_warp.pfm
  expect_error(
      [&] { load_mpcdi(make_zip(dir, "nowarp.mpcdi", members)); },
      {"nowarp.mpcdi:mpcdi.xml:34:", "region 'right': geometry warp file 'right_warp.pfm' is not in the archive"});
  members = valid_2d_members();
  members.erase(members.begin() + 3);  // left_alpha.png
  expect_error([&] { load_mpcdi(make_zip(dir, "noalpha.mpcdi", members)); },
               {"region 'left': alpha map 'left_alpha.png' is not in the archive"});
}

TEST(Mpcdi, RejectsMalformedXmlWithItsLine) {
  ScratchDir dir("mpcdi_xml");
  std::string xml = kXml2d;
  xml.replace(xml.find("</buffer>"), 9, "</bufer>");  // line 8
  Members members = valid_2d_members();
  members[0].second = xml;
  expect_error([&] { load_mpcdi(make_zip(dir, "bad.mpcdi", members)); },
               {"bad.mpcdi:mpcdi.xml:8: malformed XML: </bufer> closes <buffer> opened at line 5"});
}

TEST(Mpcdi, RejectsMissingAttributesAndBadValues) {
  ScratchDir dir("mpcdi_attr");
  const auto with_xml = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string xml = kXml2d;
    xml.replace(xml.find(from), from.size(), to);
    Members members = valid_2d_members();
    members[0].second = xml;
    return make_zip(dir, name, members);
  };
  expect_error(
      [&] {
        load_mpcdi(with_xml("a.mpcdi", " xsize=\"0.5\" ysize=\"1\" xResolution=\"4\" yResolution=\"3\"/>",
                            " ysize=\"1\" xResolution=\"4\" yResolution=\"3\"/>"));
      },
      {"a.mpcdi:mpcdi.xml:6: <region> has no attribute 'xsize'"});
  expect_error([&] { load_mpcdi(with_xml("b.mpcdi", "profile=\"2d\"", "profile=\"4d\"")); },
               {"b.mpcdi:mpcdi.xml:3:", "'profile' = '4d': must be one of 2d, 3d, a3, sl"});
  expect_error([&] { load_mpcdi(with_xml("c.mpcdi", "profile=\"2d\" ", "")); }, {"<MPCDI> has no attribute 'profile'"});
  expect_error([&] { load_mpcdi(with_xml("d.mpcdi", "xsize=\"0.5\"", "xsize=\"1.5\"")); },
               {"attribute 'xsize' = 1.5: must be in [0, 1]"});
  expect_error([&] { load_mpcdi(with_xml("e.mpcdi", "xResolution=\"4\"", "xResolution=\"four\"")); },
               {"attribute 'xResolution' = 'four' is not a finite number"});
  expect_error([&] { load_mpcdi(with_xml("f.mpcdi", "<fileset region=\"right\">", "<fileset region=\"middle\">")); },
               {"<fileset> names region 'middle'"});
  expect_error([&] { load_mpcdi(with_xml("g.mpcdi", "profile=\"2d\"", "profile=\"3d\"")); },
               {"<region> 'left' has no <frustum> (required by the 3d profile)"});
  expect_error([&] { load_mpcdi(with_xml("h.mpcdi", "<interpolation>linear", "<interpolation>nearest")); },
               {"region 'left': <interpolation> 'nearest': must be linear, cubic (smooth, bicubic) or unknown"});
}

TEST(Mpcdi, RejectsBrokenAndNaNOnlyWarps) {
  ScratchDir dir("mpcdi_pfm");
  Members members = valid_2d_members();
  members[1].second.resize(members[1].second.size() - 8);
  expect_error([&] { load_mpcdi(make_zip(dir, "short.mpcdi", members)); },
               {"short.mpcdi:left_warp.pfm: PFM: truncated"});
  members = valid_2d_members();
  members[1].second = "PF\n4 3 -1\n";
  expect_error([&] { load_mpcdi(make_zip(dir, "header.mpcdi", members)); },
               {"header.mpcdi:left_warp.pfm: PFM: truncated"});
  members[1].second = "P7\n4 3\n-1\n";
  expect_error([&] { load_mpcdi(make_zip(dir, "magic.mpcdi", members)); },
               {"magic.mpcdi:left_warp.pfm: PFM: bad header"});
  members[1].second = make_pfm(
      4, 3, 3, [](int, int, int) { return std::numeric_limits<float>::quiet_NaN(); }, true, true);
  expect_error([&] { load_mpcdi(make_zip(dir, "nan.mpcdi", members)); }, {"nan.mpcdi:left_warp.pfm", "NaN-only mesh"});
  members = valid_2d_members();
  members[3].second = "not a png";
  expect_error([&] { load_mpcdi(make_zip(dir, "png.mpcdi", members)); }, {"png.mpcdi:left_alpha.png: not a PNG file"});
  members[3].second = make_grey_png(4, 3, kAlpha).substr(0, 40);
  expect_error([&] { load_mpcdi(make_zip(dir, "pngcut.mpcdi", members)); }, {"pngcut.mpcdi:left_alpha.png:"});
}

TEST(Mpcdi, Advanced3dKeepsTheRawPointMap) {
  std::string xml = kXml2d;
  xml.replace(xml.find("profile=\"2d\""), 12, "profile=\"a3\"");
  Members members = valid_2d_members();
  members[0].second = xml;
  ScratchDir dir("mpcdi_a3");
  const MpcdiFile file = load_mpcdi(make_zip(dir, "a3.mpcdi", members));
  EXPECT_EQ(file.profile, MpcdiProfile::advanced_3d);
  const MpcdiRegion* left = file.find_region("left");
  ASSERT_TRUE(left->geometry_warp);
  EXPECT_FALSE(left->warp_mesh);
  EXPECT_EQ(left->geometry_warp->map.width, 4);
}

// ---- XML reader ---------------------------------------------------------------

TEST(XmlReader, ReadsElementsAttributesTextAndEntities) {
  const XmlElement root = parse_xml(
      "\xEF\xBB\xBF<?xml version='1.0'?>\n<!-- c -->\n<Root a='1' B=\"x &amp; y\">\n"
      "  <item>&lt;&#65;&#x42;&gt;</item><![CDATA[<raw>]]>\n  <?pi skip?><Item/>\n</ROOT>\n<!-- after -->\n",
      "doc.xml");
  EXPECT_EQ(root.name, "Root");
  EXPECT_TRUE(root.is("root"));
  ASSERT_NE(root.attribute("A"), nullptr);
  EXPECT_EQ(*root.attribute("A"), "1");
  EXPECT_EQ(*root.attribute("b"), "x & y");
  EXPECT_EQ(root.attribute("c"), nullptr);
  ASSERT_EQ(root.children_named("ITEM").size(), 2u);
  EXPECT_EQ(root.child("item")->text, "<AB>");
  EXPECT_EQ(root.child("item")->line, 4);
  EXPECT_EQ(root.children[1].line, 5);
  EXPECT_NE(root.text.find("<raw>"), std::string::npos);
}

TEST(XmlReader, RejectsMalformedDocumentsWithTheLine) {
  const auto parse = [](const std::string& text) { parse_xml(text, "t.xml"); };
  expect_error([&] { parse("<a>\n<b>\n</a>"); }, {"t.xml:3: malformed XML: </a> closes <b> opened at line 2"});
  expect_error([&] { parse("<a>\n<b>text"); }, {"t.xml:2: malformed XML: <b> is never closed"});
  expect_error([&] { parse("<!DOCTYPE a>\n<a/>"); }, {"t.xml:1:", "DTDs"});
  expect_error([&] { parse("<a>&nbsp;</a>"); }, {"unknown entity '&nbsp;'"});
  expect_error([&] { parse("<a x='1' X='2'/>"); }, {"duplicate attribute 'X'"});
  expect_error([&] { parse("<a x=1/>"); }, {"attribute value must be quoted"});
  expect_error([&] { parse("<a/>\n<b/>"); }, {"t.xml:2:", "a second root element"});
  expect_error([&] { parse("<a/>\ntext"); }, {"t.xml:2:", "text after the root element"});
  expect_error([&] { parse(""); }, {"no root element"});
  expect_error([&] { parse("<a>\n<!-- open\n</a>"); }, {"t.xml:2:", "unterminated comment"});
  expect_error([&] { parse("<!-- c --><?xml version='1.0'?><a/>"); }, {"the XML declaration must come first"});
  expect_error([&] { parse("<a b='<'/>"); }, {"'<' in an attribute value"});
}

}  // namespace
}  // namespace zenith::warp
