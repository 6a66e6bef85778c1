// The master's frame barrier without sockets (cluster/master/frame_barrier.h):
// the same decisions master.cpp makes on RenderDone, the barrier timeout and
// closed connections (docs/cluster.md, "The frame barrier").
#include "cluster/master/frame_barrier.h"

#include <gtest/gtest.h>

#include <vector>

namespace zenith::cluster {
namespace {

using Report = FrameBarrier::Report;
using Ids = std::vector<FrameBarrier::NodeId>;

/// A barrier with frame `frame` in flight on nodes 1, 2 and 3.
FrameBarrier three_nodes_at(std::uint64_t frame) {
  FrameBarrier barrier;
  barrier.begin(frame, barrier.participants_among({1, 2, 3}));
  return barrier;
}

/// Frame 0 on nodes 1, 2 and 3 released without node 2's report (the barrier
/// timed out): node 2 lags.
FrameBarrier node_2_dropped_from_frame_0() {
  FrameBarrier barrier = three_nodes_at(0);
  barrier.on_render_done(1, 0);
  barrier.on_render_done(3, 0);
  barrier.drop_unfinished();
  barrier.release();
  return barrier;
}

TEST(FrameBarrier, StartsAtFrameZeroWithNothingInFlight) {
  const FrameBarrier barrier;
  EXPECT_EQ(barrier.frame(), 0u);
  EXPECT_FALSE(barrier.in_flight());
  EXPECT_FALSE(barrier.complete());
  EXPECT_EQ(barrier.next_boundary(), 0u);
  EXPECT_EQ(barrier.participants_among({4, 2, 7}), (Ids{4, 2, 7}));
}

TEST(FrameBarrier, AStandbyTakingOverContinuesTheNumbering) {
  FrameBarrier barrier;
  barrier.start_at(42);
  EXPECT_EQ(barrier.frame(), 42u);
  EXPECT_EQ(barrier.next_boundary(), 42u);
  barrier.begin(barrier.frame(), {1});
  EXPECT_THROW(barrier.start_at(7), std::logic_error) << "not with a frame in flight";
  EXPECT_EQ(barrier.on_render_done(1, 42), Report::counted);
  EXPECT_EQ(barrier.release().frame, 42u);
  EXPECT_EQ(barrier.frame(), 43u);
}

TEST(FrameBarrier, ReleasesOnlyWhenEveryParticipantReported) {
  FrameBarrier barrier = three_nodes_at(0);
  EXPECT_TRUE(barrier.in_flight());
  EXPECT_EQ(barrier.participant_count(), 3u);
  EXPECT_EQ(barrier.next_boundary(), 1u);
  EXPECT_EQ(barrier.on_render_done(2, 0), Report::counted);
  EXPECT_FALSE(barrier.complete());
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::counted);
  EXPECT_FALSE(barrier.complete());
  EXPECT_EQ(barrier.on_render_done(3, 0), Report::counted);
  EXPECT_TRUE(barrier.complete());

  const FrameBarrier::Release release = barrier.release();
  EXPECT_EQ(release.frame, 0u);
  EXPECT_EQ(release.present_to, (Ids{1, 2, 3}));
  EXPECT_FALSE(barrier.in_flight());
  EXPECT_FALSE(barrier.complete());
  EXPECT_EQ(barrier.frame(), 1u);
  EXPECT_EQ(barrier.next_boundary(), 1u);
}

TEST(FrameBarrier, FramesFollowEachOther) {
  FrameBarrier barrier;
  for (std::uint64_t frame = 0; frame < 5; ++frame) {
    ASSERT_EQ(barrier.frame(), frame);
    barrier.begin(barrier.frame(), {7});
    EXPECT_EQ(barrier.on_render_done(7, frame), Report::counted);
    ASSERT_TRUE(barrier.complete());
    EXPECT_EQ(barrier.release().frame, frame);
  }
  EXPECT_EQ(barrier.frame(), 5u);
}

TEST(FrameBarrier, FrameNumbersMayComeFromAFeed) {
  FrameBarrier barrier;
  barrier.begin(41, {1});
  EXPECT_EQ(barrier.frame(), 41u);
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::ignored);
  EXPECT_EQ(barrier.on_render_done(1, 41), Report::counted);
  EXPECT_EQ(barrier.release().frame, 41u);
  EXPECT_EQ(barrier.frame(), 42u);
}

