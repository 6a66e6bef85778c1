#include "scene/albedo_map_cache.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <system_error>

#include "core/sha256.h"
#include "scene/albedo_map.h"

namespace zenith::scene {
namespace {

static_assert(std::endian::native == std::endian::little, "the albedo map cache's files are little-endian");

constexpr char kMagic[8] = {'Z', 'A', 'L', 'B', 'E', 'D', 'O', '1'};
constexpr std::size_t kHeaderBytes = sizeof kMagic + 2 * sizeof(std::uint32_t);

/// The map stored in `path`, or why it cannot be used.
std::optional<image::LinearImage> read_map(const std::filesystem::path& path, int width_px, int height_px,
                                           std::string& problem) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    problem = "cannot be opened";
    return std::nullopt;
  }
  char header[kHeaderBytes];
  if (!in.read(header, sizeof header) || std::memcmp(header, kMagic, sizeof kMagic) != 0) {
    problem = "is not an albedo map of this cache";
    return std::nullopt;
  }
  std::uint32_t width = 0, height = 0;
  std::memcpy(&width, header + sizeof kMagic, sizeof width);
  std::memcpy(&height, header + sizeof kMagic + sizeof width, sizeof height);
  if (width != std::uint32_t(width_px) || height != std::uint32_t(height_px)) {
    problem = fmt::format("holds {} x {} px where {} x {} are wanted", width, height, width_px, height_px);
    return std::nullopt;
  }
  image::LinearImage map;
  map.width = width_px;
  map.height = height_px;
  map.rgb.resize(std::size_t(width_px) * std::size_t(height_px) * 3);
  const auto bytes = static_cast<std::streamsize>(map.rgb.size() * sizeof(float));
  if (!in.read(reinterpret_cast<char*>(map.rgb.data()), bytes) || in.peek() != std::ifstream::traits_type::eof()) {
    problem = "is truncated or too long";
    return std::nullopt;
  }
  return map;
}

}  // namespace

AlbedoMapCache::AlbedoMapCache(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path AlbedoMapCache::file_of(const AlbedoSource& source) const {
  const std::string identity =
      fmt::format("albedo map 1\n{}\n{}\n{}x{}\n{}\n", source.procedural, source.seed, source.width_px,
                  source.height_px, procedural_albedo_fingerprint(source.procedural, source.seed));
  return directory_ / ("albedo-" + core::sha256_hex(identity.data(), identity.size()).substr(0, 32) + ".bin");
}

image::LinearImage AlbedoMapCache::load(const AlbedoSource& source) {
  if (source.kind != AlbedoSource::Kind::procedural) return load_albedo_map(source);
  const std::filesystem::path path = file_of(source);
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    std::string problem;
    if (std::optional<image::LinearImage> map = read_map(path, source.width_px, source.height_px, problem)) {
      ++statistics_.read;
      return std::move(*map);
    }
    spdlog::warn("albedo map cache: {} {}; generating it again", path.string(), problem);
  }
  image::LinearImage map = load_albedo_map(source);
  ++statistics_.generated;
  store(path, map);
  return map;
}

void AlbedoMapCache::store(const std::filesystem::path& path, const image::LinearImage& map) {
  const std::filesystem::path temporary = path.string() + fmt::format(".{}.tmp", ::getpid());
  try {
    std::filesystem::create_directories(directory_);
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      const auto width = std::uint32_t(map.width), height = std::uint32_t(map.height);
      out.write(kMagic, sizeof kMagic);
      out.write(reinterpret_cast<const char*>(&width), sizeof width);
      out.write(reinterpret_cast<const char*>(&height), sizeof height);
      out.write(reinterpret_cast<const char*>(map.rgb.data()),
                static_cast<std::streamsize>(map.rgb.size() * sizeof(float)));
      if (!out.flush()) throw std::runtime_error("cannot write " + temporary.string());
    }
    std::filesystem::rename(temporary, path);
    ++statistics_.stored;
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    if (!warned_)
      spdlog::warn("albedo map cache in {}: {}; maps are generated each run", directory_.string(), e.what());
    warned_ = true;
  }
}

image::LinearImage load_albedo_map(const AlbedoSource& source, const std::filesystem::path& cache_directory) {
  return cache_directory.empty() ? load_albedo_map(source) : AlbedoMapCache(cache_directory).load(source);
}

}  // namespace zenith::scene
