#pragma once
// Helpers of the MPCDI tests: ZIP archives built in memory (libzip), and the
// hand-written two-region 2d show most tests start from.
#include <zip.h>

#include <filesystem>
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

}  // namespace zenith::warp::testing
