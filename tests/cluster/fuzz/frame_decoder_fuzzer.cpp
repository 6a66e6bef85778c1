// libFuzzer target for FrameDecoder (docs/protocol.md, "Fuzzing").
//
// Input: one control byte, then the bytes a peer might send. Control bit 0
// set: before feeding, walk the bytes as frames and rewrite each header's
// CRC-32C fields (payload and header) to match, so mutations reach the payload parsers instead
// of all stopping at crc_mismatch. Bits 1..7 seed the split of the bytes into
// feed() calls of 1..64 (or occasionally up to 4096) bytes.
//
// Checked on every input: only ProtocolError escapes the decoder (anything
// else aborts the run), the partial frame never exceeds the decoder's bound,
// and the decoded messages re-encode to exactly the bytes they came from
// (the encoding is canonical), so decode and encode agree on every field.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "cluster/protocol/crc32c.h"
#include "cluster/protocol/frame_decoder.h"
#include "cluster/protocol/messages.h"

namespace {

using namespace zenith::cluster;

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "frame_decoder_fuzzer: %s\n", what);
  std::abort();
}

void repair_crcs(std::vector<std::uint8_t>& bytes) {
  std::size_t at = 0;
  while (bytes.size() - at >= kHeaderBytes) {
    const std::uint8_t* h = bytes.data() + at;
    const std::size_t length =
        std::size_t{h[8]} << 24 | std::size_t{h[9]} << 16 | std::size_t{h[10]} << 8 | std::size_t{h[11]};
    if (length > bytes.size() - at - kHeaderBytes) return;
    const std::uint32_t crc = crc32c(std::span<const std::uint8_t>(bytes.data() + at + kHeaderBytes, length));
    for (int i = 0; i < 4; ++i)
      bytes[at + 12 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
    const std::uint32_t header_crc = crc32c(std::span<const std::uint8_t>(bytes.data() + at, 16));
    for (int i = 0; i < 4; ++i)
      bytes[at + 16 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(header_crc >> (24 - 8 * i));
    at += kHeaderBytes + length;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t control = data[0];
  std::vector<std::uint8_t> input(data + 1, data + size);
  if (control & 1u) repair_crcs(input);

  FrameDecoder decoder;
  std::vector<std::uint8_t> reencoded;
  std::uint32_t state = 0x9E3779B9u ^ control;
  std::size_t at = 0;
  bool failed = false;
  while (at < input.size() && !failed) {
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    const std::size_t piece = (state % 16 == 0) ? 1 + state % 4096 : 1 + (state >> 8) % 64;
    const std::size_t n = std::min(piece, input.size() - at);
    decoder.feed(std::span<const std::uint8_t>(input.data() + at, n));
    at += n;
    if (decoder.buffered_bytes() > FrameDecoder::max_buffered_bytes()) fail("buffered bytes above the bound");
    try {
      while (auto message = decoder.next()) {
        const std::vector<std::uint8_t> frame = encode(*message);
        reencoded.insert(reencoded.end(), frame.begin(), frame.end());
      }
    } catch (const ProtocolError&) {
      failed = true;
      if (!decoder.poisoned()) fail("ProtocolError without poisoning the decoder");
    }
  }
  // The decoded frames are the first frames of the input, byte for byte.
  if (reencoded.size() > input.size() || !std::equal(reencoded.begin(), reencoded.end(), input.begin()))
    fail("re-encoded messages differ from the bytes they were decoded from");
  if (!failed && decoder.buffered_bytes() == 0 && reencoded.size() != input.size())
    fail("input consumed without error, yet not every byte became a message");
  return 0;
}
