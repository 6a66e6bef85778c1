#pragma once
// Procedural albedo maps kept on disk between runs, next to the lookup
// tables: generating a body's map is the start's largest cost on a CPU
// (Earth and Mars at 2048 × 1024 take 3.7 s on two cores), and a cluster
// node that restarts mid-show must not pay it again.
//
// A map's file is <directory>/albedo-<key>.bin, the key the SHA-256 of the
// generator, the seed, the size and the generator's fingerprint
// (procedural_albedo_fingerprint: its colours at 4096 points of the sphere),
// so a changed generator never meets an old map. The file is the map's own
// floats, as generated: "ZALBEDO1", width and height (uint32), then
// width · height · 3 float32, all little-endian — read back in one call (24
// MiB in 0.02 s where a ZIP-compressed EXR took 0.3 s to decompress), the
// same pixels to the bit. Written to a temporary name and renamed: a reader
// sees a whole file or none, and several processes may share the directory.
// A file with another magic, size or length is generated again and replaced,
// with one log line.
#include <filesystem>
#include <string>

#include "image/image_io.h"
#include "scene/scene.h"

namespace zenith::scene {

class AlbedoMapCache {
 public:
  /// A cache in `directory` (created on the first store).
  explicit AlbedoMapCache(std::filesystem::path directory);

  /// The map of `source`: a procedural one from its file, or generated and
  /// stored; a constant or an image file as load_albedo_map gives them (an
  /// image is read from its own file, never copied). Throws as
  /// load_albedo_map does; a cache that cannot be written is logged once and
  /// the generated map returned all the same.
  image::LinearImage load(const AlbedoSource& source);

  /// The file a procedural source's map is kept in.
  std::filesystem::path file_of(const AlbedoSource& source) const;
  const std::filesystem::path& directory() const { return directory_; }

  struct Statistics {
    int read = 0;       ///< maps read from their files
    int generated = 0;  ///< maps generated (absent, unreadable or of the wrong size)
    int stored = 0;     ///< files written
  };
  const Statistics& statistics() const { return statistics_; }

 private:
  void store(const std::filesystem::path& path, const image::LinearImage& map);

  std::filesystem::path directory_;
  bool warned_ = false;
  Statistics statistics_;
};

/// `source`'s map through the cache in `cache_directory` (AlbedoMapCache::load),
/// or load_albedo_map's where the directory is empty (no cache).
image::LinearImage load_albedo_map(const AlbedoSource& source, const std::filesystem::path& cache_directory);

}  // namespace zenith::scene
