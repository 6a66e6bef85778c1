#pragma once
// Show::Impl: what load_show fills in and Show reads (private to show/).
#include <cstddef>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/frame_description.h"
#include "show/camera_track.h"
#include "show/monotone_cubic.h"
#include "show/parameter_track.h"
#include "show/show.h"
#include "show/sun_track.h"

namespace zenith::show {

/// The show's "time" (docs/shows.md, "Time track"): the sky's UTC at show time t
/// is start + time_rate · t (the scene's "time" by default).
struct TimeTrack {
  astro::AstroTime start;
  double time_rate = 1.0;  ///< sky seconds per show second
  double end_s = 0.0;      ///< show time it runs to (counts toward the show's duration)
  astro::AstroTime at(double t_s) const { return start.plus_seconds(time_rate * t_s); }
};

/// The parameter tracks of one body's atmosphere.
struct AtmosphereTracks {
  std::string body;
  std::size_t entry = 0;  ///< index in the show file's "atmospheres" (for messages)
  nlohmann::json base;    ///< the scene's parameters for this body
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
  std::optional<Show::HouseTimecode> timecode;  ///< the "timecode" block

  // Keyframed shows: absent tracks leave the scene's value.
  std::optional<CameraTrack> camera;
  std::optional<SunTrack> sun;
  std::optional<TimeTrack> time;  ///< moves the scene's sky clock (then no sun track)
  /// The star catalogue's identity every node must draw the sky from (frames'
  /// sky.star_catalogue): stellarium-data at the renderer's default magnitude
  /// limit, read when the scene has a sky clock; zeros where it is not installed (not checked).
  scene::TableHash star_catalogue{};
  std::optional<MonotoneCubic> log_exposure;  ///< ln(exposure)
  std::vector<AtmosphereTracks> atmosphere_tracks;
  /// Body → the table hash of the scene's own atmosphere, for bodies without tracks.
  std::map<std::string, scene::TableHash> fixed_atmospheres;

  // Recordings.
  std::vector<scene::FrameDescription> frames;
  std::vector<scene::TableHash> recorded_versions;  ///< in the order of /recording/versions

  /// Every version produced or recorded so far, by table hash. Guarded by
  /// `mutex`: state_at may run on several threads. Map nodes are stable, so
  /// pointers into it stay valid for the Show's life.
  mutable std::mutex mutex;
  mutable std::map<scene::TableHash, AtmosphereVersion> versions;
  /// Body + canonical JSON text of a parameter set → its table hash, so each
  /// set is resolved once.
  mutable std::map<std::string, scene::TableHash> hash_by_parameters;

  /// The table hash of a body's tracked parameters at t, resolving (and
  /// remembering) the set when new. Throws ConfigError naming the show's
  /// "atmospheres" entry and the time when the set does not resolve.
  scene::TableHash tracked_hash(const AtmosphereTracks& tracks, double t_s) const;
  /// Remembers a version; returns its hash.
  scene::TableHash remember(AtmosphereVersion version) const;
  scene::FrameDescription keyframed_state(double t_s, std::uint64_t frame, std::uint32_t render_flags) const;
  scene::FrameDescription recorded_state(double t_s, std::uint64_t frame) const;
};

/// The table hash of a resolved atmosphere, as raw bytes.
scene::TableHash table_hash_of(const atmosphere::LoadedAtmosphere& loaded);

}  // namespace zenith::show
