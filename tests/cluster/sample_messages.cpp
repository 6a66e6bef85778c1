#include "tests/cluster/sample_messages.h"

#include <cmath>
#include <numeric>

namespace zenith::cluster {
namespace {

template <std::size_t N>
std::array<std::uint8_t, N> pattern(std::uint8_t seed) {
  std::array<std::uint8_t, N> a{};
  for (std::size_t i = 0; i < N; ++i) a[i] = static_cast<std::uint8_t>(seed + 7 * i);
  return a;
}

FrameState sample_frame_state(std::size_t wavelengths, std::size_t atmospheres, std::size_t name_bytes) {
  FrameState f;
  f.frame = 123456789012ull;
  f.show_time_s = 3723.25;
  f.camera_position_m = {6371000.0 + 1.7, -12.5, 4.0e3};
  f.camera_orientation = glm::normalize(glm::dquat(0.9, 0.1, -0.3, 0.2));
  f.exposure = 12.5;
  f.sun_direction = glm::normalize(glm::dvec3(0.3, 0.4, 0.1));
  f.sun_angular_radius_rad = 0.004654793;
  for (std::size_t i = 0; i < wavelengths; ++i) f.sun_irradiance_W_m2_nm.push_back(1.5 + 0.01 * double(i));
  for (std::size_t i = 0; i < atmospheres; ++i) {
    std::string name = i == 0 ? "Earth" : "body-" + std::to_string(i);
    if (name_bytes > 0) name = std::string(name_bytes, static_cast<char>('a' + i));
    f.atmospheres.push_back({name, pattern<32>(static_cast<std::uint8_t>(40 + i)), 100 + i});
  }
  f.render_flags = kRenderSunDisc | kRenderLimbDarkening | kRenderMultipleScattering;
  f.fade = {0.375, glm::dvec3(1.0, 0.25, 0.0)};
  return f;
}

}  // namespace

std::vector<Message> sample_messages() {
  std::vector<Message> out;
  out.push_back(Hello{kProtocolVersion, "dome-a", "node-3", pattern<32>(1)});
  out.push_back(Challenge{pattern<32>(2)});
  out.push_back(Authenticate{pattern<32>(3)});
  out.push_back(Welcome{3, pattern<32>(4), 1000, 250, 2000, 5'000'000'123ull});
  out.push_back(Reject{RejectReason::authentication_failed, "wrong shared secret"});
  out.push_back(sample_frame_state(3, 2, 0));
  out.push_back(RenderDone{123456789012ull, 8.25, 5000, 3, 16.5, 2});
  out.push_back(Present{123456789012ull});
  out.push_back(TableAnnounce{pattern<32>(5), 10000, 4096, 3, pattern<32>(6)});
  TableChunk chunk{pattern<32>(5), 2, {}};
  chunk.bytes.resize(1808);
  std::iota(chunk.bytes.begin(), chunk.bytes.end(), std::uint8_t{9});
  out.push_back(chunk);
  out.push_back(TableReady{pattern<32>(5)});
  out.push_back(Heartbeat{987654321ull});
  out.push_back(Goodbye{"shutting down: show ended"});
  out.push_back(AtmosphereDefinition{"Mars", pattern<32>(7), R"({"zenith_atmosphere": 1, "mode": "standard"})"});
  out.push_back(PreviewRequest{123456789013ull, 64});
  Thumbnail thumbnail{123456789013ull, "top-left", 4, 3, {}};
  thumbnail.rgb.resize(4 * 3 * 3);
  std::iota(thumbnail.rgb.begin(), thumbnail.rgb.end(), std::uint8_t{200});
  out.push_back(thumbnail);
  out.push_back(Hello{kProtocolVersion, "dome-a", "standby@10.0.0.2:47101", pattern<32>(8), PeerRole::standby});
  out.push_back(Reject{RejectReason::wrong_role, "the cluster config has no standby"});
  out.push_back(FrameSchedule{123456789014ull, 7'000'016'666'667ull, 16'666'667ull});
  out.push_back(ClockPing{6'000'000'001ull});
  out.push_back(ClockPong{6'000'000'001ull, 7'000'000'250ull, 7'000'000'270ull});
  out.push_back(LinkCheck{5000, 10'000, 32ull << 20});
  LinkFill fill{3, {}};
  fill.bytes.resize(700);
  std::iota(fill.bytes.begin(), fill.bytes.end(), std::uint8_t{3});
  out.push_back(fill);
  out.push_back(LinkReport{500, 497, 6'000'000'000ull, 10'990'000'000ull, 180'000ull, 240'000ull, 900'000ull,
                           2'100'000ull, 11'000'000'000ull, 7'000'000'011ull, 1'796'000'000'000'000'000ull, 90'000ull,
                           -1.5, 0, 33'554'432ull, 32'505'856ull, 280'000'000ull});
  return out;
}

std::vector<Message> max_size_messages() {
  const std::string name(kMaxNameBytes, 'n');
  // Multi-byte UTF-8 counts bytes, not characters: 1024 bytes of 'é' (2 bytes each).
  std::string reason;
  while (reason.size() < kMaxReasonBytes) reason += "\xC3\xA9";
  std::vector<Message> out;
  out.push_back(Hello{kProtocolVersion, name, name, pattern<32>(11), PeerRole::standby});
  out.push_back(Challenge{pattern<32>(12)});
  out.push_back(Authenticate{pattern<32>(13)});
  out.push_back(Welcome{0xFFFFFFFFu, pattern<32>(14), ~std::uint64_t{0}, 0xFFFFFFFFu, 0xFFFFFFFFu, ~std::uint64_t{0}});
  out.push_back(Reject{static_cast<RejectReason>(0xFFFF), reason});
  FrameState f = sample_frame_state(kMaxWavelengths, kMaxAtmospheres, kMaxNameBytes);
  f.frame = ~std::uint64_t{0};
  f.render_flags = kKnownRenderFlags;
  f.sky = {true, 2488069.0, 0.5, pattern<32>(19)};  // the largest sky: a date, a catalogue identity
  out.push_back(f);
  out.push_back(RenderDone{~std::uint64_t{0}, 1e300, ~std::uint64_t{0}, ~std::uint64_t{0}, 1e300, ~std::uint64_t{0}});
  out.push_back(Present{~std::uint64_t{0}});
  out.push_back(TableAnnounce{pattern<32>(15), kMaxTableTotalBytes, static_cast<std::uint32_t>(kMaxTableChunkBytes),
                              static_cast<std::uint32_t>(kMaxTableTotalBytes / kMaxTableChunkBytes), pattern<32>(16)});
  TableChunk chunk{pattern<32>(15), 2047, {}};
  chunk.bytes.resize(kMaxTableChunkBytes);
  for (std::size_t i = 0; i < chunk.bytes.size(); ++i) chunk.bytes[i] = static_cast<std::uint8_t>(i * 31 + (i >> 8));
  out.push_back(std::move(chunk));
  out.push_back(TableReady{pattern<32>(17)});
  out.push_back(Heartbeat{~std::uint64_t{0}});
  out.push_back(Goodbye{reason});
  std::string json = "{\"description\": \"x";  // 18 bytes: even, so 2-byte characters end exactly at the limit
  while (json.size() < kMaxDefinitionBytes - 2) json += "\xC3\xA9";
  json += "\"}";
  out.push_back(AtmosphereDefinition{name, pattern<32>(18), json});
  out.push_back(PreviewRequest{~std::uint64_t{0}, kMaxThumbnailEdgePx});
  Thumbnail thumbnail{~std::uint64_t{0}, name, kMaxThumbnailEdgePx, kMaxThumbnailEdgePx, {}};
  thumbnail.rgb.resize(std::size_t{kMaxThumbnailEdgePx} * kMaxThumbnailEdgePx * 3);
  for (std::size_t i = 0; i < thumbnail.rgb.size(); ++i) thumbnail.rgb[i] = static_cast<std::uint8_t>(i * 13);
  out.push_back(std::move(thumbnail));
  out.push_back(FrameSchedule{~std::uint64_t{0}, ~std::uint64_t{0}, kMaxFramePeriodNs});
  out.push_back(ClockPing{~std::uint64_t{0}});
  out.push_back(ClockPong{~std::uint64_t{0}, ~std::uint64_t{0}, ~std::uint64_t{0}});
  out.push_back(LinkCheck{kMaxLinkCheckMs, kMaxLinkPingIntervalUs, kMaxLinkFillBytes});
  LinkFill fill{~std::uint32_t{0}, {}};
  fill.bytes.resize(kMaxTableChunkBytes);
  for (std::size_t i = 0; i < fill.bytes.size(); ++i) fill.bytes[i] = static_cast<std::uint8_t>(i * 7);
  out.push_back(std::move(fill));
  constexpr std::uint64_t kMax = ~std::uint64_t{0};
  out.push_back(LinkReport{~std::uint32_t{0}, ~std::uint32_t{0}, kMax, kMax, kMax, kMax, kMax, kMax, kMax, kMax, kMax,
                           kMax, 1e6, ~std::uint32_t{0}, kMax, kMax, kMax});
  return out;
}

}  // namespace zenith::cluster
