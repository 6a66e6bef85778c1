// Real calibration files written by other tools (tests/data/warp/, README
// there): each loads through its viewport config, as a show would load it,
// and what it holds is checked against the file's own bytes. A stricter reader
// must never refuse one of them; damaged copies of them must still be refused
// with the file, the member and the reason named.
#include <gtest/gtest.h>
#include <zip.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "tests/warp/mpcdi_test_support.h"
#include "tests/warp/warp_file_test_support.h"
#include "warp/fisheye_projection.h"
#include "warp/mpcdi.h"
#include "warp/mpcdi_projection.h"
#include "warp/planar_projection.h"
#include "warp/viewport_config.h"
#include "warp/warp_mesh.h"

namespace zenith::warp {
namespace {

using testing::expect_error;
using testing::LogCapture;
using testing::ScratchDir;

const std::filesystem::path kRealFiles = std::filesystem::path(ZENITH_SOURCE_DIR) / "tests/data/warp";

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// One member of a ZIP archive, read with libzip alone (not through the reader under test).
std::string zip_member(const std::filesystem::path& archive, const std::string& member) {
  int code = 0;
  std::unique_ptr<zip_t, void (*)(zip_t*)> zip(zip_open(archive.c_str(), ZIP_RDONLY, &code), zip_discard);
  if (!zip) throw std::runtime_error(archive.string() + ": not a ZIP");
  zip_stat_t stat;
  if (zip_stat(zip.get(), member.c_str(), 0, &stat) != 0) throw std::runtime_error(member + ": not in the archive");
  std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> file(zip_fopen(zip.get(), member.c_str(), 0), zip_fclose);
  std::string bytes(stat.size, '\0');
  if (!file || zip_fread(file.get(), bytes.data(), stat.size) != static_cast<zip_int64_t>(stat.size))
    throw std::runtime_error(member + ": cannot read");
  return bytes;
}

/// Sample (x, y, channel) of a little-endian 3-channel PFM ("PF\nW H\n-1.000\n"
/// then floats, rows as stored), decoded by hand.
float pfm_sample(const std::string& pfm, int width, int x, int stored_row, int channel) {
  std::size_t data = 0;
  for (int newlines = 0; newlines < 3; ++data)
    if (pfm[data] == '\n') ++newlines;
  float value = 0.0f;
  std::memcpy(&value, pfm.data() + data + 4 * ((static_cast<std::size_t>(stored_row) * width + x) * 3 + channel), 4);
  static_assert(std::endian::native == std::endian::little, "the files store little-endian floats");
  return value;
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// ---- Evans & Sutherland (Digistar) MPCDI exports ---------------------------------

TEST(RealFiles, EsCorrectionMeshLoadsWithItsTbdColourAsNoLevel) {
  LogCapture log;
  MpcdiLoadOptions options;
  options.warp_values = WarpValues::offsets;
  const std::filesystem::path archive = kRealFiles / "es_correction_mesh.mpcdi";
  const MpcdiFile file = load_mpcdi(archive, options);

  EXPECT_EQ(file.descriptor, "mpcdi1_.xml");
  EXPECT_EQ(file.profile, MpcdiProfile::simulation_3d);
  EXPECT_EQ(file.version, "2.0");
  EXPECT_EQ(file.colour_level, 0);  // color="TBD": no level given
  const std::string warning = log.expect_warning({"es_correction_mesh.mpcdi:mpcdi1_.xml:2:", "'color'", "'TBD'"});
  EXPECT_NE(warning.find("no colour level given"), std::string::npos) << warning;

  ASSERT_EQ(file.buffers.size(), 1u);
  EXPECT_EQ(file.buffers[0].x_resolution_px, 512);
  EXPECT_EQ(file.buffers[0].y_resolution_px, 540);
  const MpcdiRegion* region = file.find_region("surface1_region");
  ASSERT_NE(region, nullptr);
  EXPECT_EQ(region->x_resolution_px, 512);
  EXPECT_EQ(region->y_resolution_px, 540);
  EXPECT_DOUBLE_EQ(region->xsize, 1.0);  // written "xSize"
  ASSERT_TRUE(region->frustum);
  EXPECT_NEAR(region->frustum->yaw_deg, 326.675157 - 360.0, 1e-9);  // [0, 360) read as (−180, 180]
  EXPECT_NEAR(region->frustum->pitch_deg, 27.327616, 1e-9);
  EXPECT_NEAR(region->frustum->roll_deg, -14.611227, 1e-9);
  EXPECT_NEAR(region->frustum->left_deg, -33.231552, 1e-9);
  EXPECT_NEAR(region->frustum->up_deg, 34.644394, 1e-9);
  EXPECT_FALSE(region->alpha_map);  // <alphaMap />: none
  EXPECT_FALSE(region->colour);

  // The warp: 32 × 32 offsets from the regular grid, top row first (MPCDI), v down.
  ASSERT_TRUE(region->warp_mesh);
  const WarpMesh& mesh = *region->warp_mesh;
  ASSERT_EQ(mesh.columns(), 32);
  ASSERT_EQ(mesh.rows(), 32);
  EXPECT_EQ(mesh.valid_node_count(), 32 * 32);
  const std::string pfm = zip_member(archive, "surface1.pfm");
  double largest_offset = 0.0;
  for (const auto& [i, j] : {std::pair{0, 0}, {31, 0}, {0, 31}, {31, 31}, {7, 19}, {16, 16}, {25, 3}}) {
    const double du = pfm_sample(pfm, 32, i, j, 0), dv = pfm_sample(pfm, 32, i, j, 1);
    EXPECT_NEAR(mesh.node(i, j).u, i / 31.0 + du, 1e-6) << i << "," << j;
    EXPECT_NEAR(mesh.node(i, j).v, j / 31.0 + dv, 1e-6) << i << "," << j;
    largest_offset = std::max({largest_offset, std::abs(du), std::abs(dv)});
  }
  EXPECT_GT(largest_offset, 0.01);  // a real correction, not the identity
}

TEST(RealFiles, EsZeroDistortionMeshGivesTheFrustumsOwnRays) {
  LogCapture log;
  const ViewportConfig config = load_viewport_config(kRealFiles / "es-zero-distortion.viewport.json");
  ASSERT_EQ(config.outputs.size(), 1u);
  const OutputConfig& output = config.outputs[0];
  ASSERT_FALSE(output.warp_error);
  ASSERT_TRUE(output.projection);
  log.expect_warning({"es_zero_distortion_mesh.mpcdi:mpcdi_01.xml:2:", "'TBD'"});

  // All-zero offsets: every output pixel sees what the bare frustum sees there.
  const PlanarFrustum frustum{-33.2315521175878, 33.2315521175878, -34.6443944648075, 34.6443944648075,
                              326.675157167255,  27.3276163938133, -14.6112274987403};
  const PlanarProjection bare(64, 68, frustum);
  double worst_rad = 0.0;
  int rays = 0;
  for (int y = 0; y < 68; ++y)
    for (int x = 0; x < 64; ++x) {
      const auto warped = output.projection->ray(x + 0.5, y + 0.5);
      const auto expected = bare.ray(x + 0.5, y + 0.5);
      ASSERT_TRUE(warped && expected) << x << "," << y;
      worst_rad = std::max(worst_rad, angle_between(*warped, *expected));
      ++rays;
    }
  EXPECT_EQ(rays, 64 * 68);
  EXPECT_LT(worst_rad, 1e-5);  // the mesh's float nodes; a pixel here is ~1e-2 rad
  // Its axis: 33.3° left of ahead and 27.3° up, the corner of a dome's lower band.
  const glm::dvec3 axis = glm::normalize(*bare.ray(32.0, 34.0));
  EXPECT_NEAR(std::asin(axis.y), 27.3276163938133 * M_PI / 180.0, 1e-9);
}

TEST(RealFiles, EsCorrectionMeshMovesRaysAsItsOffsetsSay) {
  const ViewportConfig correction = load_viewport_config(kRealFiles / "es-correction.viewport.json");
  const ViewportConfig zero = load_viewport_config(kRealFiles / "es-zero-distortion.viewport.json");
  ASSERT_TRUE(correction.outputs[0].projection && zero.outputs[0].projection);
  // The offsets (up to 0.27 of the image) turn rays by up to ~0.27 of the
  // frustum's 66°-69° field: more than a pixel, less than the field.
  double largest_rad = 0.0;
  for (int y = 0; y < 68; y += 3)
    for (int x = 0; x < 64; x += 3) {
      const auto a = correction.outputs[0].projection->ray(x + 0.5, y + 0.5);
      const auto b = zero.outputs[0].projection->ray(x + 0.5, y + 0.5);
      if (a && b) largest_rad = std::max(largest_rad, angle_between(*a, *b));
    }
  EXPECT_GT(largest_rad, 2.0 * M_PI / 180.0);
  EXPECT_LT(largest_rad, 25.0 * M_PI / 180.0);
}

// ---- SGCT's sample warps --------------------------------------------------------

TEST(RealFiles, BourkeStandardMeshLoadsAsTheToolsShowIt) {
  const ViewportConfig config = load_viewport_config(kRealFiles / "bourke-standard-16x9.viewport.json");
  ASSERT_FALSE(config.outputs[0].warp_error);
  ASSERT_TRUE(config.outputs[0].projection);
  // The file's first node (bottom-left, x = −16/9, y = −1): u = 0.160825,
  // v = 0.86737 counted up, intensity 0.530521.
  const WarpMesh mesh = load_bourke_mesh(kRealFiles / "standard_16x9.data");
  ASSERT_EQ(mesh.columns(), 100);
  ASSERT_EQ(mesh.rows(), 60);
  const WarpNode& bottom_left = mesh.node(0, 59);
  ASSERT_TRUE(bottom_left.valid);
  EXPECT_NEAR(bottom_left.u, 0.160825, 1e-6);
  EXPECT_NEAR(bottom_left.v, 1.0 - 0.86737, 1e-6);
  EXPECT_NEAR(bottom_left.intensity, 0.530521, 1e-6);
  // An inner node (column 20, row 45 from the bottom: the file's line 4522):
  // x = −1.05948, y = 0.525424 → u = 0.368184, v = 0.809679 (up). On a 16:9
  // projector (fit "height": x ∈ ±16/9 across the width, y ∈ ±1 across the
  // height) that point of the image shows that point of the 180° dome master.
  const WarpNode& inner = mesh.node(20, 59 - 45);
  EXPECT_NEAR(inner.u, 0.368184, 1e-6);
  EXPECT_NEAR(inner.v, 1.0 - 0.809679, 1e-6);
  EXPECT_NEAR(inner.intensity, 0.397053, 1e-6);
  const double x_px = (-1.05948 + 16.0 / 9.0) / (32.0 / 9.0) * 64.0, y_px = (1.0 - 0.525424) / 2.0 * 36.0;
  const FisheyeProjection dome(36, 36);  // 180°
  const auto seen = config.outputs[0].projection->ray(x_px, y_px);
  const auto expected = dome.ray(0.368184 * 36.0, (1.0 - 0.809679) * 36.0);
  ASSERT_TRUE(seen && expected);
  EXPECT_LT(angle_between(*seen, *expected), 1e-5);
}

TEST(RealFiles, SgctSurfacePfmLoadsTopRowFirstWithVUp) {
  const ViewportConfig config = load_viewport_config(kRealFiles / "sgct-surface1.viewport.json");
  ASSERT_FALSE(config.outputs[0].warp_error);
  ASSERT_TRUE(config.outputs[0].projection);
  const WarpMesh mesh =
      load_pfm_warp_mesh(kRealFiles / "surface1.pfm", PfmRowOrder::top_to_bottom, WarpInterpolation::catmull_rom,
                         WarpMapConventions{WarpValues::absolute, WarpVDirection::up});
  ASSERT_EQ(mesh.columns(), 100);
  ASSERT_EQ(mesh.rows(), 100);
  EXPECT_EQ(mesh.valid_node_count(), 100 * 100);  // the third channel is NaN: not a validity flag
  const std::string pfm = file_bytes(kRealFiles / "surface1.pfm");
  for (const auto& [i, j] : {std::pair{0, 0}, {99, 0}, {0, 99}, {99, 99}, {42, 57}}) {
    EXPECT_NEAR(mesh.node(i, j).u, pfm_sample(pfm, 100, i, j, 0), 1e-6) << i << "," << j;
    EXPECT_NEAR(mesh.node(i, j).v, 1.0 - pfm_sample(pfm, 100, i, j, 1), 1e-6) << i << "," << j;
  }
}

// ---- damaged copies are still refused, clearly ------------------------------------

TEST(RealFiles, DamagedCopiesOfARealArchiveAreRefusedNamingWhatIsWrong) {
  ScratchDir dir("real_files");
  const std::string bytes = file_bytes(kRealFiles / "es_correction_mesh.mpcdi");

  const auto truncated = dir.write("truncated.mpcdi", bytes.substr(0, bytes.size() / 2));
  expect_error([&] { load_mpcdi(truncated); }, {"truncated.mpcdi", "may be truncated"});

  const auto not_zip = dir.write("not_a_zip.mpcdi", "<MPCDI profile=\"3d\"/>\n");
  expect_error([&] { load_mpcdi(not_zip); }, {"not_a_zip.mpcdi", "cannot open as a ZIP archive"});

  // A flipped byte inside the compressed warp: the member's checksum or inflate fails.
  std::string corrupt = bytes;
  const std::size_t warp_data = corrupt.find("surface1.pfm") + std::strlen("surface1.pfm") + 200;
  corrupt[warp_data] = static_cast<char>(corrupt[warp_data] ^ 0x5a);
  const auto corrupted = dir.write("corrupt.mpcdi", corrupt);
  expect_error([&] { load_mpcdi(corrupted); }, {"corrupt.mpcdi:surface1.pfm"});

  // A region the archive does not have, asked for by a viewport config.
  std::filesystem::copy_file(kRealFiles / "es_correction_mesh.mpcdi", dir.path() / "es.mpcdi");
  const nlohmann::json output = {
      {"name", "p1"},
      {"size", {64, 68}},
      {"warp", {{"file", "es.mpcdi"}, {"format", "mpcdi"}, {"region", "left"}, {"values", "offsets"}}}};
  expect_error(
      [&] {
        parse_viewport_config({{"zenith_viewports", 1}, {"name", "x"}, {"outputs", nlohmann::json::array({output})}},
                              "x.json", dir.path());
      },
      {"es.mpcdi", "\"left\"", "surface1_region"});
}

// A colour level that is a number outside table 3-3 stays an error: only text
// that is no number at all (Digistar's "TBD") reads as "none given".
TEST(RealFiles, AColourLevelOutsideTheTableIsStillRefused) {
  ScratchDir dir("real_files_colour");
  std::string xml = zip_member(kRealFiles / "es_zero_distortion_mesh.mpcdi", "mpcdi_01.xml");
  const std::size_t at = xml.find("color=\"TBD\"");
  ASSERT_NE(at, std::string::npos);
  for (const char* level : {"7", "0", "2.5"}) {
    std::string edited = xml;
    edited.replace(at, std::strlen("color=\"TBD\""), std::string("color=\"") + level + "\"");
    const auto archive = testing::make_zip(
        dir, std::string("level") + level + ".mpcdi",
        {{"mpcdi_01.xml", edited},
         {"zeroDistortion.pfm", zip_member(kRealFiles / "es_zero_distortion_mesh.mpcdi", "zeroDistortion.pfm")}});
    expect_error([&] { load_mpcdi(archive); }, {"mpcdi_01.xml:2:", "attribute 'color'", "[1, 5]"});
  }
  for (const char* none : {"", "  ", "n/a"}) {
    std::string edited = xml;
    edited.replace(at, std::strlen("color=\"TBD\""), std::string("color=\"") + none + "\"");
    const auto archive = testing::make_zip(
        dir, "none.mpcdi",
        {{"mpcdi_01.xml", edited},
         {"zeroDistortion.pfm", zip_member(kRealFiles / "es_zero_distortion_mesh.mpcdi", "zeroDistortion.pfm")}});
    EXPECT_EQ(load_mpcdi(archive).colour_level, 0) << "'" << none << "'";
  }
}

}  // namespace
}  // namespace zenith::warp
