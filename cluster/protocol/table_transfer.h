#pragma once
// Lookup-table sets on the wire (docs/cluster.md, "Shared tables"): the master
// sends the bytes of a table cache file (atmosphere/lut/table_cache.h) as one
// TableAnnounce and its TableChunks; the node reassembles them, checks the
// SHA-256 of the whole content and stores the file in its own cache.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

/// Chunk size the master uses (well under kMaxTableChunkBytes).
inline constexpr std::uint32_t kTableChunkBytes = 256 * 1024;

/// SHA-256 (OpenSSL).
Digest sha256(std::span<const std::uint8_t> bytes);

/// One atmosphere's table set as the master holds it.
struct TableSetFile {
  std::string body_name;
  Digest table_hash{};                                     ///< atmosphere::lookup_table_hash as raw bytes
  std::shared_ptr<const std::vector<std::uint8_t>> bytes;  ///< the cache file's content
  Digest content_sha256{};
  /// TableAnnounce then every TableChunk, encoded once and shared by every connection.
  std::vector<std::shared_ptr<const std::vector<std::uint8_t>>> frames;
};

/// Encodes the transfer of a table set held in memory (a standby's received
/// sets). Throws std::runtime_error when `bytes` is empty or larger than
/// kMaxTableTotalBytes, std::invalid_argument for a chunk size out of range.
TableSetFile make_table_set(const std::string& body_name, const Digest& table_hash,
                            std::shared_ptr<const std::vector<std::uint8_t>> bytes,
                            std::uint32_t chunk_bytes = kTableChunkBytes);

/// Reads `cache_file` and encodes its transfer. Throws std::runtime_error when
/// the file cannot be read or is empty or larger than kMaxTableTotalBytes.
TableSetFile make_table_set_file(const std::string& body_name, const Digest& table_hash,
                                 const std::filesystem::path& cache_file, std::uint32_t chunk_bytes = kTableChunkBytes);

/// The node's side: reassembles announced sets. Throws std::runtime_error
/// (the connection is then closed) for a chunk of no announced set, an index
/// out of range, a chunk of the wrong size, a duplicate chunk, or a set whose
/// SHA-256 does not match its announcement.
class TableReceiver {
 public:
  void on_announce(const TableAnnounce& announce);
  /// The whole content once the set's last chunk arrived and verified.
  std::optional<std::vector<std::uint8_t>> on_chunk(const TableChunk& chunk);

 private:
  struct Pending {
    TableAnnounce announce;
    std::vector<std::uint8_t> bytes;
    std::vector<bool> received;
    std::uint32_t received_count = 0;
  };
  std::map<Digest, Pending> pending_;
};

/// Writes `bytes` to `path` atomically (a temporary file in the same folder,
/// then rename), creating the folder. Throws std::runtime_error.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace zenith::cluster
