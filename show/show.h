#pragma once
// A show (docs/shows.md): what the master plays, frame by frame.
//
// Two kinds share one file format ("zenith_show": 1):
//   - keyframed shows: tracks of keys over show time — the camera (position on
//     a centripetal Catmull–Rom spline, orientation by squad), the sun, the
//     exposure, and per-atmosphere parameter tracks (a JSON pointer into the
//     atmosphere's parameters, quantized to a documented step so a show needs
//     a bounded number of lookup-table sets);
//   - recordings: every frame state a live session presented, stored so that
//     each double reads back bit for bit.
// Either is evaluated into scene::FrameDescription (scene/frame_description.h),
// the frame's camera, sun, exposure and atmosphere versions: the cluster sends
// it as its FrameState message, the offline renderer renders it, and the tests
// check it, so all see a show the same way.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "astro/civil_time.h"
#include "scene/frame_description.h"
#include "scene/scene.h"
#include "show/timecode/timecode_chase.h"

namespace zenith::show {

/// Bumped when the file format changes incompatibly.
inline constexpr int kShowFormatVersion = 1;

/// One atmosphere parameter set a show uses: the body it belongs to, its
/// parameters (the scene's atmosphere with the show's tracks applied and
/// quantized; resolvable by atmosphere::resolve_atmosphere at the scene's
/// wavelengths) and the hash of the lookup tables it shapes.
struct AtmosphereVersion {
  std::string body;
  nlohmann::json parameters;
  scene::TableHash table_hash{};        ///< atmosphere::lookup_table_hash of the resolved model, raw bytes
  atmosphere::LoadedAtmosphere loaded;  ///< the resolved atmosphere
};

class Show {
 public:
  enum class Kind { keyframed, recording };

  ~Show();
  Show(Show&&) noexcept;
  Show& operator=(Show&&) noexcept;

  Kind kind() const;
  const std::string& name() const;
  const std::filesystem::path& source() const;  ///< the show file
  /// The scene the show was authored for (loaded from the show's "scene" key,
  /// relative to the show file); keys override its camera, sun and exposure,
  /// tracks override its atmospheres' parameters.
  const scene::Scene& scene() const;
  const std::filesystem::path& scene_path() const;
  /// The cluster configuration the show was authored for, if it names one.
  const std::optional<std::filesystem::path>& cluster_path() const;
  /// Show time of the last key (keyframed); (frames − 1) / frame_rate_hz() (recordings) [s].
  double duration_s() const;
  /// Whether playback loops by default.
  bool loop() const;
  /// The house timecode the show chases (its "timecode" block: the rate,
  /// the label at show time 0 as ChaseSettings::offset_s, what a dropout
  /// does); nullopt: the show runs on its own clock.
  struct HouseTimecode {
    TimecodeRate rate = TimecodeRate::fps25;
    ChaseSettings chase;
  };
  const std::optional<HouseTimecode>& timecode() const;
  /// Recordings: the frame rate they were recorded at [Hz]; keyframed: the
  /// show's suggested rate ("fps" key, default 30).
  double frame_rate_hz() const;

  /// Frames of a run at `fps` from show time 0 to duration_s():
  /// floor(duration_s · fps + 1e-9) + 1 for keyframed shows; recordings: the
  /// number of recorded frames (fps is ignored).
  std::uint64_t frame_count(double fps) const;
  /// Time of frame `index` of such a run on the show's timeline: index / fps
  /// (keyframed), index / frame_rate_hz() (recordings: their own timeline,
  /// whatever show time each recorded state carries).
  double frame_time_s(std::uint64_t index, double fps) const;

  /// The sky's UTC at show time t (clamped as state_at) when the scene gives
  /// "time" and "site": the scene's time, moved by the show's time track. The
  /// render passes of stars and the Moon place them by it (astro/sky_positions.h).
  std::optional<astro::AstroTime> sky_time_at(double show_time_s) const;

