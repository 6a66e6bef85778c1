// When a show may start while its later table sets are prepared, without
// threads or clocks (cluster/master/show_start_rule.h; docs/cluster.md,
// "Shared tables").
#include "cluster/master/show_start_rule.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace zenith::cluster {
namespace {

using test::digest;

// The Earth sunrise show at 2 fps: three sets, first used at frames 0, 44 and 68.
std::vector<ShowStartRule::Set> sunrise(bool cached = false) {
  return {{digest(1), 0, cached, false}, {digest(2), 44, cached, false}, {digest(3), 68, cached, false}};
}

TEST(ShowStartRule, OfflineStartsOnceTheFirstFramesSetsAreReady) {
  ShowStartRule rule(sunrise(), 2.0, /*paced=*/false);
  EXPECT_FALSE(rule.may_start());
  rule.prepared(digest(2), 25.0, false);  // out of order: frame 0's set still missing
  EXPECT_FALSE(rule.may_start());
  rule.prepared(digest(1), 25.0, false);
  EXPECT_TRUE(rule.may_start()) << "set 3 still missing: its frames wait for it, frame 0 does not";
}

TEST(ShowStartRule, EveryFrameZeroSetIsNeeded) {
  // Two atmospheres in the first frame.
  ShowStartRule rule({{digest(1), 0, false, false}, {digest(2), 0, true, false}}, 30.0, false);
  rule.prepared(digest(1), 20.0, false);
  EXPECT_FALSE(rule.may_start());
  rule.prepared(digest(2), 0.5, true);
  EXPECT_TRUE(rule.may_start());
}

TEST(ShowStartRule, LiveWaitsUntilTheRestIsPredictedReadyInTime) {
  // Safety 1.5: a 25 s precompute predicts 37.5 s for each later set. Set 2 is
  // due 22 s after frame 0, set 3 at 34 s: neither fits, so frame 0 waits.
  ShowStartRule rule(sunrise(), 2.0, /*paced=*/true);
  rule.prepared(digest(1), 25.0, false);
  EXPECT_FALSE(rule.may_start());
  ASSERT_TRUE(rule.predicted_remaining_s());
  EXPECT_DOUBLE_EQ(*rule.predicted_remaining_s(), 75.0);
  rule.prepared(digest(2), 24.0, false);  // the longest so far stays 25 s
  EXPECT_FALSE(rule.may_start()) << "37.5 s for set 3 > 34 s";
  rule.prepared(digest(3), 26.0, false);
  EXPECT_TRUE(rule.may_start());
  EXPECT_DOUBLE_EQ(*rule.predicted_remaining_s(), 0.0);
}

TEST(ShowStartRule, LiveStartsEarlyWhenTheRestFitsBeforeItIsNeeded) {
  // At 2 fps set 2 is due at 22 s and set 3 at 34 s. Sets that take 10 s
  // (15 s predicted) are ready at 15 s and 30 s: in time.
  ShowStartRule rule(sunrise(), 2.0, true);
  rule.prepared(digest(1), 10.0, false);
  EXPECT_TRUE(rule.may_start());
  // 12 s (18 s predicted) still fits set 2 (18 <= 22) but not set 3 (36 > 34).
  ShowStartRule slower(sunrise(), 2.0, true);
  slower.prepared(digest(1), 12.0, false);
  EXPECT_FALSE(slower.may_start());
  // Without a safety margin it would fit (12 + 12 <= 34).
  ShowStartRule unsafe(sunrise(), 2.0, true, 1.0);
  unsafe.prepared(digest(1), 12.0, false);
  EXPECT_TRUE(unsafe.may_start());
}

TEST(ShowStartRule, AKindNeverMeasuredHasNoPrediction) {
  // Set 1 came from the cache in 0.4 s; sets 2 and 3 must be precomputed: how
  // long that takes is unknown until one was, so a live show waits.
  std::vector<ShowStartRule::Set> sets = sunrise();
  sets[0].cached = true;
  ShowStartRule rule(sets, 2.0, true);
  rule.prepared(digest(1), 0.4, true);
  EXPECT_FALSE(rule.predicted_remaining_s());
  EXPECT_FALSE(rule.may_start());
  rule.prepared(digest(2), 5.0, false);
  EXPECT_TRUE(rule.may_start()) << "set 3: 7.5 s predicted, due at 34 s";
  // Offline, no prediction is needed.
  ShowStartRule offline(sets, 2.0, false);
  offline.prepared(digest(1), 0.4, true);
  EXPECT_TRUE(offline.may_start());
}

TEST(ShowStartRule, CachedSetsArePredictedFromCacheReads) {
  ShowStartRule rule({{digest(1), 0, false, false}, {digest(2), 3, true, false}}, 30.0, true);
  rule.prepared(digest(1), 20.0, false);
  EXPECT_FALSE(rule.may_start()) << "no cache read measured yet";
  ShowStartRule measured({{digest(1), 0, true, false}, {digest(2), 60, true, false}}, 30.0, true);
  measured.prepared(digest(1), 0.5, true);
  EXPECT_TRUE(measured.may_start()) << "0.75 s predicted, due at 2 s";
}

TEST(ShowStartRule, RefusesNonsense) {
  EXPECT_THROW(ShowStartRule(sunrise(), 0.0, true), std::invalid_argument);
  EXPECT_THROW(ShowStartRule(sunrise(), 30.0, true, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::cluster
