#pragma once
// The master's table schedule (docs/cluster.md, "Shared tables" and "Table
// versions"; docs/shows.md, "Table sets"; docs/operator.md, "Live atmosphere
// parameters"): which table set each node is sent and when, which version
// every atmosphere renders with, and when a new one takes effect.
//
//   the scene's sets ──► prepared before the first frame (prepare_initial)
//   a show's sets   ──► prepared in order of first use while frames go on;
//                       frame 0 starts once ShowStartRule allows, a frame
//                       waits until every participant holds its sets
//   a new version   ──► (a --switch-atmosphere frame, an operator's `set`/`clear`)
//                       prepared in the background, sent to every node, and
//                       switched at one frame once every ready node confirmed
//                       it (TableReady); a node that does not confirm within
//                       max(60 s, the barrier timeout) is disconnected
//
// It keeps the bookkeeping (TableVersions, the operator's AtmosphereEdits and
// a show's AtmosphereOverrides) and makes every decision; what needs sockets,
// threads or the frame loop it asks of the master through Actions, and it
// reads the nodes through NodeSessions (whose connections it never touches).
// No io_context, no clock of its own: tests/cluster/table_schedule_test.cpp
// drives it with fake sessions and a hand-set clock. Networking thread only.
#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "atmosphere/parameters.h"
#include "cluster/link/cluster_config.h"
#include "cluster/link/takeover_state.h"
#include "cluster/master/atmosphere_edits.h"
#include "cluster/master/atmosphere_overrides.h"
#include "cluster/master/atmosphere_switch.h"
#include "cluster/master/frame_barrier.h"
#include "cluster/master/node_sessions.h"
#include "cluster/master/show_start_rule.h"
#include "cluster/master/table_preparer.h"
#include "cluster/master/table_versions.h"
#include "cluster/operator/operator_command.h"
#include "cluster/protocol/messages.h"
#include "scene/scene.h"
#include "show/show.h"

namespace zenith::cluster {

/// Invariants: at most one version on its way (TableVersions::pending); a
/// switch or an operator's change waits its turn (switches by frame, then
/// the operator's changes in the order asked); a node joins the barrier only
/// once it holds every set the frames use; a version takes effect at one
/// frame boundary for every ready node.
class TableSchedule {
 public:
  using Clock = std::chrono::steady_clock;
  using Bytes = std::shared_ptr<const std::vector<std::uint8_t>>;

  /// What the schedule does through the master.
  struct Actions {
    /// Queues encoded messages on `session`'s connection.
    std::function<void(NodeSession& session, const Bytes& bytes)> send;
    /// Closes `session`'s connection; its close handler may remove it.
    std::function<void(NodeSession& session, const std::string& reason)> close;
    /// Prepares a set on the preparer's thread; the result comes back through
    /// on_set_prepared or on_set_failed, on this thread.
    std::function<void(TablePreparer::Job job)> prepare;
    /// Runs `f` later on this thread, once the current handler has returned.
    std::function<void(std::function<void()> f)> defer;
    /// `session` holds every set the frames use: it joins the barrier.
    std::function<void(NodeSession& session)> node_ready;
    /// A set of the show is ready: frame 0 may be able to start now.
    std::function<void()> show_set_ready;
    /// Whether frame 0 has started.
    std::function<bool()> started;
    /// A set of the show could not be prepared: the show cannot go on.
    std::function<void(const std::string& reason, std::exception_ptr error)> show_failed;
    std::function<Clock::time_point()> now = [] { return Clock::now(); };
  };

  struct Options {
    render::TableRequest request;            ///< precompute options, backend and cache of every set
    std::uint32_t barrier_timeout_ms = 0;    ///< a confirmation is late after max(60 s, this)
    std::vector<AtmosphereSwitch> switches;  ///< the default show's switches, any order
    double fps = 30.0;                       ///< a show's frames per second (its table plan)
    bool paced = true;                       ///< live (ShowStartRule)
    bool operator_changes = true;            ///< false: the frames come from an offline render's feed
  };

  /// The precompute options and cache of every set of the cluster `config`
  /// (its table sizes and orders), on the CPU with `cpu_precompute`.
  static render::TableRequest request_for(const ClusterConfig& config,
                                          const std::optional<std::filesystem::path>& cache_directory,
                                          bool cpu_precompute);

  /// `scene` is the master's (a show's scene with a show); `show` nullptr for
  /// the default show. `sessions` and `barrier` are the master's, read here.
  TableSchedule(Options options, const scene::Scene& scene, const show::Show* show, NodeSessions& sessions,
                const FrameBarrier& barrier, Actions actions);

  // ---- before the first frame ----
  /// Checks every switch against the scene (fail before any precompute).
  /// Throws std::invalid_argument / ConfigError naming the switch.
  void check_switches() const;
  /// The default show: every atmosphere's set obtained now (`obtain`: cache
  /// or precompute). A show: its plan reported and every set it uses handed
  /// to the preparer in order of first use (ShowStartRule decides when frame
  /// 0 may start).
  void prepare_initial(const std::function<TableSetFile(const TablePreparer::Job&)>& obtain);
  /// A standby taking over: the versions the active master distributed as
  /// the tables; a show's sets not received are prepared as at the start.
  void adopt_takeover(const TakeoverState& state);
  /// Whether frame 0 may start as far as the tables go (a show waits for ShowStartRule).
  bool may_start() const;
  /// Whether a show's sets are prepared while frames go on (ShowStartRule decides when frame 0 starts).
  bool prepares_show_sets() const { return show_start_.has_value(); }
  /// The master is stopping: nothing more is sent, prepared or switched.
  void stop() { stopped_ = true; }

