// Property test of FrameDecoder for the default (GCC) build; the libFuzzer
// target (ZENITH_FUZZ) explores further. 200 000 deterministic mutations of
// valid frame streams (bit flips, truncations, insertions, deletions, length
// and type overwrites, with and without repairing the CRC so that payload
// parsers are reached) fed in random chunkings. Properties:
//   - nothing but ProtocolError escapes (anything else fails the test);
//   - the partial frame never exceeds kHeaderBytes + the type's maximum;
//   - after an error the decoder stays poisoned;
//   - what decodes re-encodes to exactly the bytes it came from.
#include <gtest/gtest.h>

#include <random>

#include "cluster/protocol/frame_decoder.h"
#include "test_support.h"
#include "tests/cluster/sample_messages.h"

namespace zenith::cluster {
namespace {

using Bytes = std::vector<std::uint8_t>;

/// Rewrites every CRC of the frames that fit in `bytes` (as the fuzzer's control bit does).
void repair_crcs(Bytes& bytes) {
  std::size_t at = 0;
  while (bytes.size() - at >= kHeaderBytes) {
    const std::size_t length = std::size_t{bytes[at + 8]} << 24 | std::size_t{bytes[at + 9]} << 16 |
                               std::size_t{bytes[at + 10]} << 8 | bytes[at + 11];
    if (length > bytes.size() - at - kHeaderBytes) return;
    test::put_be32(bytes, at + 12, crc32c(std::span<const std::uint8_t>(bytes).subspan(at + kHeaderBytes, length)));
    test::put_be32(bytes, at + 16, crc32c(std::span<const std::uint8_t>(bytes).subspan(at, 16)));
    at += kHeaderBytes + length;
  }
}

struct Outcome {
  std::size_t messages = 0;
  bool error = false;
  ProtocolErrorCode code{};
};

TEST(FrameDecoderProperty, TwoHundredThousandMutationsNeverCrashNorOverBufferAndFailOnlyWithProtocolError) {
  std::mt19937_64 rng(20240611);
  const auto samples = sample_messages();
  std::vector<Bytes> frames;
  for (const Message& m : samples) frames.push_back(encode(m));
  const auto below = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };

  constexpr int kIterations = 200000;
  std::size_t error_counts[7] = {};
  std::size_t decoded_total = 0, clean_inputs = 0;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    // A stream of 1–3 valid frames...
    Bytes input;
    const std::size_t frame_count = 1 + below(3);
    for (std::size_t i = 0; i < frame_count; ++i) {
      const Bytes& f = frames[below(frames.size())];
      input.insert(input.end(), f.begin(), f.end());
    }
    // ...then 1–4 mutations.
    const std::size_t mutations = 1 + below(4);
    for (std::size_t k = 0; k < mutations && !input.empty(); ++k) {
      switch (below(8)) {
        case 0:
        case 1:  // bit flip (often inside the payload)
          input[below(input.size())] ^= static_cast<std::uint8_t>(1u << below(8));
          break;
        case 2:  // truncation
          input.resize(below(input.size() + 1));
          break;
        case 3: {  // insertion of random bytes
          const std::size_t at = below(input.size() + 1), n = 1 + below(16);
          Bytes extra(n);
          for (auto& b : extra) b = static_cast<std::uint8_t>(rng());
          input.insert(input.begin() + at, extra.begin(), extra.end());
          break;
        }
        case 4: {  // deletion
          const std::size_t at = below(input.size()), n = std::min(input.size() - at, 1 + below(8));
          input.erase(input.begin() + at, input.begin() + at + n);
          break;
        }
        case 5: {  // length-field overwrite of the first frame: small, boundary or huge
          if (input.size() < kHeaderBytes) break;
          const std::uint32_t choices[] = {0u,
                                           1u,
                                           static_cast<std::uint32_t>(rng() % 2048),
                                           static_cast<std::uint32_t>(*max_payload_bytes(33)),
                                           static_cast<std::uint32_t>(*max_payload_bytes(33) + 1),
                                           0xFFFFFFFFu,
                                           static_cast<std::uint32_t>(rng())};
          test::put_be32(input, 8, choices[below(7)]);
          break;
        }
        case 6: {  // type overwrite of the first frame
          if (input.size() < kHeaderBytes) break;
          test::put_be16(input, 6, static_cast<std::uint16_t>(below(4) == 0 ? rng() : 1 + below(50)));
          break;
        }
        case 7: {  // overwrite a byte with a boundary value
          const std::uint8_t values[] = {0x00, 0x01, 0x7F, 0x80, 0xFE, 0xFF};
          input[below(input.size())] = values[below(6)];
          break;
        }
      }
    }
    if (below(2) == 0) repair_crcs(input);

    // Feed in random chunks (1 byte, small, or large), draining after each feed.
    FrameDecoder decoder;
    Bytes reencoded;
    Outcome outcome;
    std::size_t at = 0;
    while (at < input.size() && !outcome.error) {
      const std::size_t mode = below(3);
      const std::size_t piece = mode == 0 ? 1 : mode == 1 ? 1 + below(32) : 1 + below(4096);
      const std::size_t n = std::min(piece, input.size() - at);
      decoder.feed(std::span<const std::uint8_t>(input).subspan(at, n));
      at += n;
      ASSERT_LE(decoder.buffered_bytes(), FrameDecoder::max_buffered_bytes()) << "iteration " << iteration;
      if (decoder.buffered_bytes() >= kHeaderBytes) {
        const std::uint16_t type = static_cast<std::uint16_t>(input[at - decoder.buffered_bytes() + 6] << 8 |
                                                              input[at - decoder.buffered_bytes() + 7]);
        ASSERT_TRUE(max_payload_bytes(type).has_value()) << "buffering a frame of an unknown type";
        ASSERT_LE(decoder.buffered_bytes(), kHeaderBytes + *max_payload_bytes(type)) << "iteration " << iteration;
      }
      try {
        while (auto m = decoder.next()) {
          const Bytes f = encode(*m);
          reencoded.insert(reencoded.end(), f.begin(), f.end());
          ++outcome.messages;
        }
      } catch (const ProtocolError& e) {
        outcome.error = true;
        outcome.code = e.code();
        ASSERT_TRUE(decoder.poisoned());
        ASSERT_THROW(decoder.next(), ProtocolError);
      }
      // Any other exception type propagates and fails the test.
    }
    ASSERT_LE(reencoded.size(), input.size());
    ASSERT_TRUE(std::equal(reencoded.begin(), reencoded.end(), input.begin()))
        << "iteration " << iteration << ": a decoded message re-encodes to different bytes";
    if (outcome.error) {
      ++error_counts[static_cast<int>(outcome.code)];
    } else if (decoder.buffered_bytes() == 0) {
      ASSERT_EQ(reencoded.size(), input.size());
      ++clean_inputs;
    }
    decoded_total += outcome.messages;
  }
  // The mutations must actually reach every kind of failure.
  for (int c = 0; c < 7; ++c)
    EXPECT_GT(error_counts[c], 0u) << "no input triggered " << to_string(static_cast<ProtocolErrorCode>(c));
  std::printf("decoded %zu messages; %zu inputs decoded cleanly; errors:", decoded_total, clean_inputs);
  for (int c = 0; c < 7; ++c) std::printf(" %s=%zu", to_string(static_cast<ProtocolErrorCode>(c)), error_counts[c]);
  std::printf("\n");
}

}  // namespace
}  // namespace zenith::cluster
