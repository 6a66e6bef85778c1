#pragma once
// Helpers of the MPCDI tests: ZIP archives built in memory (libzip), and the
// hand-written two-region 2d show most tests start from.
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tests/warp/warp_file_test_support.h"

namespace zenith::warp::testing {

using Members = std::vector<std::pair<std::string, std::string>>;

/// Writes a ZIP archive holding `members` (name, bytes).
inline std::filesystem::path make_zip(const ScratchDir& dir, const std::string& name, const Members& members) {
  const std::filesystem::path path = dir.path() / name;
  int code = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  EXPECT_NE(archive, nullptr) << "zip_open " << code;
  for (const auto& [member, bytes] : members) {
    zip_source_t* source = zip_source_buffer(archive, bytes.data(), bytes.size(), 0);
    EXPECT_NE(source, nullptr);
    EXPECT_GE(zip_file_add(archive, member.c_str(), source, ZIP_FL_OVERWRITE), 0) << zip_strerror(archive);
  }
  EXPECT_EQ(zip_close(archive), 0);
  return path;
}

// The 4 × 3 warp of the examples: x = 0.1 + 0.25 i, y = 0.2 + 0.3 j (top-left first).
inline float warp_value(int x, int y, int c) { return c == 0 ? 0.1f + 0.25f * x : c == 1 ? 0.2f + 0.3f * y : 0.0f; }

inline const std::vector<unsigned char> kAlpha = {0, 64, 128, 255, 10, 20, 30, 40, 255, 255, 0, 1};

inline const char* const kXml2d = R"(<?xml version="1.0" encoding="utf-8"?>
<!-- a two-region 2d show -->
<MPCDI profile="2d" geometry="1" color="1" version="2.0">
  <display>
    <buffer id="main" xResolution="1920" yResolution="1080">
      <region id="left" x="0" y="0" xsize="0.5" ysize="1" xResolution="4" yResolution="3"/>
      <region id="right" x="0.5" y="0" xsize="0.5" ysize="1" xResolution="4" yResolution="3"></region>
    </buffer>
  </display>
  <files>
    <fileset region="left">
      <geometryWarpFile>
        <path>left_warp.pfm</path>
        <interpolation>linear</interpolation>
        <componentDepth>2</componentDepth>
        <bitDepth>32</bitDepth>
        <xSamples>4</xSamples>
        <ySamples>3</ySamples>
        <originOf2DData>topLeftCorner</originOf2DData>
      </geometryWarpFile>
      <alphaMap>
        <path>left_alpha.png</path>
        <componentDepth>1</componentDepth>
        <bitDepth>8</bitDepth>
        <gammaEmbedded>2.2</gammaEmbedded>
      </alphaMap>
      <betaMap>
        <path>left_beta.png</path>
        <componentDepth>1</componentDepth>
        <bitDepth>8</bitDepth>
      </betaMap>
    </fileset>
    <fileset region="right">
      <geometryWarpFile><path>right_warp.pfm</path></geometryWarpFile>
    </fileset>
  </files>
</MPCDI>
)";

inline Members valid_2d_members() {
  return {{"mpcdi.xml", kXml2d},
          {"left_warp.pfm", make_pfm(4, 3, 3, warp_value, true, true)},    // little endian
          {"right_warp.pfm", make_pfm(4, 3, 3, warp_value, false, true)},  // big endian
          {"left_alpha.png", make_grey_png(4, 3, kAlpha)},
          {"left_beta.png", make_grey_png(4, 3, std::vector<unsigned char>(12, 7))}};
}

/// A region of a 2d archive for the blend-map tests: its id, resolution and
/// the elements of its fileset besides the geometry warp (<alphaMap>, <betaMap>).
struct MapsRegion {
  std::string id;
  int width_px = 0, height_px = 0;
  std::string maps;
};

/// The descriptor of a 2d archive of one buffer holding `regions`, each with
/// the identity geometry warp "<id>.pfm" (identity_warp()).
inline std::string descriptor_with_maps(const std::vector<MapsRegion>& regions) {
  std::string xml =
      "<?xml version=\"1.0\"?>\n<MPCDI profile=\"2d\" geometry=\"1\" color=\"2\" version=\"2.0\">\n<display>\n"
      "<buffer id=\"b\">\n";
  for (const MapsRegion& r : regions)
    xml += "<region id=\"" + r.id + "\" x=\"0\" y=\"0\" xsize=\"1\" ysize=\"1\" xResolution=\"" +
           std::to_string(r.width_px) + "\" yResolution=\"" + std::to_string(r.height_px) + "\"/>\n";
  xml += "</buffer>\n</display>\n<files>\n";
  for (const MapsRegion& r : regions)
    xml += "<fileset region=\"" + r.id + "\">\n<geometryWarpFile><path>" + r.id +
           ".pfm</path><interpolation>linear</interpolation></geometryWarpFile>\n" + r.maps + "</fileset>\n";
  return xml + "</files>\n</MPCDI>\n";
}

/// A geometry warp of 2 × 2 samples at the region's corners mapping each
/// point to itself: the output shows its projection's image unchanged.
inline std::string identity_warp() {
  return make_pfm(
      2, 2, 3, [](int x, int y, int c) { return c == 0   ? float(x)
                                                : c == 1 ? float(y)
                                                         : 0.0f; }, true, true);
}

/// The stored samples of a w × h map, row 0 at the top: value(i, j) each.
template <typename Sample>
std::vector<Sample> map_samples(int w, int h, Sample (*value)(int, int)) {
  std::vector<Sample> samples;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) samples.push_back(value(i, j));
  return samples;
}

/// An <alphaMap> (with gammaEmbedded when `gamma` > 0) or <betaMap> element.
inline std::string map_element(const std::string& tag, const std::string& path, int component_depth, int bit_depth,
                               double gamma = 0.0) {
  return "<" + tag + "><path>" + path + "</path><componentDepth>" + std::to_string(component_depth) +
         "</componentDepth><bitDepth>" + std::to_string(bit_depth) + "</bitDepth>" +
         (gamma > 0.0 ? "<gammaEmbedded>" + std::to_string(gamma) + "</gammaEmbedded>" : std::string()) + "</" + tag +
         ">\n";
}

/// A w × h map's value at the centre of pixel (x, y) of a width_px × height_px
/// output, worked out as a sum of tent weights over every sample: sample (i, j)
/// sits at its texel centre, the pixel reads the map at ((x + ½) / width_px ·
/// w − ½, (y + ½) / height_px · h − ½), clamped to the samples (OpenGL's clamp
/// to edge). The tests' own form of warp/mpcdi_blend.h's bilinear lookup.
inline double tent_sum(const std::function<double(int, int)>& sample, int w, int h, int width_px, int height_px, int x,
                       int y) {
  const double s = std::clamp((x + 0.5) / width_px * w - 0.5, 0.0, w - 1.0);
  const double t = std::clamp((y + 0.5) / height_px * h - 0.5, 0.0, h - 1.0);
  double sum = 0.0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      sum += std::max(0.0, 1.0 - std::abs(s - i)) * std::max(0.0, 1.0 - std::abs(t - j)) * sample(i, j);
  return sum;
}

}  // namespace zenith::warp::testing
