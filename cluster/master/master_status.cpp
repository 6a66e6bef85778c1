#include "cluster/master/master_status.h"

#include <chrono>
#include <stdexcept>
#include <vector>

#include "core/sha256.h"

namespace zenith::cluster {
namespace {

using nlohmann::json;

/// "starting", "playing", "paused", "finished" or "stopping".
std::string playback_state(const StatusSources& s) {
  if (s.stopping) return "stopping";
  if (!s.started) return "starting";
  if (s.clock == nullptr) return "playing";  // the default show has no clock
  if (s.clock->finished()) return "finished";
  return s.clock->playing() ? "playing" : "paused";
}

/// What a node is doing: "connecting" (handshake), "loading tables", "ready", "lagging".
std::string node_state(const NodeSession& session, const FrameBarrier& barrier) {
  switch (session.state) {
    case NodeSession::State::handshake: return "connecting";
    case NodeSession::State::tables: return "loading tables";
    case NodeSession::State::ready: return barrier.is_lagging(session.id) ? "lagging" : "ready";
  }
  return "unknown";
}

/// How the node's datagrams reach the master (docs/cluster.md, "The frame
/// schedule"): "datagrams" (its ClockPings arrive: frames go that way),
/// "unreachable" (none for NodeDatagrams::kQuiet: its link is cut, its
/// projectors hold the last frame while the others go on), "tcp only" (never
/// heard on UDP: a firewall), or null without a session.
json link_status(const NodeSession* session, std::chrono::steady_clock::time_point now) {
  if (session == nullptr || session->state == NodeSession::State::handshake) return nullptr;
  if (!session->datagram_peer) return {{"state", "tcp only"}, {"silent_ms", nullptr}};
  const double silent_ms = std::chrono::duration<double, std::milli>(now - session->last_datagram).count();
  return {{"state", session->link_quiet ? "unreachable" : "datagrams"}, {"silent_ms", silent_ms}};
}

/// One configured node: its newest open session, if any, and its statistics.
json node_status(const StatusSources& s, const ClusterNodeConfig& node) {
  // The newest session of the node (a reconnecting node replaces its old one).
  const NodeSession* session = nullptr;
  s.sessions.for_each([&](const NodeSession& candidate) {
    if (candidate.name == node.name && candidate.connection->is_open()) session = &candidate;
  });
  const NodeStatistics::Counts counts = s.statistics.of(node.name);
  json held = json::array();
  if (session != nullptr)
    for (const Digest& hash : session->tables_ready) held.push_back(version_hex16(hash));
  return {
      {"name", node.name},
      {"host", node.host},
      {"state", session == nullptr ? std::string("disconnected") : node_state(*session, s.barrier)},
      {"address", session == nullptr ? json(nullptr) : json(session->connection->peer())},
      {"last_render_ms", counts.last_render_ms ? json(*counts.last_render_ms) : json(nullptr)},
      {"frames_rendered", counts.frames_rendered},
      {"barrier_waits", counts.barrier_waits},
      {"drops", counts.drops},
      {"rejoins", counts.rejoins},
      {"joins", counts.joins},
      {"presents", counts.presents},
      {"late_presents", counts.late_presents},
      {"last_present_ms", counts.last_present_ms ? json(*counts.last_present_ms) : json(nullptr)},
      {"missed_frames", counts.missed_frames},
      {"tables", counts.tables_s ? json{{"bytes", counts.tables_bytes}, {"seconds", *counts.tables_s}} : json(nullptr)},
      {"link", link_status(session, std::chrono::steady_clock::now())},
      {"tables_held", std::move(held)}};
}

/// The version on its way: its stage, the precompute's progress, the nodes holding it.
json pending_status(const StatusSources& s, const TableVersions::Pending& pending) {
  std::size_t ready = 0, holding = 0;
  s.sessions.for_each([&](const NodeSession& session) {
    if (session.state != NodeSession::State::ready) return;
    ++ready;
    holding += session.tables_ready.count(pending.hash);
  });
  std::string stage = "waiting to be prepared";
  json precompute_stage = nullptr;
  double fraction = 0.0;
  if (pending.distributed) {
    stage = "loading on the nodes";
    fraction = 1.0;
  } else if (s.preparing && s.preparing->table_hash == pending.hash) {
    stage = "preparing";
    precompute_stage = s.preparing->stage;
    fraction = s.preparing->fraction;
  }
  return {{"version", version_hex16(pending.hash)},
          {"change", s.pending_change},
          {"stage", stage},
          {"precompute_stage", precompute_stage},
          {"fraction", fraction},
          {"nodes_holding", holding},
          {"nodes_ready", ready}};
}

/// One atmosphere (current()[index] or the latest frame's): version, parameters, pending and waiting changes.
json atmosphere_status(const StatusSources& s, std::size_t index, const AtmosphereTableRef& ref) {
  json parameters = nullptr;
  try {
    parameters = s.tables.version(ref.table_hash).parameters;
  } catch (const std::out_of_range&) {  // every version in use was added; keep the status whole regardless
  }
  const auto& pending = s.tables.pending();
  const AtmosphereEdits::Edit* waiting = s.edits != nullptr ? s.edits->waiting(ref.body_name) : nullptr;
  json show_version = nullptr;
  for (const AtmosphereTableRef& own : s.show_versions)
    if (own.body_name == ref.body_name) show_version = version_hex16(own.table_hash);
  const bool overridden = s.overrides != nullptr && s.overrides->active(ref.body_name);
  return {{"body", ref.body_name},
          {"version", version_hex16(ref.table_hash)},
          {"effective_from_frame", ref.effective_from_frame},
          {"parameters", std::move(parameters)},
          {"pending", pending && pending->ref_index == index ? pending_status(s, *pending) : json(nullptr)},
          {"waiting", waiting != nullptr ? json(waiting->change) : json(nullptr)},
          {"show_version", std::move(show_version)},
          {"operator_changes", overridden ? json(s.overrides->describe(ref.body_name)) : json(nullptr)}};
}

/// {"on", "layout", "width_px", "height_px", "tiles", "outputs", "frame", "oldest_frame"}, or null without a preview.
json preview_status(const StatusSources& s) {
  if (s.preview == nullptr) return nullptr;
  const auto frame = [](std::optional<std::uint64_t> f) { return f ? json(*f) : json(nullptr); };
  return {{"on", s.preview_on},
          {"layout", s.preview->layout() == DomePreview::Layout::dome ? "dome" : "grid"},
          {"width_px", s.preview->width_px()},
          {"height_px", s.preview->height_px()},
          {"tiles", s.preview->tiles()},
          {"outputs", s.preview->outputs()},
          {"frame", frame(s.preview->newest_frame())},
          {"oldest_frame", frame(s.preview->oldest_frame())}};
}

/// {"elevation_deg", "azimuth_deg"}, or null.
json sky_angles(const std::optional<scene::SkyAngles>& angles) {
  if (!angles) return nullptr;
  return {{"elevation_deg", angles->elevation_deg}, {"azimuth_deg", angles->azimuth_deg}};
}

/// The chase of the house's timecode: {"state", "last", "rate", "offset", "drift_ppm", "locates", "before_start"},
/// or null.
json timecode_status(const show::ChasePosition* p) {
  if (p == nullptr) return nullptr;
  return {{"state", show::to_string(p->state)},
          {"last", p->last ? json(show::format_timecode(*p->last, p->rate)) : json(nullptr)},
          {"rate", show::to_string(p->rate)},
          {"offset", show::format_timecode(show::timecode_at_seconds(p->offset_s, p->rate), p->rate)},
          {"drift_ppm", p->drift_ppm},
          {"locates", p->locates},
          {"before_start", p->before_start}};
}

}  // namespace

std::string version_hex16(const Digest& hash) { return core::to_hex(hash).substr(0, 16); }

json master_status(const StatusSources& s) {
  json show = nullptr;
  if (s.show != nullptr && s.clock != nullptr)
    show = {{"name", s.show->name()},
            {"duration_s", s.clock->duration_s()},
            {"time_s", s.clock->time_s()},
            {"rate", s.clock->rate()},
            {"loop", s.clock->looping()}};
  json nodes = json::array();
  for (const ClusterNodeConfig& node : s.config.nodes) nodes.push_back(node_status(s, node));
  // Every atmosphere of the latest frame (a show's tracks change them); before frame 0, the current versions.
  const std::vector<AtmosphereTableRef>& refs =
      s.last_frame != nullptr && s.show != nullptr ? s.last_frame->atmospheres : s.tables.current();
  json atmospheres = json::array();
  for (std::size_t i = 0; i < refs.size(); ++i) atmospheres.push_back(atmosphere_status(s, i, refs[i]));
  return {{"state", playback_state(s)},
          {"show_time_s", s.last_frame != nullptr ? s.last_frame->show_time_s : 0.0},
          {"frame", s.last_frame != nullptr ? json(s.last_frame->frame) : json(nullptr)},
          {"frames_presented", s.frames_presented},
          {"frame_rate_hz", s.frame_rate_hz},
          {"show", std::move(show)},
          {"exposure", s.last_frame != nullptr ? json(s.last_frame->exposure) : json(nullptr)},
          {"exposure_override", s.exposure_override ? json(*s.exposure_override) : json(nullptr)},
          {"sun", sky_angles(s.sun)},
          {"sun_override", sky_angles(s.sun_override)},
          {"preview", preview_status(s)},
          {"live_atmospheres", s.edits != nullptr},
          {"nodes", std::move(nodes)},
          {"atmospheres", std::move(atmospheres)},
          {"last_error", s.last_error.empty() ? json(nullptr) : json(s.last_error)},
          {"timecode", timecode_status(s.timecode)}};
}

}  // namespace zenith::cluster
