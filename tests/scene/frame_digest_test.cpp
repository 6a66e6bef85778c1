#include "scene/frame_digest.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cluster/protocol/messages.h"
#include "core/sha256.h"

namespace zenith::scene {
namespace {

/// A frame with every field away from its default: irradiance, an atmosphere.
FrameDescription full_frame() {
  FrameDescription f;
  f.frame = 7;
  f.show_time_s = 2.5;
  f.camera_position_m = {1.0, 2.0, 3.0};
  f.sun_angular_radius_rad = 0.00465;
  f.sun_irradiance_W_m2_nm = {1.5, 1.75};
  AtmosphereTableRef earth;
  earth.body_name = "Earth";
  for (std::size_t i = 0; i < earth.table_hash.size(); ++i) earth.table_hash[i] = static_cast<std::uint8_t>(i);
  earth.effective_from_frame = 3;
  f.atmospheres = {earth};
  f.render_flags = kRenderSunDisc | kRenderMultipleScattering;
  return f;
}

// The canonical order written out independently (Python's struct and hashlib
// over the byte sequence documented in frame_digest.h):
//   hashlib.sha256(struct.pack('>Q',0) + struct.pack('>d',0.0) + … ).hexdigest()[:16]
TEST(FrameDigest, MatchesTheDocumentedOrderComputedIndependently) {
  EXPECT_EQ(frame_digest(FrameDescription{}), "a0c727735aa8c9fc");
  EXPECT_EQ(frame_digest(full_frame()), "509a472f64b90b7b");
}

// The digest is the SHA-256 of the FrameState payload (protocol 4), as the
// nodes' presented.log and the offline manifests have always named a frame.
TEST(FrameDigest, EqualsTheDigestOfTheFrameStatePayload) {
  for (const FrameDescription& frame : {FrameDescription{}, full_frame()}) {
    const std::vector<std::uint8_t> payload = cluster::encode_payload(cluster::Message{frame});
    EXPECT_EQ(frame_digest(frame), core::to_hex(core::sha256(payload.data(), payload.size())).substr(0, 16));
  }
}

TEST(FrameDigest, EqualStatesHaveEqualDigests) {
  const FrameDescription a = full_frame();
  const FrameDescription b = full_frame();
  ASSERT_EQ(a, b);
  EXPECT_EQ(frame_digest(a), frame_digest(b));
  EXPECT_EQ(frame_digest(a).size(), 16u);
}

TEST(FrameDigest, AnyFieldChangeChangesIt) {
  using Change = std::pair<const char*, std::function<void(FrameDescription&)>>;
  const std::vector<Change> changes = {
      {"frame", [](FrameDescription& f) { f.frame += 1; }},
      {"show_time_s", [](FrameDescription& f) { f.show_time_s += 1e-9; }},
      {"camera_position_m.x", [](FrameDescription& f) { f.camera_position_m.x += 1e-6; }},
      {"camera_position_m.y", [](FrameDescription& f) { f.camera_position_m.y += 1e-6; }},
      {"camera_position_m.z", [](FrameDescription& f) { f.camera_position_m.z += 1e-6; }},
      {"camera_orientation.w", [](FrameDescription& f) { f.camera_orientation.w = -1.0; }},
      {"camera_orientation.x", [](FrameDescription& f) { f.camera_orientation.x = 1e-9; }},
      {"camera_orientation.y", [](FrameDescription& f) { f.camera_orientation.y = 1e-9; }},
      {"camera_orientation.z", [](FrameDescription& f) { f.camera_orientation.z = 1e-9; }},
      {"exposure", [](FrameDescription& f) { f.exposure *= 2.0; }},
      {"sun_direction.x", [](FrameDescription& f) { f.sun_direction.x = 1e-9; }},
      {"sun_direction.y", [](FrameDescription& f) { f.sun_direction.y = 1e-9; }},
      {"sun_direction.z", [](FrameDescription& f) { f.sun_direction.z = -1.0; }},
      {"sun_angular_radius_rad", [](FrameDescription& f) { f.sun_angular_radius_rad = 0.0; }},
      {"sun_irradiance value", [](FrameDescription& f) { f.sun_irradiance_W_m2_nm[1] = 1.76; }},
      {"sun_irradiance count", [](FrameDescription& f) { f.sun_irradiance_W_m2_nm.push_back(0.0); }},
      {"sun_irradiance order",
       [](FrameDescription& f) { std::swap(f.sun_irradiance_W_m2_nm[0], f.sun_irradiance_W_m2_nm[1]); }},
      {"atmosphere body_name", [](FrameDescription& f) { f.atmospheres[0].body_name = "Mars"; }},
      {"atmosphere table_hash", [](FrameDescription& f) { f.atmospheres[0].table_hash[31] ^= 1; }},
      {"atmosphere effective_from_frame", [](FrameDescription& f) { f.atmospheres[0].effective_from_frame = 4; }},
      {"atmosphere count", [](FrameDescription& f) { f.atmospheres.push_back(f.atmospheres[0]); }},
      {"no atmospheres", [](FrameDescription& f) { f.atmospheres.clear(); }},
      {"render_flags", [](FrameDescription& f) { f.render_flags |= kRenderEclipses; }},
      {"fade level", [](FrameDescription& f) { f.fade.level = 0.5; }},
      {"fade colour", [](FrameDescription& f) { f.fade.colour.g = 0.25; }},
      {"sky time",
       [](FrameDescription& f) {
         f.sky.has_time = true;
         f.sky.utc_jd1 = 2461000.5;
       }},
      {"sky catalogue", [](FrameDescription& f) { f.sky.star_catalogue[0] = 1; }},
  };
  std::set<std::string> seen = {frame_digest(full_frame())};
  for (const auto& [field, change] : changes) {
    FrameDescription f = full_frame();
    change(f);
    EXPECT_TRUE(seen.insert(frame_digest(f)).second) << field << " left the digest unchanged or collided";
  }
}

}  // namespace
}  // namespace zenith::scene
