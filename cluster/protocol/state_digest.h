#pragma once
// A short fingerprint of a frame's description: equal on every node that
// received the same FrameState, and the same for a frame rendered offline, so
// presented.log and the offline manifest (offline/offline_manifest.h) name a
// frame's state the same way.
#include <string>

#include "scene/frame_description.h"

namespace zenith::cluster {

/// First 16 hex digits of the SHA-256 of the frame's FrameState wire payload
/// (cluster/protocol/messages.h).
std::string state_digest(const scene::FrameDescription& frame);

}  // namespace zenith::cluster
