#pragma once
// The master's frame barrier (docs/cluster.md, "The frame barrier"), as pure
// bookkeeping: no sockets, no timers, no clock. The master asks it who takes
// part in a frame, tells it what the nodes report and when the barrier
// timeout fired, and it says when Present may go out and to whom.
#include <cstdint>
#include <map>
#include <set>
#include <vector>

namespace zenith::cluster {

/// Tracks one frame at a time: the participants of frame N (ready nodes that
/// are not lagging), which of them reported RenderDone N, and the nodes
/// dropped from an earlier barrier ("lagging") until their late report brings
/// them back at the next frame boundary.
///
/// Invariants: at most one frame is in flight; `frame()` is the frame in
/// flight, or the next one to start; a lagging node is never a participant;
/// Present for frame N goes only to participants that reported N.
class FrameBarrier {
 public:
  /// The master's session id of a node connection (never reused).
  using NodeId = std::uint32_t;

  /// What a RenderDone did to the barrier.
  enum class Report {
    counted,          ///< a participant finished the frame in flight
    rejoins,          ///< a lagging node reported an earlier frame: it takes part again from the next boundary
    ignored_lagging,  ///< a lagging node reported the frame in flight (or later): it stays out
    ignored,          ///< not the frame in flight, not a participant, or no frame in flight
  };

  /// The frame that was complete: Present it to these nodes.
  struct Release {
    std::uint64_t frame = 0;
    std::vector<NodeId> present_to;
  };

  /// The frame in flight, or the next one to start.
  std::uint64_t frame() const { return frame_; }
  bool in_flight() const { return in_flight_; }
  /// The first frame a node that becomes ready now takes part in.
  std::uint64_t next_boundary() const { return in_flight_ ? frame_ + 1 : frame_; }
  bool is_lagging(NodeId node) const { return lagging_.count(node) > 0; }
  /// The participants of the frame in flight (all of them, done or not).
  std::size_t participant_count() const { return participants_.size(); }

  /// Numbers the next frame `frame` instead of 0 (a standby master taking
  /// over continues the active master's numbering). Precondition: no frame in flight.
  void start_at(std::uint64_t frame);

  /// Of the nodes that are ready (tables held, connection open), those that
  /// take part in the next frame: every one that is not lagging, in order.
  std::vector<NodeId> participants_among(const std::vector<NodeId>& ready) const;

  /// Frame `frame` goes out to `participants` (from participants_among). The
  /// frame number is the caller's: the next one, or a frame feed's.
  /// Precondition: no frame in flight.
  void begin(std::uint64_t frame, const std::vector<NodeId>& participants);

  /// RenderDone `frame` from `node`.
  Report on_render_done(NodeId node, std::uint64_t frame);

  /// The barrier timeout of the frame in flight: every participant that has
  /// not reported is dropped from it and lags. Returns those nodes.
  std::vector<NodeId> drop_unfinished();

  /// `node`'s connection closed. Returns true when it was a participant of the
  /// frame in flight (the barrier may now be complete: see complete()).
  bool remove(NodeId node);

  /// A frame is in flight and every remaining participant reported it (also
  /// when none remain).
  bool complete() const;

  /// Ends the frame in flight: the participants that reported it, and the
  /// frame number moves on by one. Precondition: a frame is in flight.
  Release release();

 private:
  std::uint64_t frame_ = 0;
  bool in_flight_ = false;
  std::map<NodeId, bool> participants_;  ///< node → RenderDone received for frame_
  std::set<NodeId> lagging_;
};

}  // namespace zenith::cluster
