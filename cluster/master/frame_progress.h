#pragma once
// How far the master's frames are: written by its frame loop
// (cluster/master/frame_loop.h), read by the operator's door
// (cluster/master/master_desk.h).
#include <cstdint>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

struct FrameProgress {
  bool started = false;  ///< frame 0 has started
  bool stopping = false;
  std::uint64_t presented = 0;  ///< frames presented so far
  FrameState in_flight;         ///< the latest frame started (meaningful once started)
};

}  // namespace zenith::cluster
