// When a standby master takes over, without sockets or clock
// (cluster/standby/takeover_rule.h; docs/cluster.md, "Standby master").
#include "cluster/standby/takeover_rule.h"

#include <gtest/gtest.h>

namespace zenith::cluster {
namespace {

using Phase = TakeoverRule::Phase;

TEST(TakeoverRule, NeverTakesOverBeforeItFollowedTheActiveMaster) {
  TakeoverRule rule;
  EXPECT_EQ(rule.phase(), Phase::connecting);
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(rule.attempt_failed()) << "a master not up yet is no failure";
  rule.lost();  // cannot happen before a Welcome; changes nothing
  EXPECT_EQ(rule.phase(), Phase::connecting);
}

TEST(TakeoverRule, ALossThenAFailedAttemptIsATakeover) {
  TakeoverRule rule;
  EXPECT_FALSE(rule.welcomed());
  EXPECT_EQ(rule.phase(), Phase::following);
  EXPECT_FALSE(rule.attempt_failed()) << "following: an attempt cannot fail";
  rule.lost();
  EXPECT_EQ(rule.phase(), Phase::checking);
  EXPECT_TRUE(rule.attempt_failed()) << "refused, unreachable or no Welcome in time: the master is gone";
  EXPECT_EQ(rule.phase(), Phase::taking_over);
  EXPECT_FALSE(rule.attempt_failed()) << "once";
}

TEST(TakeoverRule, AWelcomeAfterALossMeansTheActiveMasterIsAlive) {
  TakeoverRule rule;
  (void)rule.welcomed();
  rule.lost();  // the standby stalled past the silence limit, or the network between the two dropped
  EXPECT_TRUE(rule.welcomed()) << "it was checking: a false alarm";
  EXPECT_EQ(rule.phase(), Phase::following);
  EXPECT_EQ(rule.false_alarms(), 1u);
  rule.lost();
  EXPECT_TRUE(rule.attempt_failed());
}

}  // namespace
}  // namespace zenith::cluster