TEST(FrameBarrier, IgnoresReportsOfOtherFrames) {
  FrameBarrier barrier = three_nodes_at(5);
  EXPECT_EQ(barrier.on_render_done(1, 4), Report::ignored);  // stale
  EXPECT_EQ(barrier.on_render_done(1, 6), Report::ignored);  // not sent yet
  EXPECT_EQ(barrier.on_render_done(2, 5), Report::counted);
  EXPECT_EQ(barrier.on_render_done(3, 5), Report::counted);
  EXPECT_FALSE(barrier.complete()) << "node 1 has not reported frame 5";
  EXPECT_EQ(barrier.on_render_done(1, 5), Report::counted);
  EXPECT_TRUE(barrier.complete());
}

TEST(FrameBarrier, IgnoresReportsFromNodesOutsideTheFrame) {
  FrameBarrier barrier;
  barrier.begin(0, {1, 2});
  EXPECT_EQ(barrier.on_render_done(9, 0), Report::ignored);  // joined after the frame started
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::counted);
  EXPECT_FALSE(barrier.complete());
}

TEST(FrameBarrier, IgnoresReportsBetweenFrames) {
  FrameBarrier barrier;
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::ignored);
  barrier.begin(0, {1});
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::counted);
  barrier.release();
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::ignored);  // a duplicate after Present
  EXPECT_FALSE(barrier.in_flight());
  EXPECT_EQ(barrier.frame(), 1u);
}

TEST(FrameBarrier, ADuplicateReportCountsOnce) {
  FrameBarrier barrier = three_nodes_at(0);
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::counted);
  EXPECT_EQ(barrier.on_render_done(1, 0), Report::counted);
  EXPECT_FALSE(barrier.complete()) << "two reports of one node do not stand for another node";
  EXPECT_EQ(barrier.participant_count(), 3u);
}

TEST(FrameBarrier, TimeoutDropsTheUnfinishedAndPresentsToTheOthers) {
  FrameBarrier barrier = three_nodes_at(7);
  EXPECT_EQ(barrier.on_render_done(1, 7), Report::counted);
  EXPECT_EQ(barrier.on_render_done(3, 7), Report::counted);
  EXPECT_EQ(barrier.drop_unfinished(), (Ids{2}));
  EXPECT_TRUE(barrier.is_lagging(2));
  EXPECT_FALSE(barrier.is_lagging(1));
  EXPECT_TRUE(barrier.complete());
  const FrameBarrier::Release release = barrier.release();
  EXPECT_EQ(release.frame, 7u);
  EXPECT_EQ(release.present_to, (Ids{1, 3})) << "Present only to nodes that finished the frame";
}

TEST(FrameBarrier, TimeoutWithNoReportPresentsToNobody) {
  FrameBarrier barrier = three_nodes_at(0);
  EXPECT_EQ(barrier.drop_unfinished(), (Ids{1, 2, 3}));
  EXPECT_TRUE(barrier.complete());
  EXPECT_TRUE(barrier.release().present_to.empty());
  EXPECT_EQ(barrier.frame(), 1u);
  EXPECT_TRUE(barrier.participants_among({1, 2, 3}).empty());
}

TEST(FrameBarrier, ALaggingNodeIsLeftOutOfLaterFrames) {
  FrameBarrier barrier = node_2_dropped_from_frame_0();
  const Ids participants = barrier.participants_among({1, 2, 3});
  EXPECT_EQ(participants, (Ids{1, 3}));
  barrier.begin(barrier.frame(), participants);
  EXPECT_EQ(barrier.on_render_done(1, 1), Report::counted);
  EXPECT_EQ(barrier.on_render_done(3, 1), Report::counted);
  EXPECT_TRUE(barrier.complete()) << "a dropped node no longer blocks the barrier";
  EXPECT_EQ(barrier.release().present_to, (Ids{1, 3}));
}

TEST(FrameBarrier, ALateReportDuringALaterFrameRejoinsAtTheNextBoundary) {
  FrameBarrier barrier = node_2_dropped_from_frame_0();
  barrier.begin(barrier.frame(), barrier.participants_among({1, 2, 3}));  // frame 1 on 1 and 3

  EXPECT_EQ(barrier.on_render_done(2, 0), Report::rejoins);  // frame 0, late
  EXPECT_FALSE(barrier.is_lagging(2));
  EXPECT_EQ(barrier.next_boundary(), 2u);
  EXPECT_EQ(barrier.participant_count(), 2u) << "it does not join the frame in flight";
  EXPECT_EQ(barrier.on_render_done(2, 1), Report::ignored);  // it was never sent frame 1
  barrier.on_render_done(1, 1);
  barrier.on_render_done(3, 1);
  ASSERT_TRUE(barrier.complete());
  EXPECT_EQ(barrier.release().present_to, (Ids{1, 3}));

  EXPECT_EQ(barrier.participants_among({1, 2, 3}), (Ids{1, 2, 3})) << "back at frame 2";
}

