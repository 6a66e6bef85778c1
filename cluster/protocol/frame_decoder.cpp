#include "cluster/protocol/frame_decoder.h"

#include <algorithm>
#include <sstream>

#include "cluster/protocol/crc32c.h"
#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

std::size_t FrameDecoder::max_buffered_bytes() { return kHeaderBytes + largest_max_payload_bytes(); }

std::uint32_t max_handshake_payload_bytes() {
  std::size_t most = 0;
  for (const MessageType t : {MessageType::hello, MessageType::authenticate, MessageType::goodbye})
    most = std::max(most, *max_payload_bytes(static_cast<std::uint16_t>(t)));
  return static_cast<std::uint32_t>(most);
}

void FrameDecoder::limit_payload(std::uint32_t max_bytes, std::string why) {
  limit_ = Limit{max_bytes, std::move(why)};
}

void FrameDecoder::feed(std::span<const std::uint8_t> bytes) {
  while (!bytes.empty() && !error_) {
    try {
      if (!header_) {
        const std::size_t take = std::min(kHeaderBytes - frame_.size(), bytes.size());
        frame_.insert(frame_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(take));
        bytes = bytes.subspan(take);
        if (frame_.size() < kHeaderBytes) return;
        header_ = parse_header(std::span<const std::uint8_t, kHeaderBytes>(frame_.data(), kHeaderBytes));
        if (limit_ && header_->payload_bytes > limit_->max_bytes)
          throw ProtocolError(
              ProtocolErrorCode::oversized,
              cat("frame header payload length: ", header_->payload_bytes, " bytes of a ", to_string(header_->type),
                  " exceeds the ", limit_->max_bytes, "-byte limit ", limit_->why));
        // The length is within the type's limit: reserving it is bounded.
        frame_.reserve(kHeaderBytes + header_->payload_bytes);
      }
      const std::size_t wanted = kHeaderBytes + header_->payload_bytes - frame_.size();
      const std::size_t take = std::min(wanted, bytes.size());
      frame_.insert(frame_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(take));
      bytes = bytes.subspan(take);
      if (take == wanted) complete_frame();
    } catch (const ProtocolError& e) {
      error_ = e;
      frame_.clear();
      frame_.shrink_to_fit();
      header_.reset();
    }
  }
}

void FrameDecoder::complete_frame() {
  const std::span<const std::uint8_t> payload(frame_.data() + kHeaderBytes, header_->payload_bytes);
  const std::uint32_t crc = crc32c(payload);
  if (crc != header_->payload_crc32c) {
    std::ostringstream detail;
    detail << to_string(header_->type) << " payload CRC-32C: computed 0x" << std::hex << crc << ", header says 0x"
           << header_->payload_crc32c;
    throw ProtocolError(ProtocolErrorCode::crc_mismatch, detail.str());
  }
  ready_.push_back(decode_payload(static_cast<std::uint16_t>(header_->type), payload));
  header_.reset();
  // Keep small buffers for reuse; give back a large one (a TableChunk) at once.
  if (frame_.capacity() > 64 * 1024) {
    std::vector<std::uint8_t>().swap(frame_);
  } else {
    frame_.clear();
  }
}

std::optional<Message> FrameDecoder::next() {
  if (!ready_.empty()) {
    Message m = std::move(ready_.front());
    ready_.pop_front();
    return m;
  }
  if (error_) throw *error_;
  return std::nullopt;
}

}  // namespace zenith::cluster
