#pragma once
// The master's state as the operator console shows it and scripts read it
// (GET /api/status; docs/operator.md, "Status"): the playback state and show
// time, every configured node (connected, loading tables, ready or lagging;
// last render time, barrier waits, drops and rejoins, table versions held),
// every atmosphere's table version and the one on its way with its progress
// (precompute, then loading on the nodes). Built on the networking thread from
// the master's parts; reads them, changes nothing.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "cluster/link/cluster_config.h"
#include "cluster/master/atmosphere_edits.h"
#include "cluster/master/atmosphere_overrides.h"
#include "cluster/master/frame_barrier.h"
#include "cluster/master/node_sessions.h"
#include "cluster/master/node_statistics.h"
#include "cluster/master/table_preparer.h"
#include "cluster/master/table_versions.h"
#include "cluster/operator/dome_preview.h"
#include "cluster/protocol/messages.h"
#include "scene/local_horizon.h"
#include "show/playback_clock.h"
#include "show/show.h"

namespace zenith::cluster {

/// What the status is made of: the master's parts (read only) and the few
/// facts only the master's wiring knows.
struct StatusSources {
  const ClusterConfig& config;
  const NodeSessions& sessions;
  const FrameBarrier& barrier;
  const TableVersions& tables;
  std::optional<TablePreparer::Progress> preparing;  ///< the preparer's running job
  const NodeStatistics& statistics;
  const AtmosphereEdits* edits = nullptr;      ///< the operator's waiting changes; nullptr with a show
  const show::Show* show = nullptr;            ///< nullptr: the default show
  const show::PlaybackClock* clock = nullptr;  ///< a show's clock
  bool started = false;                        ///< frame 0 has started
  bool stopping = false;
  const FrameState* last_frame = nullptr;  ///< the latest frame started; nullptr before frame 0
  std::uint64_t frames_presented = 0;
  double frame_rate_hz = 30.0;
  std::optional<double> exposure_override;
  std::string pending_change;                    ///< what the pending version changes
  std::string last_error;                        ///< the latest table version that could not be prepared, and why
  std::optional<scene::SkyAngles> sun;           ///< the latest frame's sun in its camera's sky; nullopt before frame 0
  std::optional<scene::SkyAngles> sun_override;  ///< the operator's sun, nullopt: the show's
  const AtmosphereOverrides* overrides = nullptr;  ///< a show's: the operator's changes of its atmospheres
  std::vector<AtmosphereTableRef> show_versions;   ///< a show's own versions of the latest frame
  const DomePreview* preview = nullptr;            ///< the dome preview; nullptr without the HTTP console
  bool preview_on = false;
  const show::ChasePosition* timecode = nullptr;  ///< the chase of the house's timecode; nullptr: none
};

/// The status as JSON (schema in docs/operator.md, "Status"):
///   {"state": "starting"|"playing"|"paused"|"finished"|"stopping", "show_time_s", "frame",
///    "frames_presented", "frame_rate_hz", "show": {...}|null, "exposure", "exposure_override",
///    "sun": {"elevation_deg", "azimuth_deg"}|null, "sun_override": {...}|null, "preview": {...}|null,
///    "live_atmospheres", "nodes": [...], "atmospheres": [...], "last_error"}
/// Table versions are the first 16 hex digits of the table hash, as in presented.log.
nlohmann::json master_status(const StatusSources& sources);

/// The first 16 hex digits of a table hash (presented.log's form).
std::string version_hex16(const Digest& hash);

}  // namespace zenith::cluster
