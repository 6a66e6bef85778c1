#include "cluster/protocol/table_transfer.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/sha256.h"
#include "core/strings.h"

namespace zenith::cluster {
namespace {

using core::cat;

}  // namespace

Digest sha256(std::span<const std::uint8_t> bytes) { return core::sha256(bytes.data(), bytes.size()); }

TableSetFile make_table_set(const std::string& body_name, const Digest& table_hash,
                            std::shared_ptr<const std::vector<std::uint8_t>> bytes, std::uint32_t chunk_bytes) {
  if (!bytes || bytes->empty() || bytes->size() > kMaxTableTotalBytes)
    throw std::runtime_error(cat("table set ", short_hex(table_hash), ": ", bytes ? bytes->size() : 0,
                                 " bytes: a table set must hold 1 to ", kMaxTableTotalBytes, " bytes"));
  if (chunk_bytes == 0 || chunk_bytes > kMaxTableChunkBytes)
    throw std::invalid_argument("table chunk size out of range");
  TableSetFile set;
  set.body_name = body_name;
  set.table_hash = table_hash;
  set.content_sha256 = sha256(*bytes);
  TableAnnounce announce;
  announce.table_hash = table_hash;
  announce.total_bytes = bytes->size();
  announce.chunk_bytes = chunk_bytes;
  announce.chunk_count = static_cast<std::uint32_t>((bytes->size() + chunk_bytes - 1) / chunk_bytes);
  announce.content_sha256 = set.content_sha256;
  set.frames.push_back(std::make_shared<const std::vector<std::uint8_t>>(encode(announce)));
  for (std::uint32_t i = 0; i < announce.chunk_count; ++i) {
    TableChunk chunk;
    chunk.table_hash = table_hash;
    chunk.index = i;
    const std::size_t begin = std::size_t{i} * chunk_bytes;
    const std::size_t end = std::min(bytes->size(), begin + chunk_bytes);
    chunk.bytes.assign(bytes->begin() + static_cast<std::ptrdiff_t>(begin),
                       bytes->begin() + static_cast<std::ptrdiff_t>(end));
    set.frames.push_back(std::make_shared<const std::vector<std::uint8_t>>(encode(chunk)));
  }
  set.bytes = std::move(bytes);
  return set;
}

TableSetFile make_table_set_file(const std::string& body_name, const Digest& table_hash,
                                 const std::filesystem::path& cache_file, std::uint32_t chunk_bytes) {
  std::ifstream in(cache_file, std::ios::binary);
  if (!in) throw std::runtime_error(cat(cache_file.string(), ": cannot open the table cache file"));
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty() || bytes.size() > kMaxTableTotalBytes)
    throw std::runtime_error(cat(cache_file.string(), ": ", bytes.size(), " bytes: a table set must hold 1 to ",
                                 kMaxTableTotalBytes, " bytes"));
  return make_table_set(body_name, table_hash, std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes)),
                        chunk_bytes);
}

void TableReceiver::on_announce(const TableAnnounce& announce) {
  // The decoder checked the sizes and chunk_count = ceil(total / chunk).
  Pending p;
  p.announce = announce;
  p.bytes.resize(announce.total_bytes);
  p.received.assign(announce.chunk_count, false);
  pending_[announce.table_hash] = std::move(p);
}

std::optional<std::vector<std::uint8_t>> TableReceiver::on_chunk(const TableChunk& chunk) {
  auto it = pending_.find(chunk.table_hash);
  if (it == pending_.end())
    throw std::runtime_error(cat("TableChunk ", chunk.index, " of table set ", to_hex(chunk.table_hash).substr(0, 12),
                                 "…, which was not announced"));
  Pending& p = it->second;
  const TableAnnounce& a = p.announce;
  if (chunk.index >= a.chunk_count)
    throw std::runtime_error(cat("TableChunk index ", chunk.index, " out of range (", a.chunk_count, " chunks)"));
  const std::size_t begin = std::size_t{chunk.index} * a.chunk_bytes;
  const std::size_t expected = std::min<std::size_t>(a.chunk_bytes, a.total_bytes - begin);
  if (chunk.bytes.size() != expected)
    throw std::runtime_error(
        cat("TableChunk ", chunk.index, " holds ", chunk.bytes.size(), " bytes, expected ", expected));
  if (p.received[chunk.index]) throw std::runtime_error(cat("TableChunk ", chunk.index, " received twice"));
  std::copy(chunk.bytes.begin(), chunk.bytes.end(), p.bytes.begin() + static_cast<std::ptrdiff_t>(begin));
  p.received[chunk.index] = true;
  if (++p.received_count < a.chunk_count) return std::nullopt;
  std::vector<std::uint8_t> bytes = std::move(p.bytes);
  const Digest expected_sha = a.content_sha256;
  pending_.erase(it);
  if (sha256(bytes) != expected_sha)
    throw std::runtime_error("table set content does not match the SHA-256 of its TableAnnounce");
  return bytes;
}

void write_file_atomically(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::filesystem::path temp = path;
  temp += cat(".tmp-", ::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(cat(temp.string(), ": cannot create"));
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw std::runtime_error(cat(temp.string(), ": write failed"));
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw std::runtime_error(cat(path.string(), ": cannot rename the temporary file into place"));
  }
}

}  // namespace zenith::cluster
