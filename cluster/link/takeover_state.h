#pragma once
// What a standby master knows of the show when it takes over (docs/cluster.md,
// "Standby master"): the frames the active master sent last and every table
// version it had distributed. The standby builds it while it follows
// (StandbyFollower) and hands it to the master it becomes (MasterOptions::takeover).
#include <cstdint>
#include <optional>
#include <vector>

#include "cluster/protocol/messages.h"
#include "cluster/protocol/table_transfer.h"

namespace zenith::cluster {

struct TakeoverState {
  /// One table version the active master distributed: its definition and its set.
  struct Version {
    AtmosphereDefinition definition;
    TableSetFile set;
  };

  /// The last FrameState the active master sent (the frame in flight, or the
  /// last presented); none when the show had not started.
  std::optional<FrameState> last_frame;
  /// The show time the frames were advancing by: the last step between
  /// consecutive frames seen twice in a row (rate / fps; 0 when paused), so
  /// that a seek or a loop's wrap just before the failure does not count;
  /// none before such a step was seen.
  std::optional<double> show_time_step_s;
  /// The last frame the active master presented, as far as the standby saw.
  std::optional<std::uint64_t> last_presented;
  /// Every version received in full, in the order received.
  std::vector<Version> versions;

  /// The frame the standby continues with: the one after the last it saw (0 without any).
  std::uint64_t next_frame() const { return last_frame ? last_frame->frame + 1 : 0; }
  /// Whether the last frame was still in flight (sent but not seen presented)
  /// when the active master was lost: then it is the one frame nodes may never present.
  bool frame_in_flight() const { return last_frame && (!last_presented || *last_presented < last_frame->frame); }
};

}  // namespace zenith::cluster
