#pragma once
// The atmospheres a render node can render, by table version (docs/cluster.md,
// "Table versions"): a node can only use tables whose parameters it knows.
// They are the scene's, the presets and atmosphere files that fit a body, and
// the versions the master defines (AtmosphereDefinition), which are kept in
// the cache folder so that after a restart the node knows what it cached.
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "atmosphere/parameters.h"
#include "cluster/protocol/messages.h"
#include "scene/scene.h"

namespace zenith::cluster {

/// Thread-safe: the networking thread adds definitions while the render
/// thread looks versions up. Entries are never changed or erased, so a
/// reference returned by find() stays valid for the catalogue's lifetime.
class KnownAtmospheres {
 public:
  /// One known version: the body it belongs to and the resolved atmosphere.
  struct Entry {
    std::string body;
    atmosphere::LoadedAtmosphere loaded;
  };

  /// `scene` must outlive the catalogue; definitions are kept under
  /// `cache_directory`/definitions; `node_name` is for log lines.
  KnownAtmospheres(const scene::Scene& scene, std::filesystem::path cache_directory, std::string node_name);
  KnownAtmospheres(const KnownAtmospheres&) = delete;
  KnownAtmospheres& operator=(const KnownAtmospheres&) = delete;

  /// For each body with an atmosphere: the scene's atmosphere, every preset
  /// and every file of `atmosphere_files` that fits it (ground radius within
  /// 1 m). Errors in the files are fatal (thrown).
  void add_scene_and_candidates(const std::vector<std::filesystem::path>& atmosphere_files);
  /// Definitions kept by earlier runs; an unreadable or stale one is skipped with a log line.
  void load_kept_definitions();
  /// An AtmosphereDefinition from the master: resolves the parameters at the
  /// scene's wavelengths, checks the body and the hash, and adds the version
  /// (kept on disk when `keep`). Throws std::runtime_error naming the body and both hashes.
  void define(const AtmosphereDefinition& definition, bool keep);

  /// The version `hash`; throws std::out_of_range if unknown.
  const Entry& find(const Digest& hash) const;
  bool knows(const Digest& hash) const;
  /// A copy of every known version, for a walk without the lock.
  std::map<Digest, Entry> snapshot() const;

 private:
  std::filesystem::path definitions_directory() const { return cache_directory_ / "definitions"; }

  const scene::Scene& scene_;
  std::filesystem::path cache_directory_;
  std::string node_name_;
  std::map<Digest, Entry> entries_;
  mutable std::mutex mutex_;
};

}  // namespace zenith::cluster