TEST(FrameBarrier, ALateReportBetweenFramesRejoins) {
  FrameBarrier barrier = three_nodes_at(3);
  barrier.on_render_done(1, 3);
  barrier.on_render_done(2, 3);
  barrier.drop_unfinished();
  barrier.release();
  EXPECT_EQ(barrier.on_render_done(3, 3), Report::rejoins);  // no frame in flight: even frame 3 (now < 4)
  EXPECT_EQ(barrier.participants_among({1, 2, 3}), (Ids{1, 2, 3}));
}

TEST(FrameBarrier, ALaggingNodeReportingTheFrameInFlightStaysOut) {
  FrameBarrier barrier;
  barrier.begin(4, {1, 2});
  barrier.on_render_done(1, 4);
  barrier.drop_unfinished();  // 2 lags
  barrier.release();
  barrier.begin(5, barrier.participants_among({1, 2}));
  EXPECT_EQ(barrier.on_render_done(2, 5), Report::ignored_lagging);
  EXPECT_EQ(barrier.on_render_done(2, 9), Report::ignored_lagging);
  EXPECT_TRUE(barrier.is_lagging(2));
  EXPECT_EQ(barrier.participant_count(), 1u);
}

TEST(FrameBarrier, AClosedParticipantNoLongerBlocks) {
  FrameBarrier barrier = three_nodes_at(2);
  barrier.on_render_done(1, 2);
  barrier.on_render_done(2, 2);
  EXPECT_FALSE(barrier.complete());
  EXPECT_TRUE(barrier.remove(3));
  EXPECT_TRUE(barrier.complete());
  EXPECT_EQ(barrier.release().present_to, (Ids{1, 2}));
}

TEST(FrameBarrier, ClosingEveryParticipantCompletesTheFrameOnNobody) {
  FrameBarrier barrier;
  barrier.begin(0, {1});
  EXPECT_TRUE(barrier.remove(1));
  EXPECT_TRUE(barrier.complete());
  const FrameBarrier::Release release = barrier.release();
  EXPECT_EQ(release.frame, 0u);
  EXPECT_TRUE(release.present_to.empty());
}

TEST(FrameBarrier, ClosingANodeOutsideTheFrameChangesNothing) {
  FrameBarrier barrier = three_nodes_at(0);
  EXPECT_FALSE(barrier.remove(9));
  EXPECT_EQ(barrier.participant_count(), 3u);
  EXPECT_FALSE(barrier.complete());
  barrier.on_render_done(1, 0);
  barrier.on_render_done(2, 0);
  barrier.on_render_done(3, 0);
  barrier.release();
  EXPECT_FALSE(barrier.remove(1)) << "no frame in flight";
}

TEST(FrameBarrier, AClosedLaggingNodeIsForgotten) {
  FrameBarrier barrier;
  barrier.begin(0, {1, 2});
  barrier.on_render_done(1, 0);
  barrier.drop_unfinished();
  barrier.release();
  EXPECT_TRUE(barrier.is_lagging(2));
  EXPECT_FALSE(barrier.remove(2));  // not in frame 1's barrier, nothing to complete
  EXPECT_FALSE(barrier.is_lagging(2));
}

TEST(FrameBarrier, ADroppedReportArrivingAfterTheTimeoutRejoins) {
  // The timeout fired before node 2's RenderDone 0 arrived; the report
  // crosses Present 0 and arrives while frame 1 is in flight without it.
  FrameBarrier barrier;
  barrier.begin(0, {1, 2});
  barrier.on_render_done(1, 0);
  EXPECT_EQ(barrier.drop_unfinished(), (Ids{2}));
  barrier.release();
  barrier.begin(1, barrier.participants_among({1, 2}));
  EXPECT_EQ(barrier.participant_count(), 1u);
  EXPECT_EQ(barrier.on_render_done(2, 0), Report::rejoins);
}

}  // namespace
}  // namespace zenith::cluster
