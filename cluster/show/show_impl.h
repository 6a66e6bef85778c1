#pragma once
// Show::Impl: what load_show fills in and Show reads (private to cluster/show/).
#include <cstddef>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cluster/messages.h"
#include "cluster/show/camera_track.h"
#include "cluster/show/monotone_cubic.h"
#include "cluster/show/parameter_track.h"
#include "cluster/show/show.h"
#include "cluster/show/sun_track.h"

namespace zenith::show {

/// The parameter tracks of one body's atmosphere.
struct AtmosphereTracks {
  std::string body;
  std::size_t entry = 0;     ///< index in the show file's "atmospheres" (for messages)
  nlohmann::json base;       ///< the scene's parameters for this body
  std::vector<ParameterTrack> tracks;

  /// The body's parameters at t: `base` with every track applied.
  nlohmann::json parameters_at(double t_s) const;
};

struct Show::Impl {
  Kind kind = Kind::keyframed;
  std::string name;
  std::filesystem::path source, scene_path;
  std::optional<std::filesystem::path> cluster_path;
  scene::Scene scene;
  double duration_s = 0.0;
  double frame_rate_hz = 30.0;
  bool loop = false;

  // Keyframed shows: absent tracks leave the scene's value.
  std::optional<CameraTrack> camera;
  std::optional<SunTrack> sun;
  std::optional<MonotoneCubic> log_exposure;  ///< ln(exposure)
  std::vector<AtmosphereTracks> atmosphere_tracks;
  /// Body → the table hash of the scene's own atmosphere, for bodies without tracks.
  std::map<std::string, cluster::Digest> fixed_atmospheres;

  // Recordings.
  std::vector<cluster::FrameState> frames;
  std::vector<cluster::Digest> recorded_versions;  ///< in the order of /recording/versions

  /// Every version produced or recorded so far, by table hash. Guarded by
  /// `mutex`: state_at may run on several threads. Map nodes are stable, so
  /// pointers into it stay valid for the Show's life.
  mutable std::mutex mutex;
  mutable std::map<cluster::Digest, AtmosphereVersion> versions;
  /// Body + canonical JSON text of a parameter set → its table hash, so each
  /// set is resolved once.
  mutable std::map<std::string, cluster::Digest> hash_by_parameters;

  /// The table hash of a body's tracked parameters at t, resolving (and
  /// remembering) the set when new. Throws ConfigError naming the show's
  /// "atmospheres" entry and the time when the set does not resolve.
  cluster::Digest tracked_hash(const AtmosphereTracks& tracks, double t_s) const;
  /// Remembers a version; returns its hash.
  cluster::Digest remember(AtmosphereVersion version) const;
  cluster::FrameState keyframed_state(double t_s, std::uint64_t frame, std::uint32_t render_flags) const;
  cluster::FrameState recorded_state(double t_s, std::uint64_t frame) const;
};

/// The table hash of a resolved atmosphere, as raw bytes.
cluster::Digest table_hash_of(const atmosphere::LoadedAtmosphere& loaded);

}  // namespace zenith::show
