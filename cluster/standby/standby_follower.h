#pragma once
// What a standby master keeps of the show while it follows the active master
// (docs/cluster.md, "Standby master"), as pure bookkeeping: no sockets, no
// clock. The standby's link hands it every message of the active master after
// the Welcome (but Heartbeat and Goodbye); it reassembles and verifies every
// table set (TableReceiver) and keeps it with its definition, encoded for
// sending, so that after a takeover it serves nodes' inventories and sends
// sets as the active master did; it keeps the last FrameState, the show-time
// step the frames advance by, and the last Present, from which the show
// continues.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "cluster/link/takeover_state.h"
#include "cluster/protocol/messages.h"
#include "cluster/protocol/table_transfer.h"

namespace zenith::cluster {

/// Invariants: every version held has its definition and a set whose SHA-256
/// matched its announcement; versions() holds each table hash once, in the
/// order first completed; last_frame() is the FrameState received last.
class StandbyFollower {
 public:
  /// A connection to the active master was welcomed (the first, or again):
  /// transfers in progress are dropped (the master sends every set afresh);
  /// the sets and frames held stay.
  void on_welcome();

  /// One message of the active master after the Welcome, but Heartbeat and
  /// Goodbye (the link's): AtmosphereDefinition, TableAnnounce, TableChunk,
  /// FrameState, Present. Throws std::runtime_error for any other message, a
  /// TableAnnounce of a set without its definition, and what TableReceiver
  /// refuses (a chunk of no announced set, a SHA-256 mismatch, …).
  void on_message(const Message& message);

  /// The FrameState received last, if any.
  const std::optional<FrameState>& last_frame() const { return last_; }
  /// FrameStates received in all.
  std::uint64_t frames_seen() const { return frames_seen_; }
  /// The versions held (definition and set), in the order completed.
  const std::vector<TakeoverState::Version>& versions() const { return versions_; }

  /// Why this standby cannot continue the show, or nullopt when it can: the
  /// last frame uses a table set it does not hold. Without any frame it can
  /// (it starts the show from frame 0, preparing its tables itself).
  std::optional<std::string> takeover_problem() const;
  /// The state handed to the master this standby becomes. Precondition:
  /// takeover_problem() is nullopt.
  TakeoverState takeover_state() const;

 private:
  TableReceiver receiver_;
  std::map<Digest, AtmosphereDefinition> definitions_;
  std::vector<TakeoverState::Version> versions_;
  std::optional<FrameState> last_;
  std::optional<double> last_step_s_;    ///< show time from the frame before last_ to last_, when consecutive
  std::optional<double> steady_step_s_;  ///< the last step seen twice in a row
  std::optional<std::uint64_t> last_presented_;
  std::uint64_t frames_seen_ = 0;
};

}  // namespace zenith::cluster
