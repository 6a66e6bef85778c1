// The node's estimate of the master's clock (cluster/link/clock_sync.h),
// driven by simulated clocks: an offset, a drift, a step, asymmetric and
// delayed legs. The true offset is known, so every estimate is checked
// against it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "cluster/link/clock_sync.h"

namespace zenith::cluster {
namespace {

/// A master clock running at (1 + drift) of the node's, `offset` ahead at node time 0.
struct SimulatedMaster {
  double offset_ns = 0.0;
  double drift = 0.0;
  std::int64_t at(std::int64_t node_ns) const {
    return static_cast<std::int64_t>(std::llround(static_cast<double>(node_ns) * (1.0 + drift) + offset_ns));
  }
  std::int64_t true_offset(std::int64_t node_ns) const { return at(node_ns) - node_ns; }
};

/// One exchange at node time t: `out_ns` to the master, 20 µs there, `back_ns` home.
ClockSync::Exchange exchange(const SimulatedMaster& m, std::int64_t t, std::int64_t out_ns, std::int64_t back_ns) {
  const std::int64_t t2 = m.at(t + out_ns);
  return {t, t2, t2 + 20'000, t + out_ns + 20'000 + back_ns};
}

TEST(ClockSync, SymmetricExchangesGiveTheOffsetExactly) {
  const SimulatedMaster master{3.7e9, 0.0};
  ClockSync sync;
  EXPECT_FALSE(sync.has_estimate());
  for (int k = 0; k < 8; ++k) sync.add(exchange(master, 1'000'000'000LL + k * 100'000'000LL, 150'000, 150'000));
  EXPECT_TRUE(sync.synchronized());
  EXPECT_NEAR(static_cast<double>(sync.offset_ns(2'000'000'000)), 3.7e9, 1.0);
  EXPECT_EQ(sync.round_trip_ns(), 300'000);
  EXPECT_EQ(sync.to_node(master.at(2'500'000'000)), 2'500'000'000);
}

TEST(ClockSync, TheSeedIsTheOneWayEstimateUntilTheFirstExchange) {
  ClockSync sync;
  sync.seed(5'000'400'000, 1'000'000'000);  // the Welcome left the master 0.4 ms before it arrived
  EXPECT_TRUE(sync.has_estimate());
  EXPECT_FALSE(sync.synchronized());
  EXPECT_EQ(sync.offset_ns(1'000'000'000), 4'000'400'000);
}

// A queue on one leg (a retransmission, a busy switch) biases that exchange by
// half its extra delay; the least-delay filter keeps the clean ones.
TEST(ClockSync, DelayedLegsDoNotMoveTheEstimate) {
  const SimulatedMaster master{-2.5e8, 0.0};
  std::mt19937 random(7);
  std::uniform_int_distribution<int> pick(0, 3);
  ClockSync sync;
  for (int k = 0; k < 400; ++k) {
    const std::int64_t t = 1'000'000'000LL + k * 100'000'000LL;
    // Three of four exchanges have one leg held up 1 to 200 ms.
    const int kind = pick(random);
    const std::int64_t extra = 1'000'000LL * (1 + (k * 37) % 200);
    sync.add(exchange(master, t, 100'000 + (kind == 1 ? extra : 0), 100'000 + (kind == 2 || kind == 3 ? extra : 0)));
  }
  EXPECT_NEAR(static_cast<double>(sync.offset_ns(41'000'000'000)), -2.5e8, 1e3);  // within 1 µs
  EXPECT_EQ(sync.steps(), 0u);
}

// Crystal oscillators differ by tens of ppm: 100 ppm is 6 ms a minute. The
// fitted line follows it, so the estimate between exchanges stays exact.
TEST(ClockSync, ADriftingClockIsFollowed) {
  const SimulatedMaster master{1e6, 100e-6};
  ClockSync sync;
  std::int64_t t = 0;
  for (int k = 0; k < 600; ++k, t += 100'000'000LL) sync.add(exchange(master, t, 200'000, 200'000));
  EXPECT_NEAR(sync.drift_ppm(), 100.0, 0.5);
  // 2 s past the last exchange (a lost run of pings): still within 20 µs.
  const std::int64_t later = t + 2'000'000'000LL;
  EXPECT_NEAR(static_cast<double>(sync.offset_ns(later)), static_cast<double>(master.true_offset(later)), 2e4);
  EXPECT_NEAR(static_cast<double>(sync.to_node(master.at(later))), static_cast<double>(later), 2e4);
}

// Two seconds of exchanges over a jittery link (5 ± 1 ms each way, as the
// rig's delaying relay makes it) whose offsets ramp by chance from 1 ms below
// the truth to 1 ms above. A straight line through the kept samples says
// ~1000 ppm, which would carry the estimate 2 ms off a second later; clocks
// differ by tens of ppm, so the estimate keeps to the samples' mean.
TEST(ClockSync, TwoSecondsOfJitteryExchangesInventNoDrift) {
  const SimulatedMaster master{4e8, 0.0};
  ClockSync sync;
  std::int64_t t = 0;
  for (int k = 0; k < 20; ++k, t += 100'000'000LL) {
    // θ is off by (out − back) / 2: from −1 ms at k = 0 to +1 ms at k = 19, δ always 10 ms.
    const std::int64_t skew = -2'000'000 + k * 4'000'000 / 19;
    sync.add(exchange(master, t, 5'000'000 + skew / 2, 5'000'000 - skew / 2));
  }
  EXPECT_LT(std::abs(sync.drift_ppm()), 500.0);
  const std::int64_t later = t + 1'000'000'000LL;
  EXPECT_NEAR(static_cast<double>(sync.offset_ns(later)), static_cast<double>(master.true_offset(later)), 1.1e6);
}

TEST(ClockSync, AStepStartsTheEstimateAfreshAfterThreeExchangesSayIt) {
  SimulatedMaster master{0.0, 0.0};
  ClockSync sync;
  std::int64_t t = 0;
  for (int k = 0; k < 100; ++k, t += 100'000'000LL) sync.add(exchange(master, t, 100'000, 100'000));
  master.offset_ns = 50e6;  // the node's clock was set back 50 ms
  sync.add(exchange(master, t, 100'000, 100'000));
  t += 100'000'000LL;
  EXPECT_NEAR(static_cast<double>(sync.offset_ns(t)), 0.0, 1e3) << "one odd exchange is not a step";
  for (int k = 0; k < 3; ++k, t += 100'000'000LL) sync.add(exchange(master, t, 100'000, 100'000));
  EXPECT_EQ(sync.steps(), 1u);
  EXPECT_NEAR(static_cast<double>(sync.offset_ns(t)), 50e6, 1e3);
}

// On a loaded host the very first exchange may wait 10 ms on one leg: its θ is
// 5 ms off, within its own bound. The clean exchanges after it disagree with
// it by more than 2 ms, yet their bounds overlap: no step, a better estimate.
TEST(ClockSync, AHeldUpFirstExchangeIsAPoorEstimateNotAStep) {
  const SimulatedMaster master{7e8, 0.0};
  ClockSync sync;
  std::int64_t t = 0;
  sync.add(exchange(master, t, 10'000'000, 100'000));
  for (int k = 1; k < 20; ++k) sync.add(exchange(master, t += 10'000'000LL, 100'000, 100'000));
  EXPECT_EQ(sync.steps(), 0u);
  EXPECT_NEAR(static_cast<double>(sync.offset_ns(t)), 7e8, 1e3);
}

TEST(ClockSync, ImpossibleExchangesAreIgnored) {
  ClockSync sync;
  sync.add({1000, 5000, 4000, 2000});  // the master answered before it received
  sync.add({1000, 5000, 5100, 900});   // arrived before it left
  sync.add({1000, 5000, 9000, 2000});  // held longer on the master than the whole round trip
  EXPECT_FALSE(sync.synchronized());
  EXPECT_EQ(sync.exchanges(), 0u);
}

}  // namespace
}  // namespace zenith::cluster