  /// The state at show time t (clamped to [0, duration_s()]) as frame `frame`.
  /// Keyframed: the tracks interpolated at t, with `render_flags` and each
  /// atmosphere's table reference effective from frame 0. Recordings: the
  /// recorded state number ⌊t · frame_rate_hz()⌋ (+1e-9 s of slack), exactly as
  /// recorded except the frame number (and table references' effective frames
  /// clamped to ≤ `frame`); `render_flags` is ignored.
  scene::FrameDescription state_at(double show_time_s, std::uint64_t frame, std::uint32_t render_flags) const;

  /// Every distinct atmosphere version the show uses when sampled at `fps`
  /// (keyframed: every frame of frame_count(fps); recordings: the recorded
  /// ones), in order of first use. Includes the scene's own atmospheres when
  /// they are used.
  std::vector<AtmosphereVersion> atmosphere_versions(double fps) const;
  /// The version with this table hash (any the show produced so far or
  /// recorded); nullptr if unknown.
  const AtmosphereVersion* find_version(const scene::TableHash& table_hash) const;

  struct Impl;
  explicit Show(std::unique_ptr<Impl> impl);

 private:
  std::unique_ptr<Impl> impl_;
};

/// Bounds on what a show file may ask for, checked while it loads
/// (docs/shows.md, "Limits"): its text (core/files.h, kMaxInputFileBytes),
/// its keys per track (100 000 by default), and the lookup-table sets its atmosphere
/// tracks step through — each is resolved now and precomputed later, so a
/// tiny step once meant thousands of sets (6 199 at a turbidity step of
/// 0.01: 14 GB of tables) before anything was said.
struct ShowLimits {
  static constexpr std::size_t kDefaultMaxTableSets = 256;
  static constexpr std::size_t kDefaultMaxKeysPerTrack = 100000;
  /// The most keys a --max-keys may allow: a million keys of a parameter
  /// track are ~30 MB of text, within the file limit, ~0.3 GB parsed.
  static constexpr std::size_t kMaxKeysPerTrackCeiling = 1000000;
  /// Distinct table sets the show's frames use, the scene's own included.
  std::size_t max_table_sets = kDefaultMaxTableSets;
  /// Keys of any one track (camera, sun, exposure, an atmosphere parameter),
  /// counted before any key is read.
  std::size_t max_keys_per_track = kDefaultMaxKeysPerTrack;
};

/// Reads and checks a show file and the scene it names. Throws
/// zenith::ConfigError naming the file, the JSON pointer of the offending key
/// and the allowed range or reason.
Show load_show(const std::filesystem::path& path, const ShowLimits& limits = {});

/// `scene` with the per-frame parts of `state` applied (camera, exposure, sun)
/// and each body's atmosphere replaced by the version `versions` holds for the
/// table hash the state names. Throws std::invalid_argument naming the body and
/// hash when a version is missing or belongs to another body.
void apply_state(const scene::FrameDescription& state, const std::map<scene::TableHash, AtmosphereVersion>& versions,
                 scene::Scene& scene);

/// Records a live session (docs/shows.md, "Recordings"): every presented frame
/// state and the atmosphere versions they reference. finish() writes the show
/// file atomically (PATH.partial, then rename); the destructor finishes if
/// finish() was not called (errors are logged, not thrown).
class ShowRecorder {
 public:
  /// `scene_path` is stored relative to the recording's folder when possible.
  ShowRecorder(std::filesystem::path path, std::filesystem::path scene_path, std::string name, double frame_rate_hz);
  ~ShowRecorder();
  ShowRecorder(const ShowRecorder&) = delete;
  ShowRecorder& operator=(const ShowRecorder&) = delete;

  /// Remembers a version (once per table hash) so playback can rebuild its tables.
  void add_version(const AtmosphereVersion& version);
  /// Appends a presented frame. Every referenced table hash must have been added.
  void record(const scene::FrameDescription& state);
  std::size_t frames() const;
  /// Writes the file; returns its path. Throws std::runtime_error on I/O errors.
  std::filesystem::path finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::show
