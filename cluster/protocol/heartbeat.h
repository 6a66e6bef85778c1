#pragma once
// The Heartbeat message master and nodes send each other (docs/protocol.md),
// stamped with the sender's steady clock (for round-trip times only: liveness
// counts bytes received, not stamps).
#include <chrono>
#include <cstdint>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// A Heartbeat stamped with `now` in nanoseconds of the steady clock.
inline Heartbeat heartbeat_at(std::chrono::steady_clock::time_point now) {
  return Heartbeat{
      static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count())};
}

}  // namespace zenith::cluster
