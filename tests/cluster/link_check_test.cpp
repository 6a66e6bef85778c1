// The link check's pure parts (docs/cluster.md, "Checking the network"): the
// node's ping counts and fill bookkeeping, the verdict's closed forms, the
// table and the JSON.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "cluster/check/link_check_report.h"
#include "cluster/check/link_verdict.h"
#include "cluster/link/clock_sync.h"
#include "cluster/link/ping_probe.h"
#include "cluster/node/link_check_answer.h"

namespace zenith::cluster {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

TEST(PingProbe, CountsDistinctAnswersAndTheirRoundTripPercentiles) {
  PingProbe probe;
  for (std::uint64_t k = 1; k <= 100; ++k) probe.sent(1000 * k);
  // Pings 1..98 answered with round trips of k µs; 99 and 100 lost.
  for (std::uint64_t k = 1; k <= 98; ++k) EXPECT_TRUE(probe.answered(1000 * k, 1000 * k));
  EXPECT_FALSE(probe.answered(1000 * 5, 1)) << "a duplicated pong counts once";
  EXPECT_FALSE(probe.answered(777, 1)) << "a pong of a ping the probe never sent counts nothing";
  const PingProbe::Summary s = probe.summary();
  EXPECT_EQ(s.pings, 100u);
  EXPECT_EQ(s.pongs, 98u);
  EXPECT_EQ(s.first_ping_ns, 1000u);
  EXPECT_EQ(s.last_ping_ns, 100'000u);
  // Nearest rank over 98 samples 1..98 µs: median ⌈0.5·98⌉ = 49th, 99th percentile ⌈0.99·98⌉ = 98th.
  EXPECT_EQ(s.round_trip_min_ns, 1000u);
  EXPECT_EQ(s.round_trip_p50_ns, 49'000u);
  EXPECT_EQ(s.round_trip_p99_ns, 98'000u);
  EXPECT_EQ(s.round_trip_max_ns, 98'000u);
}

TEST(PingProbe, WithoutAnswersTheRoundTripsAreZero) {
  PingProbe probe;
  probe.sent(5);
  const PingProbe::Summary s = probe.summary();
  EXPECT_EQ(s.pings, 1u);
  EXPECT_EQ(s.pongs, 0u);
  EXPECT_EQ(s.round_trip_p99_ns, 0u);
}

TEST(LinkCheckAnswer, ReportsOnceThePingsAreOverAndEveryFillByteCame) {
  LinkCheckAnswer answer;
  const Clock::time_point t0{std::chrono::seconds(100)};
  answer.start(LinkCheck{1000, 10'000, 3000}, t0);
  EXPECT_EQ(answer.pings_until(), t0 + 1000ms);
  EXPECT_FALSE(answer.complete(t0 + 2000ms)) << "no fill yet";
  answer.on_fill(LinkFill{0, std::vector<std::uint8_t>(1000)}, t0 + 900ms);
  EXPECT_EQ(answer.pings_until(), t0 + 900ms) << "the first fill ends the pings: they would time its queue";
  EXPECT_THROW(answer.on_fill(LinkFill{2, std::vector<std::uint8_t>(1000)}, t0 + 950ms), std::runtime_error);
  answer.on_fill(LinkFill{1, std::vector<std::uint8_t>(1000)}, t0 + 1000ms);
  EXPECT_FALSE(answer.complete(t0 + 1000ms));
  answer.on_fill(LinkFill{2, std::vector<std::uint8_t>(1000)}, t0 + 1100ms);
  EXPECT_THROW(answer.on_fill(LinkFill{3, std::vector<std::uint8_t>(1)}, t0 + 1100ms), std::runtime_error)
      << "more than the check named";
  EXPECT_TRUE(answer.complete(t0 + 1100ms));

  ClockSync clock;
  clock.add({1'000'000, 5'000'100, 5'000'200, 1'000'400});  // δ = 300 ns, θ = 4 000 000 − 50 ns
  PingProbe probe;
  probe.sent(1'000'000);
  probe.answered(1'000'000, 300);
  const LinkReport r = answer.report(probe.summary(), clock, 2'000'000, 1'700'000'000'000'000'000ull);
  EXPECT_FALSE(answer.running());
  EXPECT_EQ(r.pings_sent, 1u);
  EXPECT_EQ(r.pongs_received, 1u);
  EXPECT_EQ(r.fill_bytes, 3000u);
  EXPECT_EQ(r.fill_timed_bytes, 2000u) << "the bytes after the first fill, over its arrival to the last's";
  EXPECT_EQ(r.fill_ns, 200'000'000u);
  EXPECT_EQ(r.clock_uncertainty_ns, 150u);
  EXPECT_EQ(r.master_steady_ns, 2'000'000u + 4'000'000u - 50u);
  EXPECT_EQ(r.node_wall_ns, 1'700'000'000'000'000'000ull);
  EXPECT_NO_THROW(encode(r)) << "a report the encoder takes";
}

TEST(LinkCheckAnswer, AFillWithoutACheckIsAnError) {
  LinkCheckAnswer answer;
  EXPECT_THROW(answer.on_fill(LinkFill{0, {1}}, Clock::now()), std::runtime_error);
  answer.start(LinkCheck{100, 1000, 0}, Clock::time_point{});
  EXPECT_TRUE(answer.complete(Clock::time_point{} + 100ms)) << "no fill asked: done when the pings are";
}

LinkMeasurement healthy() {
  LinkMeasurement m;
  m.node = "render-1";
  m.address = "198.18.0.11:40000";
  m.connected = m.reported = true;
  m.pings_sent = m.pings_heard = m.pongs = 500;
  m.round_trip_min_ms = 0.1;
  m.round_trip_p50_ms = 0.2;
  m.round_trip_p99_ms = 0.4;
  m.round_trip_max_ms = 0.9;
  m.clock_uncertainty_ms = 0.05;
  m.throughput_bits_per_s = 940e6;
  m.fill_bytes = 32 << 20;
  m.fill_seconds = 0.29;
  return m;
}

TEST(LinkVerdict, CopiesInTimeFollowTheClosedForm) {
  // Copy j (sent j half periods ahead: one at each tick, one half a period after) is in time when
  // j·T/2 − d ≥ T/2: the last, half a period ahead, never is; the other five of six are on a switch.
  EXPECT_EQ(copies_in_time(0.2, {30, 3, 0}), 5);
  EXPECT_EQ(copies_in_time(20.0, {60, 3, 0}), 3);  // T = 16.7: j ≥ 3.4
  EXPECT_EQ(copies_in_time(40.0, {60, 3, 0}), 1);  // j ≥ 5.8
  EXPECT_EQ(copies_in_time(60.0, {60, 3, 0}), 0);  // j ≥ 8.2
  EXPECT_EQ(copies_in_time(0.0, {60, 0, 0}), 0) << "the barrier sends no copies";
}

TEST(LinkVerdict, AHealthyLinkIsOk) {
  const LinkVerdict v = judge(healthy(), {60, 3, 100e6});
  EXPECT_EQ(v.grade, LinkGrade::ok);
  EXPECT_TRUE(v.reasons.empty());
  EXPECT_EQ(v.copies_in_time, 5);
  EXPECT_EQ(v.held_frames_per_hour, 0.0);
  EXPECT_EQ(v.lookahead_for_two_copies, 2);
}

TEST(LinkVerdict, LossGivesTheExpectedHeldFramesAnHour) {
  LinkMeasurement m = healthy();
  m.pongs = 475;  // 5 % toward the node
  LinkVerdict v = judge(m, {30, 3, 100e6});
  // 3600 · 30 · 0.05⁵ = 0.034 frames an hour with five copies in time, but a
  // loss a dedicated switch never has: a warning, not a failure.
  EXPECT_NEAR(v.held_frames_per_hour, 0.03375, 1e-9);
  EXPECT_EQ(v.grade, LinkGrade::warn);
  ASSERT_EQ(v.reasons.size(), 1u);
  EXPECT_NE(v.reasons[0].find("5.0 % of the datagrams lost (toward it 5.0 %, from it 0.0 %)"), std::string::npos)
      << v.reasons[0];
  EXPECT_NE(v.reasons[0].find("frames an hour held a period longer (5 of 6 copies in time)"), std::string::npos)
      << v.reasons[0];
  m.pongs = 400;  // 20 %: 3600 · 30 · 0.2⁵ = 34.6 an hour, a warning
  v = judge(m, {30, 3, 100e6});
  EXPECT_NEAR(v.held_frames_per_hour, 34.56, 1e-9);
  EXPECT_EQ(v.grade, LinkGrade::warn);
  m.pongs = 350;  // 30 %: 262 an hour, more than one a minute
  v = judge(m, {30, 3, 100e6});
  EXPECT_NEAR(v.held_frames_per_hour, 262.44, 1e-9);
  EXPECT_EQ(v.grade, LinkGrade::fail);
  m.pongs = 495;  // 1 %: 1.1e-5 an hour, within what a few lost pings in a check can be
  EXPECT_EQ(judge(m, {30, 3, 100e6}).grade, LinkGrade::ok);
  // A cut link: the master heard a third fewer pings, and answered all it heard.
  m.pongs = m.pings_heard = 333;
  v = judge(m, {30, 3, 100e6});
  EXPECT_NEAR(v.held_frames_per_hour, 3600.0 * 30 * std::pow(0.334, 5), 1e-6);
  EXPECT_EQ(v.grade, LinkGrade::fail);
  m.pongs = m.pings_heard = 495;
  // Under the barrier any loss freezes the dome.
  v = judge(m, {30, 0, 100e6});
  EXPECT_EQ(v.grade, LinkGrade::fail);
  EXPECT_NE(v.reasons[0].find("freezes every projector"), std::string::npos) << v.reasons[0];
}

TEST(LinkVerdict, ALongRoundTripNeedsMoreLookahead) {
  LinkMeasurement m = healthy();
  m.round_trip_p99_ms = 120;  // one way 60 ms at 60 Hz: no copy of three in time
  const LinkVerdict v = judge(m, {60, 3, 100e6});
  EXPECT_EQ(v.grade, LinkGrade::fail);
  EXPECT_EQ(v.copies_in_time, 0);
  // j ≥ 1 + 2 · 60 / 16.67 = 8.2: copies from j = 9 on (4.5 periods ahead), two of them (j = 9, 10) with a
  // lookahead of 5.
  EXPECT_EQ(v.lookahead_for_two_copies, 5);
  EXPECT_NE(v.reasons[0].find("use 5"), std::string::npos) << v.reasons[0];
}

TEST(LinkVerdict, UnreachableSilentOrFirewalledNodesFail) {
  LinkMeasurement never;
  never.node = "render-3";
  never.problem = "nothing connected";
  EXPECT_EQ(judge(never, {}).grade, LinkGrade::fail);
  LinkMeasurement udp_closed = healthy();
  udp_closed.pings_heard = udp_closed.pongs = 0;
  const LinkVerdict v = judge(udp_closed, {60, 3, 100e6});
  EXPECT_EQ(v.grade, LinkGrade::fail);
  EXPECT_NE(v.reasons[0].find("UDP port"), std::string::npos);
  EXPECT_EQ(judge(udp_closed, {60, 0, 100e6}).grade, LinkGrade::warn) << "the barrier needs no datagrams";
}

TEST(LinkVerdict, ClockThroughputAndWallClockFindingsWarn) {
  LinkMeasurement m = healthy();
  m.clock_uncertainty_ms = 0.6;
  m.throughput_bits_per_s = 50e6;
  m.wall_clock_offset_ms = -2500;
  m.clock_steps = 1;
  const LinkVerdict v = judge(m, {60, 3, 100e6});
  EXPECT_EQ(v.grade, LinkGrade::warn);
  EXPECT_EQ(v.reasons.size(), 4u);
  m.clock_uncertainty_ms = 9;  // more than half a period at 60 Hz
  const LinkVerdict f = judge(m, {60, 3, 100e6});
  EXPECT_EQ(f.grade, LinkGrade::fail);
  EXPECT_NE(f.reasons[0].find("half a frame"), std::string::npos) << "failures come first: " << f.reasons[0];
}

TEST(LinkCheckReport, TheTableAndTheJsonSayTheVerdictPerNodeAndOverall) {
  LinkCheckOptions options;
  options.config.name = "dome";
  options.config.frame_rate_hz = 60;
  options.config.lookahead_frames = 3;
  LinkMeasurement lossy = healthy();
  lossy.node = "render-2";
  lossy.pongs = 475;
  LinkMeasurement gone;
  gone.node = "render-3";
  gone.problem = "nothing connected as 'render-3' within 30 s";
  const LinkCheckReport r = make_report(options, {healthy(), lossy, gone});
  EXPECT_EQ(r.grade(), LinkGrade::fail);
  const std::string table = format_table(r);
  for (const char* text : {"render-1", "render-2", "render-3", "0.10/0.20/0.40", "940", "verdict: FAIL",
                           "render-3: never connected: nothing connected as 'render-3' within 30 s"})
    EXPECT_NE(table.find(text), std::string::npos) << text << "\n" << table;
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j["verdict"], "fail");
  EXPECT_EQ(j["lookahead_frames"], 3);
  EXPECT_EQ(j["nodes"][0]["verdict"], "ok");
  EXPECT_EQ(j["nodes"][1]["verdict"], "warn");
  EXPECT_NEAR(j["nodes"][1]["datagrams"]["loss_to_node"].get<double>(), 0.05, 1e-12);
  EXPECT_NEAR(j["nodes"][1]["held_frames_per_hour"].get<double>(), 3600 * 60 * std::pow(0.05, 5), 1e-9);
  EXPECT_NEAR(j["nodes"][0]["throughput_mbit_s"].get<double>(), 940, 1e-9);
  EXPECT_EQ(j["nodes"][2]["connected"], false);
  EXPECT_EQ(j["nodes"][2]["problem"], "nothing connected as 'render-3' within 30 s");
}

}  // namespace
}  // namespace zenith::cluster
