#pragma once
// Valid example messages of every type: the seed corpus of the fuzzer, the
// inputs of the mutation property test and of the round-trip tests.
#include <vector>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// One typical message of every type (small TableChunk), deterministic.
std::vector<Message> sample_messages();
/// One message of every type with every variable-length field at its maximum
/// (names of kMaxNameBytes, kMaxWavelengths irradiance values, kMaxAtmospheres
/// atmospheres, a kMaxTableChunkBytes chunk, ...): each encodes to exactly
/// max_payload_bytes(type) payload bytes.
std::vector<Message> max_size_messages();

}  // namespace zenith::cluster
