#pragma once
// The master's frame loop (docs/cluster.md, "Frame barrier"; docs/shows.md,
// "Playback"): frame 0 starts once the tables allow it and every configured
// node is ready (or the wait for nodes is over); each frame is the feed's,
// the show's or the default show's, shaped by the operator (OperatorDesk),
// held until every participant holds its table sets (TableSchedule), then
// sent; the RenderDone of every participant (or the barrier timeout, which
// drops the late ones) releases Present; the next frame starts at the frame
// rate (live) or at once (offline). The master stops after its frames, at the
// end of a show or of a feed. On the master's io_context, its timers only.
//
// Scheduled frames (a paced show with timing.lookahead_frames > 0; docs/cluster.md,
// "The frame schedule"): after the warm-up frame 0, no barrier. Frame n is
// sent lookahead periods before its moment t0 + n / rate, with that moment
// (FrameSchedule), to every ready node — as a datagram to the nodes heard on
// UDP, again at every tick until its moment, else on TCP — and each node
// presents it at that moment on its own; RenderDone only reports. No node and
// no link can hold up another node's frames.
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "cluster/master/frame_barrier.h"
#include "cluster/master/frame_pacer.h"
#include "cluster/master/frame_progress.h"
#include "cluster/master/master_options.h"
#include "cluster/master/node_datagrams.h"
#include "cluster/master/node_sessions.h"
#include "cluster/master/node_statistics.h"
#include "cluster/master/playback.h"
#include "cluster/master/table_schedule.h"
#include "cluster/operator/operator_desk.h"
#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// Invariants: at most one frame in flight (FrameBarrier); a frame is sent
/// only to participants that hold every table set it uses; frames go out in
/// order and no faster than the frame rate when paced.
class FrameLoop {
 public:
  using Clock = std::chrono::steady_clock;

  /// The master's parts the loop reads and drives (they outlive it).
  struct Parts {
    const MasterOptions& options;
    Playback& play;
    NodeSessions& sessions;
    FrameBarrier& barrier;
    TableSchedule& tables;
    const OperatorDesk& desk;
    NodeStatistics& statistics;
    FrameProgress& progress;
    NodeDatagrams& datagrams;
    std::function<void(const std::string& reason)> stop;  ///< the master stops (the show is over)
  };

  FrameLoop(boost::asio::io_context& io, Parts parts);

  /// The wait for nodes counts from now (the tables of frame 0 are ready).
  void start_waiting() { waiting_since_ = Clock::now(); }
  /// Starts frame 0 when the tables allow it and every configured node is
  /// ready, or the wait for nodes is over with at least one; logs once when
  /// none is ready after the wait.
  void maybe_start();
  /// A node's RenderDone: counted in the barrier (Present when it was the
  /// last), or the late node rejoins at the next boundary.
  void on_render_done(const NodeSession& session, const RenderDone& done);
  /// A node left: the frame in flight may be complete without it.
  void on_node_left(std::uint32_t session);
  /// No more frames: the timers are cancelled.
  void stop();

 private:
  void start_frame();
  bool next_frame(FrameState& next);
  /// The next frame for `participants`, once `holders` hold its table sets
  /// (the operator's overrides applied); nothing when there is none yet —
  /// no participant, the feed has none, or its tables are on their way: a
  /// retry is then set.
  std::optional<FrameState> frame_for(const std::vector<std::uint32_t>& participants,
                                      const std::vector<std::uint32_t>& holders);
  /// The show time of the frame presented at `moment`, from the chase of the
  /// house's timecode (its new frames taken first); logs the chase's changes.
  double chased_show_time(Clock::time_point moment);
  void on_barrier_timeout();
  void complete_frame();
  void note_presents(const NodeSession& session, const RenderDone& done);
  /// start_frame after `delay` unless the timer is cancelled (stop) or set again.
  void retry_after(Clock::duration delay);

  // ---- scheduled frames ----
  bool scheduled() const { return p_.options.paced && !p_.options.feed && p_.options.config.lookahead_frames > 0; }
  /// Sends the next frame, lookahead periods before its moment, and the
  /// frames still ahead again to the nodes heard on UDP; then waits for the next tick.
  void schedule_tick();
  /// After a tick: the next one, or after the last frame its tail (tail_tick).
  void after_tick(bool last_frame);
  /// After the last frame, the ticks that would have sent frames `k`, k + 1, …
  /// send only the copies of the frames still ahead, so the show's last
  /// frames get as many copies as every other (a lost datagram costs nothing
  /// there either); one period after the last frame's moment, the stop.
  void tail_tick(std::uint64_t k, const std::string& reason);
  /// The frames still ahead of their moment, again, to `nodes` heard on UDP.
  void resend_ahead(const std::vector<std::uint32_t>& nodes);
  /// Half a period after a tick, the frames still ahead once more: each
  /// frame goes out twice a period over its lookahead, so a node misses it
  /// only when all 2 × lookahead copies are lost (5 % independent loss,
  /// lookahead 3: once in 64 million frames; with a copy a tick, once in 8 000).
  void resend_between_ticks();
  void send_scheduled(const FrameState& state, const FrameSchedule& when, const std::vector<std::uint32_t>& nodes);
  /// A frame sent with its moment, kept to be sent again until then.
  struct Scheduled {
    FrameSchedule when;
    FrameState state;
  };
  std::deque<Scheduled> ahead_;
  bool schedule_started_ = false;

  Parts p_;
  boost::asio::steady_timer barrier_timer_, frame_timer_, resend_timer_;
  /// The next frame, evaluated but not yet sent: it uses a table set that is
  /// still being prepared, or that a participant has not confirmed yet.
  std::optional<FrameState> held_frame_;
  Clock::time_point held_since_;
  bool held_logged_ = false;
  Clock::time_point frame_started_;
  FramePacer pacer_;  ///< when each frame is due
  std::uint64_t last_slip_logged_ = 0;
  std::uint64_t late_frames_ = 0;                         ///< presented more than a period after they were due (paced)
  std::map<std::string, Clock::time_point> late_logged_;  ///< per node: the last log line of its late presents
  /// Since when frame 0 could start as far as the tables go (the wait for nodes counts from here).
  std::optional<Clock::time_point> waiting_since_;
  bool waiting_logged_ = false;
};

}  // namespace zenith::cluster
