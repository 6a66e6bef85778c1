#include "cluster/protocol/state_digest.h"

#include <cstdint>
#include <vector>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

std::string state_digest(const scene::FrameDescription& frame) {
  const std::vector<std::uint8_t> payload = encode_payload(frame);
  return to_hex(core::sha256(payload.data(), payload.size())).substr(0, 16);
}

}  // namespace zenith::cluster