  // ---- results of the preparer ----
  void on_set_prepared(TableSetFile set, double seconds, bool from_cache);
  void on_set_failed(const Digest& hash, std::exception_ptr error);

  // ---- the nodes ----
  /// The node's inventory is complete: sends what it lacks.
  void finish_inventory(NodeSession& session);
  /// The node's TableReady for `hash`: false when that set was never sent (a protocol violation).
  bool on_table_ready(NodeSession& session, const Digest& hash);
  /// A node left: it may have been the last one without the pending version.
  void on_node_left() { maybe_apply_pending(); }
  /// Disconnects every ready node that has not confirmed the distributed
  /// pending version in time (the heartbeat tick).
  void check_confirmations();

  // ---- the frames ----
  /// Starts the next switch whose frame has come, else the operator's next
  /// change (one version in flight at a time).
  void maybe_start_switch();
  /// A show's frame about to be sent: remembers the show's own versions,
  /// asks for a new operator version of every overridden body whose track has
  /// moved on, and puts the overrides in effect in place of the show's versions.
  void apply_overrides(FrameState& state);
  /// Whether every participant holds every set `state` uses. A set of the
  /// show may still be being prepared, or just sent: the frame then waits
  /// (logged when `log`). A node that has not confirmed a sent set in time is
  /// disconnected, as for switches.
  bool participants_hold(const FrameState& state, const std::vector<std::uint32_t>& participants, bool log);

  // ---- the operator's atmosphere commands ----
  /// `set` (docs/operator.md, "Live atmosphere parameters"): checked like an
  /// atmosphere file, prepared as a new version and switched at one frame; in
  /// a show it replaces the body's track until cleared. Returns the reply.
  /// Throws (std::invalid_argument, ConfigError) when refused.
  std::string set_atmosphere(const operator_command::Set& set);
  /// `clear` of an atmosphere: a show's track again, or the scene's own
  /// atmosphere as a new version. Returns the reply; throws when refused.
  std::string clear_atmosphere(const std::string& body);

  // ---- read by the status and the frame loop ----
  const TableVersions& tables() const { return tables_; }
  /// The version atmosphere current()[index] renders with now.
  Digest effective_version(std::size_t index) const;
  const AtmosphereEdits* edits() const { return edits_ ? &*edits_ : nullptr; }
  const AtmosphereOverrides& overrides() const { return overrides_; }
  /// A show's own versions of the latest frame started (before the overrides).
  const std::vector<AtmosphereTableRef>& show_versions() const { return show_versions_; }
  const std::string& pending_change() const { return pending_change_; }
  const std::string& last_error() const { return last_error_; }

 private:
  std::pair<std::size_t, atmosphere::LoadedAtmosphere> resolve_switch(const AtmosphereSwitch& sw) const;
  TablePreparer::Job job(const std::string& body, const atmosphere::AtmosphereModel& model) const;
  void prepare_show_sets();
  void send_set(NodeSession& session, const TableSetFile& set);
  void maybe_become_ready(NodeSession& session);
  void every_node_maybe_ready();
  const AtmosphereTableRef& show_version_of(std::size_t index) const;
  Digest latest_version(std::size_t index) const;
  void begin_version(std::size_t index, atmosphere::LoadedAtmosphere loaded, const std::string& why,
                     const std::string& what);
  void on_version_prepared(std::optional<TableSetFile> set);
  void maybe_apply_pending();
  /// max(60 s, the barrier timeout): how long a node has to confirm a set.
  double confirmation_limit_ms() const;
  double ms_since(Clock::time_point t) const;

  Options options_;
  const scene::Scene& scene_;
  const show::Show* show_;
  NodeSessions& sessions_;
  const FrameBarrier& barrier_;
  Actions actions_;

  TableVersions tables_;
  std::size_t next_switch_ = 0;  ///< into options_.switches (sorted by frame)
  /// The operator's changes waiting to become table versions (not with a frame feed).
  std::optional<AtmosphereEdits> edits_;
  /// A show: the operator's parameter changes on top of its atmospheres.
  AtmosphereOverrides overrides_;
  std::vector<AtmosphereTableRef> show_versions_;
  std::string pending_change_;  ///< what the pending version changes (a preset, a file, an operator's change)
  std::string last_error_;      ///< the latest table version that could not be prepared, and why
  /// While the show's later table sets are prepared: when frame 0 may start.
  std::optional<ShowStartRule> show_start_;
  /// When each table set of the show was sent to the nodes (for the confirmation limit).
  std::map<Digest, Clock::time_point> show_set_sent_at_;
  bool stopped_ = false;
};

}  // namespace zenith::cluster
