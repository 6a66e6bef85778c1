#include "core/json_reader.h"
#include "cluster/master/master.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <chrono>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "render/lut/table_provider.h"
#include "atmosphere/model_hash.h"
#include "cluster/link/connection.h"
#include "scene/frame_scene.h"
#include "cluster/protocol/heartbeat.h"
#include "cluster/master/atmosphere_edits.h"
#include "cluster/master/atmosphere_overrides.h"
#include "cluster/master/dome_preview.h"
#include "cluster/master/frame_barrier.h"
#include "cluster/master/heartbeat_monitor.h"
#include "cluster/master/master_status.h"
#include "cluster/master/node_sessions.h"
#include "cluster/master/node_statistics.h"
#include "cluster/master/operator_command.h"
#include "cluster/master/operator_http_server.h"
#include "cluster/master/operator_input.h"
#include "cluster/master/osc_receiver.h"
#include "cluster/master/show_start_rule.h"
#include "cluster/master/sun_override.h"
#include "cluster/master/takeover.h"
#include "cluster/master/table_preparer.h"
#include "cluster/master/table_versions.h"
#include "show/playback_clock.h"
#include "show/show.h"
#include "show/table_plan.h"
#include "render/render_flags.h"
#include "cluster/protocol/table_transfer.h"
#include "scene/scene_loader.h"
#include "core/timing.h"
#include "image/png_encoder.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::tcp;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

namespace {

using core::cat;

using core::ms_since;

}  // namespace


struct Master::Impl {
  MasterOptions options;
  SharedSecret secret;
  scene::Scene scene;
  /// Table sets, the current version of every atmosphere, the pending one
  /// (prepared by `preparer` while frames go on with the old one).
  TableVersions tables;
  std::size_t next_switch = 0;  ///< into options.atmosphere_switches (sorted by frame)
  /// The operator's atmosphere changes waiting to become table versions (not with a frame feed).
  std::optional<AtmosphereEdits> edits;
  /// A show: the operator's parameter changes applied on top of its atmospheres, and the show's
  /// own versions of the latest frame started (before the overrides).
  AtmosphereOverrides overrides;
  std::vector<AtmosphereTableRef> show_versions;
  std::string pending_change;  ///< what the pending version changes (a preset, a file, an operator's change)
  /// The operator's exposure, replacing the show's (or scene's) from the next frame on.
  std::optional<double> exposure_override;
  /// The operator's sun, replacing the show's (or the default show's) from the next frame on.
  std::optional<SunOverride> sun_override;
  std::uint32_t render_flags = 0;

  // ---- the show (docs/shows.md) ----
  std::optional<show::Show> show;
  std::optional<show::PlaybackClock> clock;
  double fps = 30.0;             ///< frames per second of show time (and of pacing)
  std::unique_ptr<show::ShowRecorder> recorder;
  FrameState frame_in_flight;    ///< the state of the frame in flight (recorded once presented)
  /// While the show's later table sets are prepared: when frame 0 may start.
  std::optional<ShowStartRule> show_start;
  /// The next frame, evaluated but not yet sent: it uses a table set that is
  /// still being prepared, or that a participant has not confirmed yet.
  std::optional<FrameState> held_frame;
  Clock::time_point held_since;
  bool held_logged = false;
  /// Why a table set of the show could not be prepared: run() rethrows it.
  std::exception_ptr preparation_error;

  asio::io_context io;
  tcp::acceptor acceptor{io};
  /// Installed once the scene's tables are ready (a show's are prepared after
  /// it: SIGINT then cancels their precompute); before, SIGINT/SIGTERM end the process at once.
  std::optional<asio::signal_set> signals;
  asio::steady_timer heartbeat_timer{io}, barrier_timer{io}, frame_timer{io};
  NodeSessions sessions;  ///< every node connection, from accept to close

  // The frame loop.
  FrameBarrier barrier;  ///< the frame in flight (or the next one), its participants, lagging nodes
  HeartbeatMonitor heartbeats{options.config.heartbeat_ms};  ///< when to send Heartbeats, when to close
  /// Playback commands from the console and the control socket.
  OperatorInput operator_input{io, [this](std::string line) { return on_command(std::move(line)); }};
  /// The operator console (docs/operator.md): the web page and JSON API, and OSC from show-control desks.
  std::optional<OperatorHttpServer> http_console;
  std::optional<OscReceiver> osc;
  /// The dome preview from the nodes' thumbnails (with the HTTP console); asked for only while on.
  std::optional<DomePreview> preview;
  bool preview_on = false;
  NodeStatistics node_statistics;  ///< per node name, for the console's status
  std::string last_version_error;  ///< the latest table version that could not be prepared, and why
  Clock::time_point frame_started, show_started;
  /// Since when frame 0 could start as far as the tables go (the wait for nodes counts from here).
  std::optional<Clock::time_point> waiting_since;
  /// When each table set of the show was sent to the nodes (for the confirmation limit).
  std::map<Digest, Clock::time_point> show_set_sent_at;
  bool started = false, stopping = false, waiting_logged = false;
  std::uint64_t presented = 0;

  /// Obtains table sets on its own thread, in order; results come back to the
  /// networking thread. Last member: stopped and joined before the rest goes.
  TablePreparer preparer{
      [this](TableSetFile set, double seconds, bool from_cache) {
        asio::post(io, [this, set = std::move(set), seconds, from_cache]() mutable {
          on_set_prepared(std::move(set), seconds, from_cache);
        });
      },
      [this](const Digest& hash, std::exception_ptr error) {
        asio::post(io, [this, hash, error] { on_set_failed(hash, error); });
      },
      [this, jobs = std::make_shared<std::atomic<int>>(0)](const TablePreparer::Job& job, bool* from_cache,
                                                           const TablePreparer::Cancelled& cancelled) {
        if (options.debug_table_delay_ms > 0 && (*jobs)++ > 0)
          for (std::uint32_t ms = 0; ms < options.debug_table_delay_ms && !cancelled(); ms += 10)
            std::this_thread::sleep_for(milliseconds(10));
        return TablePreparer::obtain_set(job, from_cache, cancelled);
      }};

  Impl(MasterOptions o, SharedSecret s) : options(std::move(o)), secret(std::move(s)) {
    std::stable_sort(options.atmosphere_switches.begin(), options.atmosphere_switches.end(),
                     [](const AtmosphereSwitch& a, const AtmosphereSwitch& b) { return a.frame < b.frame; });
  }
  ~Impl() { preparer.stop(); }

  render::TableRequest table_request() const {
    render::TableRequest request;
    request.options.sizes = render::table_sizes_by_name(options.config.table_sizes);
    request.options.max_orders = options.config.table_orders;
    request.backend = options.cpu_precompute ? render::PrecomputeBackend::Cpu : render::PrecomputeBackend::Gpu;
    request.cache_directory = options.cache_directory;
    request.show_progress = false;
    return request;
  }

  /// A job for the preparer: the set of `model` for `body`.
  TablePreparer::Job preparation_job(const std::string& body, const atmosphere::AtmosphereModel& model) const {
    return TablePreparer::Job{body, digest_from_hex(atmosphere::lookup_table_hash(model)), model, table_request()};
  }

  /// The atmosphere a switch names, resolved at the scene's wavelengths and
  /// checked against its body. Throws std::invalid_argument / ConfigError.
  std::pair<std::size_t, atmosphere::LoadedAtmosphere> resolve_switch(const AtmosphereSwitch& sw) const {
    // tables.current() lists the bodies with an atmosphere in scene order (prepare_tables).
    std::optional<std::size_t> index;
    std::size_t with_atmosphere = 0;
    for (const scene::Body& body : scene.bodies) {
      if (!body.atmosphere) continue;
      if (body.name == sw.body) index = with_atmosphere;
      ++with_atmosphere;
    }
    if (!index)
      throw std::invalid_argument(cat("atmosphere switch at frame ", sw.frame, ": the scene ", scene.source,
                                      " has no body '", sw.body, "' with an atmosphere"));
    atmosphere::LoadedAtmosphere loaded = render::load_atmosphere_argument(sw.atmosphere, {scene.wavelengths_nm});
    scene::Scene changed = scene;
    for (scene::Body& body : changed.bodies)
      if (body.name == sw.body) body.atmosphere->loaded = loaded;
    try {
      scene::check_scene(changed);
    } catch (const std::exception& e) {
      throw std::invalid_argument(
          cat("atmosphere switch at frame ", sw.frame, " (", sw.body, ": ", sw.atmosphere, "): ", e.what()));
    }
    return {*index, std::move(loaded)};
  }

  // ---- preparation ----------------------------------------------------------

  void prepare_tables() {
    const render::TableRequest request = table_request();
    if (show) return prepare_show_tables(request);
    for (const scene::Body& body : scene.bodies) {
      if (!body.atmosphere) continue;
      TableSetFile set = TablePreparer::obtain_set(preparation_job(body.name, body.atmosphere->loaded.model), nullptr);
      tables.add_current(body.name, set.table_hash);
      tables.add_version(body.name, body.atmosphere->loaded, set.table_hash);
      spdlog::info("master: tables of '{}' ready to share: version {} ({} bytes, sha256 {}…)", body.name,
                   short_hex(set.table_hash), set.bytes->size(), to_hex(set.content_sha256).substr(0, 12));
      tables.add_set(std::move(set));
    }
  }

  /// With a show: reports its table plan and hands every set it uses to the
  /// preparer, in order of first use. Frame 0 starts once its own sets are
  /// ready (offline) or once the rest are predicted ready in time (live:
  /// ShowStartRule); the later sets reach the nodes while frames go on.
  void prepare_show_tables(const render::TableRequest& request) {
    const show::TablePlan plan =
        show::plan_tables(*show, fps, request.options,
                          atmosphere::lut::TableCache(request.cache_directory.value_or(atmosphere::lut::default_cache_directory())));
    spdlog::info("master: show '{}' at {} fps needs {} table set{} ({} to precompute):\n{}", show->name(), fps,
                 plan.sets.size(), plan.sets.size() == 1 ? "" : "s", plan.missing(), show::describe(plan));
    std::vector<Digest> show_sets;
    std::vector<ShowStartRule::Set> schedule;
    for (const show::TablePlanEntry& entry : plan.sets) {
      tables.add_version(entry.version.body, entry.version.loaded, entry.version.table_hash);
      show_sets.push_back(entry.version.table_hash);
      const bool held = tables.has_set(entry.version.table_hash);  // a standby's, from the active master
      schedule.push_back({entry.version.table_hash, entry.first_frame, entry.cached, held});
      if (!held) preparer.enqueue(preparation_job(entry.version.body, entry.version.loaded.model));
    }
    tables.use_show_sets(std::move(show_sets), show->state_at(0.0, 0, render_flags).atmospheres);
    show_start.emplace(std::move(schedule), fps, options.paced);
    spdlog::info("master: preparing the show's table sets in the background; frame 0 starts {}",
                 options.paced ? "once the sets it uses are ready and the others are predicted ready before they "
                                 "are needed"
                               : "once the sets it uses are ready");
  }

  /// Networking thread: a set from the preparer.
  void on_set_prepared(TableSetFile set, double seconds, bool from_cache) {
    if (stopping) return;
    if (!show_start || !tables.is_show_set(set.table_hash)) {  // a switch or an operator's version
      on_version_prepared(std::move(set));
      return;
    }
    const Digest hash = set.table_hash;
    const auto& sets = show_start->sets();
    const auto index = std::find_if(sets.begin(), sets.end(), [&](const auto& e) { return e.table_hash == hash; }) -
                       sets.begin() + 1;
    show_start->prepared(hash, seconds, from_cache);
    tables.add_set(std::move(set));
    const TableSetFile& prepared = tables.set(hash);
    show_set_sent_at[hash] = Clock::now();
    std::size_t receivers = 0;
    sessions.for_each([&](NodeSession& s) {
      if (s.state == NodeSession::State::handshake || !s.inventory_done) return;  // gets it with its inventory
      send_table_set(s, prepared);
      ++receivers;
    });
    spdlog::info("master: table set {} of {} ('{}', version {}) ready ({:.1f} s, {}); sent to {} node{}", index,
                 sets.size(), prepared.body_name, short_hex(hash), seconds, from_cache ? "from the cache" : "precomputed",
                 receivers, receivers == 1 ? "" : "s");
    // An operator's version that is one of the show's own was waiting for it.
    if (tables.pending() && tables.pending()->hash == hash && !tables.pending()->distributed) on_version_prepared(std::nullopt);
    for (const std::uint32_t id : sessions.ids())
      if (NodeSession* s = sessions.find(id)) maybe_become_ready(*s);
    maybe_start_show();
    if (!started && !show_start->may_start() && std::none_of(sets.begin(), sets.end(), [](const auto& e) {
          return e.first_frame == 0 && !e.prepared;
        })) {
      const std::optional<double> remaining = show_start->predicted_remaining_s();
      spdlog::info("master: live show: frame 0 waits until the remaining table sets are predicted ready before they "
                   "are needed ({}), so that playback does not stall",
                   remaining ? fmt::format("about {:.0f} s of preparation left", *remaining) : "no estimate yet");
    }
  }

  /// Networking thread: the preparer could not prepare a set. A show cannot
  /// go on without it (the master stops and run() throws); a switch of the
  /// default show is abandoned and the show goes on with the current version.
  void on_set_failed(const Digest& hash, std::exception_ptr error) {
    if (stopping) return;
    std::string what = "unknown error";
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    if (show_start && tables.is_show_set(hash)) {
      preparation_error = error;
      stop(cat("table set ", short_hex(hash), " of the show could not be prepared: ", what));
      return;
    }
    if (!tables.pending() || tables.pending()->hash != hash) return;  // abandoned meanwhile (clear)
    spdlog::error("master: the new tables could not be prepared: {}; the show goes on with the current version", what);
    last_version_error = cat("table version ", short_hex(hash), " (", pending_change, "): ", what);
    tables.abandon_pending();
    maybe_start_switch();
  }

  /// A standby taking over (docs/cluster.md, "Standby master"): the table
  /// versions the active master distributed instead of preparing them, and the
  /// show from the frame after the last one it sent, its show time going on
  /// at the same step (the operator's exposure kept).
  void adopt_takeover() {
    const TakeoverState& t = *options.takeover;
    adopt_takeover_tables(t, scene, tables, !show);
    if (show) prepare_show_tables(table_request());  // the sets not received are prepared as at the start
    const FrameState& last = *t.last_frame;
    const Continuation c = continuation_of(
        t, show ? show->state_at(last.show_time_s, last.frame, render_flags)
                : scene::default_show_frame(scene, last.frame, options.sun_step_deg, tables.current(), render_flags),
        fps);
    barrier.start_at(c.next_frame);
    exposure_override = c.exposure;
    if (clock) continue_clock(c, *clock);
    for (const std::string& what : c.mismatches)
      spdlog::warn("master: taking over: the {} of frame {} differs from this standby's show (are its scene, show "
                   "and --sun-step-deg the active master's?): the picture jumps at the takeover",
                   what, last.frame);
    spdlog::info("master: taking over the show at frame {} (the active master's last was frame {}, show time {:.3f} s, "
                 "{}) with the {} table version{} it distributed",
                 c.next_frame, last.frame, last.show_time_s,
                 t.frame_in_flight() ? "in flight, not seen presented" : "presented", t.versions.size(),
                 t.versions.size() == 1 ? "" : "s");
  }

  // ---- table versions -------------------------------------------------------

  /// Sends one set: the whole transfer, or only its TableAnnounce when the
  /// node's inventory holds it (the node then loads its cached copy).
  void send_table_set(NodeSession& s, const TableSetFile& set) {
    if (auto definition = tables.definition(set.table_hash)) s.connection->send_encoded(definition);
    if (s.cached.count(set.table_hash)) {
      s.connection->send_encoded(set.frames.front());
      return;
    }
    for (const auto& f : set.frames) s.connection->send_encoded(f);
    s.chunks_sent += set.frames.size() - 1;
  }

  /// The node's inventory is complete: send what it lacks.
  void finish_inventory(NodeSession& s) {
    s.inventory_done = true;
    const std::vector<Digest> wanted = tables.wanted_sets();
    const std::uint64_t chunks_before = s.chunks_sent;
    std::size_t cached = 0;
    for (const Digest& h : wanted) {
      cached += s.cached.count(h);
      send_table_set(s, tables.set(h));
    }
    spdlog::info("master: {} '{}' holds {} of its {} table set{} in its cache: sent {} table chunk{}", to_string(s.role),
                 s.name, cached, wanted.size(), wanted.size() == 1 ? "" : "s", s.chunks_sent - chunks_before,
                 s.chunks_sent - chunks_before == 1 ? "" : "s");
    maybe_become_ready(s);
  }

  void maybe_become_ready(NodeSession& s) {
    if (s.state != NodeSession::State::tables || !s.inventory_done || s.role != PeerRole::node) return;
    if (tables.ready_with(s.tables_ready)) become_ready(s);
  }

  /// The version atmosphere current()[index] renders with now: the default
  /// show's current one; in a show the operator's override, else the show's
  /// own of the latest frame started.
  Digest effective_version(std::size_t index) const {
    if (!show) return tables.current()[index].table_hash;
    if (const auto& o = tables.override_of(index)) return o->table_hash;
    return show_version_of(index).table_hash;
  }

  /// A show: the show's own version of atmosphere current()[index] in the
  /// latest frame started (before frame 0: the first frame's).
  const AtmosphereTableRef& show_version_of(std::size_t index) const {
    const std::string& body = tables.current()[index].body_name;
    for (const AtmosphereTableRef& ref : show_versions)
      if (ref.body_name == body) return ref;
    return tables.current()[index];
  }

  /// The newest version asked for atmosphere current()[index]: its waiting
  /// change's, else its pending version, else the one it renders with.
  Digest latest_version(std::size_t index) const {
    if (const AtmosphereEdits::Edit* waiting = edits->waiting(tables.current()[index].body_name))
      return digest_from_hex(atmosphere::lookup_table_hash(waiting->loaded.model));
    if (tables.pending() && tables.pending()->ref_index == index) return tables.pending()->hash;
    return effective_version(index);
  }

  /// A show's frame about to be sent (docs/operator.md, "set during a show"):
  /// remembers the show's own versions, asks for a new operator version of
  /// every overridden body whose track has moved on (the show's new version
  /// with the operator's changes), and puts the overrides in effect in place
  /// of the show's versions.
  void apply_atmosphere_overrides(FrameState& state) {
    show_versions = state.atmospheres;
    for (const AtmosphereTableRef& ref : show_versions) {
      const std::string& body = ref.body_name;
      if (!overrides.active(body) || overrides.base(body) == ref.table_hash) continue;
      const std::size_t index = edits->index_of(body);
      // A change on its way was built on an earlier show version: follow once it is in.
      if (edits->waiting(body) || (tables.pending() && tables.pending()->ref_index == index)) continue;
      overrides.set_base(body, ref.table_hash);
      try {
        AtmosphereEdits::Edit edit = edits->resolve_parameters(
            body, overrides.apply(body, tables.version(ref.table_hash).parameters),
            cat("the show's version ", short_hex(ref.table_hash), " with ", overrides.describe(body)));
        if (digest_from_hex(atmosphere::lookup_table_hash(edit.loaded.model)) == effective_version(index)) continue;
        spdlog::info("master: the show's track of '{}' moved on to version {}: preparing it with the operator's changes",
                     body, short_hex(ref.table_hash));
        edits->enqueue(std::move(edit));
      } catch (const std::exception& e) {
        spdlog::warn("master: the show's track of '{}' moved on to version {}, but the operator's changes do not fit "
                     "it ({}); '{}' keeps the operator's version until cleared",
                     body, short_hex(ref.table_hash), e.what(), body);
      }
    }
    state.atmospheres = tables.with_overrides(std::move(state.atmospheres));
    maybe_start_switch();
  }

  /// Starts the next switch whose frame has come, else the operator's next
  /// change (one version in flight at a time).
  void maybe_start_switch() {
    if (tables.pending()) return;
    if (next_switch < options.atmosphere_switches.size() &&
        options.atmosphere_switches[next_switch].frame <= barrier.frame()) {
      const AtmosphereSwitch& sw = options.atmosphere_switches[next_switch++];
      auto [index, loaded] = resolve_switch(sw);  // checked at start-up: does not throw here
      begin_version(index, std::move(loaded), cat("frame ", barrier.frame()), sw.atmosphere);
    } else if (std::optional<AtmosphereEdits::Edit> edit = edits ? edits->take_next() : std::nullopt) {
      begin_version(edit->index, std::move(edit->loaded), "operator", edit->change);
    }
  }

  /// Atmosphere current()[index] is to become `loaded` (`why`: when or who
  /// asked; `what`: the preset, file or change, for the log): prepares its
  /// table version in the background unless it is the current one.
  void begin_version(std::size_t index, atmosphere::LoadedAtmosphere loaded, const std::string& why,
                     const std::string& what) {
    const std::string body = tables.current()[index].body_name;
    const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(loaded.model));
    if (hash == effective_version(index)) {
      spdlog::info("master: {}: '{}' already uses {}; nothing to switch", why, body, what);
      maybe_start_switch();
      return;
    }
    tables.add_version(body, loaded, hash);
    tables.begin_pending(index, hash);
    pending_change = what;
    spdlog::info("master: {}: preparing table version {} of '{}' ({}) in the background; the show goes on with "
                 "version {}",
                 why, short_hex(hash), body, what, short_hex(effective_version(index)));
    if (tables.has_set(hash)) {  // an earlier version again: already encoded
      asio::post(io, [this] { on_version_prepared(std::nullopt); });
      return;
    }
    if (tables.is_show_set(hash)) return;  // the show's own, still being prepared: on_set_prepared goes on
    preparer.enqueue(preparation_job(body, loaded.model));
  }

  /// Networking thread: the pending version's tables are ready; send them to every node.
  /// A set of a version abandoned meanwhile (cleared) is kept for later.
  void on_version_prepared(std::optional<TableSetFile> set) {
    if (stopping) return;
    if (!tables.pending() || (set && set->table_hash != tables.pending()->hash)) {
      if (set) tables.add_set(std::move(*set));
      return;
    }
    if (set) tables.add_set(std::move(*set));
    const Digest hash = tables.pending()->hash;
    const TableSetFile& prepared = tables.set(hash);
    tables.mark_distributed(Clock::now());
    std::size_t receivers = 0;
    sessions.for_each([&](NodeSession& s) {
      if (s.state == NodeSession::State::handshake || !s.inventory_done) return;  // gets it with its inventory
      // A node that holds it (an earlier version again, a show's own set) is not sent it again.
      if (s.tables_ready.count(hash) || tables.is_show_set(hash)) return;
      send_table_set(s, prepared);
      ++receivers;
    });
    spdlog::info("master: table version {} of '{}' prepared ({} bytes); sent to {} node{}", short_hex(hash),
                 prepared.body_name, prepared.bytes->size(), receivers, receivers == 1 ? "" : "s");
    maybe_apply_pending();
  }

  /// Once every ready node holds the pending version, it takes effect at the next frame to start.
  void maybe_apply_pending() {
    if (!tables.pending() || !tables.pending()->distributed || stopping) return;
    const Digest hash = tables.pending()->hash;
    std::size_t ready = 0;
    bool all_hold_it = true;
    sessions.for_each([&](const NodeSession& s) {
      if (s.state != NodeSession::State::ready) return;
      if (!s.tables_ready.count(hash)) all_hold_it = false;
      ++ready;
    });
    if (!all_hold_it) return;
    const std::uint64_t effective = barrier.next_boundary();
    const AtmosphereTableRef before = tables.apply_pending(effective);
    spdlog::info("master: table version {} of '{}' takes effect at frame {} on all {} ready node{} (was {})",
                 short_hex(hash), before.body_name, effective, ready, ready == 1 ? "" : "s",
                 short_hex(before.table_hash));
    // Nodes still joining now need the new version (they were sent it) and no longer the old one.
    for (const std::uint32_t id : sessions.ids())
      if (NodeSession* s = sessions.find(id)) maybe_become_ready(*s);
    maybe_start_switch();
  }

  /// A ready node that does not confirm a distributed version within the
  /// barrier timeout (at least 60 s: a node loads and warms the tables first)
  /// would hold the switch back forever: it is disconnected with a log line
  /// naming it, the switch goes ahead on the others, and the node rejoins at a
  /// frame boundary with the new version when it reconnects.
  void check_pending_confirmations() {
    if (!tables.pending() || !tables.pending()->distributed || stopping) return;
    const Digest hash = tables.pending()->hash;
    const double limit_ms = std::max(60000.0, static_cast<double>(options.config.barrier_timeout_ms));
    if (ms_since(tables.pending()->distributed_at) <= limit_ms) return;
    std::vector<std::shared_ptr<Connection>> late;
    sessions.for_each([&](const NodeSession& s) {
      if (s.state == NodeSession::State::ready && !s.tables_ready.count(hash)) {
        spdlog::warn("master: node '{}' did not confirm table version {} within {:.0f} ms: disconnecting it so the "
                     "switch can take effect (it rejoins with the new version when it reconnects)",
                     s.name, short_hex(hash), limit_ms);
        late.push_back(s.connection);
      }
    });
    for (const auto& connection : late) connection->close("table version not confirmed in time");
    maybe_apply_pending();
  }

  // ---- connections ----------------------------------------------------------

  void accept() {
    acceptor.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
      if (stopping) return;
      if (!ec) on_accept(std::move(socket));
      else spdlog::warn("master: accept failed: {}", ec.message());
      accept();
    });
  }

  void on_accept(tcp::socket socket) {
    boost::system::error_code ec;
    const tcp::endpoint remote = socket.remote_endpoint(ec);
    const std::string peer = ec ? std::string("unknown peer") : cat(remote.address().to_string(), ":", remote.port());
    NodeSession& session = sessions.add(std::make_shared<Connection>(std::move(socket), peer),
                                        MasterHandshake(secret, options.config.name));
    const std::uint32_t id = session.id;
    spdlog::debug("master: connection from {}", peer);
    session.connection->start([this, id](Message&& m) { on_message(id, std::move(m)); },
                              [this, id](const std::string& reason) { on_closed(id, reason); });
  }

  void on_closed(std::uint32_t id, const std::string& reason) {
    NodeSession* found = sessions.find(id);
    if (found == nullptr) return;
    const NodeSession& s = *found;
    const bool bad_peer = reason.starts_with("protocol error") || reason.find("truncated") != std::string::npos;
    if (s.state == NodeSession::State::ready || !s.name.empty())
      spdlog::log(stopping ? spdlog::level::info : spdlog::level::warn, "master: {} disconnected: {}", s.who(), reason);
    else
      spdlog::log(bad_peer ? spdlog::level::warn : spdlog::level::info, "master: {} closed: {}", s.who(), reason);
    // Release the session after the connection's handlers have returned.
    asio::post(io, [keep = sessions.take(id)] {});
    if (barrier.remove(id) && barrier.complete()) complete_frame();
    maybe_apply_pending();  // it may have been the last node without the pending version
  }

  void on_message(std::uint32_t id, Message&& message) {
    NodeSession* s = sessions.find(id);
    if (s == nullptr) return;
    try {
      if (s->state == NodeSession::State::handshake)
        sessions.on_handshake_message(*s, message, options.config, barrier.frame());
      else
        on_running_message(*s, message);
    } catch (const HandshakeError& e) {
      s->refuse(e.reason(), e.what());
    }
  }

  void become_ready(NodeSession& s) {
    s.state = NodeSession::State::ready;
    node_statistics.joined(s.name);
    spdlog::info("master: node '{}' is ready: it joins the barrier at the next frame boundary (frame {})", s.name,
                 barrier.next_boundary());
    maybe_start_show();
  }

  /// A standby master past its handshake (docs/cluster.md, "Standby master"):
  /// its first Heartbeat ends an empty inventory, so it is sent every set a
  /// node would be, then every new set, FrameState and Present. It sends only
  /// Heartbeats and Goodbye, and never joins the barrier.
  void on_standby_message(NodeSession& s, const Message& message) {
    if (std::holds_alternative<Heartbeat>(message)) {
      if (!s.inventory_done) finish_inventory(s);
    } else if (const auto* goodbye = std::get_if<Goodbye>(&message)) {
      spdlog::info("master: the standby said goodbye: {}", goodbye->reason);
      s.connection->close(cat("Goodbye: ", goodbye->reason));
    } else {
      s.close_for_protocol_violation(cat(to_string(message_type(message)), " is not sent by a standby master"));
    }
  }

  void on_running_message(NodeSession& s, const Message& message) {
    if (s.role == PeerRole::standby) return on_standby_message(s, message);
    if (!s.inventory_done) {
      if (const auto* held = std::get_if<TableReady>(&message)) {
        s.cached.insert(held->table_hash);  // any set, even one this show does not use
        return;
      }
      finish_inventory(s);  // the first other message (the node sends a Heartbeat) ends it
    }
    std::visit(
        [&](const auto& m) {
          using T = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<T, Heartbeat>) {
          } else if constexpr (std::is_same_v<T, TableReady>) {
            if (!tables.has_set(m.table_hash)) {
              s.close_for_protocol_violation("TableReady for a table set that was never sent");
              return;
            }
            s.tables_ready.insert(m.table_hash);
            maybe_become_ready(s);
            maybe_apply_pending();
          } else if constexpr (std::is_same_v<T, RenderDone>) {
            on_render_done(s, m);
          } else if constexpr (std::is_same_v<T, Thumbnail>) {
            if (!preview_on) return;  // sent before the preview was turned off
            try {
              preview->add(s.name, m);
            } catch (const std::invalid_argument& e) {
              s.close_for_protocol_violation(e.what());
            }
          } else if constexpr (std::is_same_v<T, Goodbye>) {
            spdlog::info("master: node '{}' said goodbye: {}", s.name, m.reason);
            s.connection->close(cat("Goodbye: ", m.reason));
          } else {
            s.close_for_protocol_violation(cat(to_string(message_type(message)), " is not sent by nodes"));
          }
        },
        message);
  }

  // ---- the frame loop -------------------------------------------------------

  void maybe_start_show() {
    if (started || stopping) return;
    if (show_start && !show_start->may_start() && !options.takeover) return;
    if (!waiting_since) waiting_since = Clock::now();
    const std::size_t ready = sessions.ready_count();
    const bool waited = ms_since(*waiting_since) >= options.wait_for_nodes_ms;
    if (ready == options.config.nodes.size() || (waited && ready > 0)) {
      started = true;
      show_started = Clock::now();
      spdlog::info("master: starting the show with {} of {} node{}{}", ready, options.config.nodes.size(),
                   options.config.nodes.size() == 1 ? "" : "s",
                   options.frames ? cat(", ", options.frames, " frames") : std::string(", until stopped"));
      start_frame();
    } else if (waited && !waiting_logged) {
      waiting_logged = true;
      spdlog::warn("master: no node is ready after {} ms; still waiting", options.wait_for_nodes_ms);
    }
  }

  void start_frame() {
    if (stopping) return;
    const std::vector<std::uint32_t> participants = barrier.participants_among(sessions.ready_ids());
    if (participants.empty()) {
      if (!waiting_logged) spdlog::warn("master: no node is ready for frame {}; waiting", barrier.frame());
      waiting_logged = true;
      frame_timer.expires_after(milliseconds(20));
      frame_timer.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) start_frame();
      });
      return;
    }
    waiting_logged = false;
    maybe_start_switch();
    if (!held_frame) {
      FrameState next;
      if (options.feed) {
        switch (options.feed->pop(next)) {
          case FrameFeed::Next::finished: stop("every frame of the feed was presented"); return;
          case FrameFeed::Next::wait:
            frame_timer.expires_after(milliseconds(2));
            frame_timer.async_wait([this](const boost::system::error_code& ec) {
              if (!ec) start_frame();
            });
            return;
          case FrameFeed::Next::frame: break;
        }
      } else {
        const std::uint64_t frame = barrier.frame();
        next = show ? show->state_at(clock->next_frame_time_s(), frame, render_flags)
                    : scene::default_show_frame(scene, frame, options.sun_step_deg, tables.current(), render_flags);
        if (!show) next.show_time_s = static_cast<double>(frame) / fps;  // the live session's clock
        if (exposure_override) next.exposure = *exposure_override;
        sun_override->apply(next);
      }
      held_frame = std::move(next);
      held_since = Clock::now();
      held_logged = false;
    }
    if (!participants_hold_tables(*held_frame, participants)) {
      frame_timer.expires_after(milliseconds(20));
      frame_timer.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) start_frame();
      });
      return;
    }
    if (held_logged) {
      spdlog::info("master: frame {} goes on after waiting {:.1f} s for its tables", held_frame->frame,
                   ms_since(held_since) / 1000.0);
      // Paced: the frames after the wait keep the frame rate instead of
      // catching up on the time spent waiting.
      show_started += Clock::now() - held_since;
    }
    frame_in_flight = std::move(*held_frame);
    held_frame.reset();
    if (show && !options.feed) apply_atmosphere_overrides(frame_in_flight);
    const std::uint64_t frame = options.feed ? frame_in_flight.frame : barrier.frame();
    auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(frame_in_flight));
    if (preview_on && frame % preview_interval_frames() == 0) {  // before the FrameState it names
      auto request = std::make_shared<const std::vector<std::uint8_t>>(encode(PreviewRequest{frame, kMaxThumbnailEdgePx}));
      for (const std::uint32_t id : participants) sessions.find(id)->connection->send_encoded(request);
    }
    for (const std::uint32_t id : participants) sessions.find(id)->connection->send_encoded(encoded);
    sessions.send_to_standbys(encoded);
    barrier.begin(frame, participants);
    frame_started = Clock::now();
    spdlog::debug("master: frame {} sent to {} node{}", frame, participants.size(), participants.size() == 1 ? "" : "s");
    barrier_timer.expires_after(milliseconds(options.config.barrier_timeout_ms));
    barrier_timer.async_wait([this, frame](const boost::system::error_code& ec) {
      if (!ec && barrier.in_flight() && barrier.frame() == frame) on_barrier_timeout();
    });
  }

  /// Whether every participant holds (TableReady) every table set `state`
  /// uses. A set of the show may still be being prepared, or just sent: the
  /// frame then waits (logged once). A node that has not confirmed a sent set
  /// within max(60 s, the barrier timeout) is disconnected, as for switches.
  bool participants_hold_tables(const FrameState& state, const std::vector<std::uint32_t>& participants) {
    for (const AtmosphereTableRef& ref : state.atmospheres) {
      if (!tables.has_set(ref.table_hash)) {
        if (!held_logged)
          spdlog::info("master: frame {} waits for table set {} of '{}', still being prepared", state.frame,
                       short_hex(ref.table_hash), ref.body_name);
        held_logged = true;
        return false;
      }
      std::vector<std::string> missing;
      std::vector<std::shared_ptr<Connection>> late;
      const auto sent = show_set_sent_at.find(ref.table_hash);
      const double limit_ms = std::max(60000.0, static_cast<double>(options.config.barrier_timeout_ms));
      for (const std::uint32_t id : participants) {
        NodeSession* s = sessions.find(id);
        if (s == nullptr || s->tables_ready.count(ref.table_hash)) continue;
        missing.push_back(s->name);
        if (sent != show_set_sent_at.end() && ms_since(sent->second) > limit_ms) {
          spdlog::warn("master: node '{}' did not confirm table set {} within {:.0f} ms: disconnecting it so that "
                       "frame {} can go on (it rejoins with the set when it reconnects)",
                       s->name, short_hex(ref.table_hash), limit_ms, state.frame);
          late.push_back(s->connection);
        }
      }
      for (const auto& connection : late) connection->close("table set not confirmed in time");
      if (!missing.empty()) {
        if (!held_logged)
          spdlog::info("master: frame {} waits for node{} '{}' to load table set {} of '{}'", state.frame,
                       missing.size() == 1 ? "" : "s", fmt::join(missing, "', '"), short_hex(ref.table_hash),
                       ref.body_name);
        held_logged = true;
        return false;
      }
    }
    return true;
  }

  void on_render_done(NodeSession& s, const RenderDone& done) {
    switch (barrier.on_render_done(s.id, done.frame)) {
      case FrameBarrier::Report::counted:
        node_statistics.rendered(s.name, done.render_ms, barrier.complete() && barrier.participant_count() > 1);
        if (barrier.complete()) complete_frame();
        return;
      case FrameBarrier::Report::rejoins:
        node_statistics.rendered(s.name, done.render_ms, false);
        node_statistics.rejoined(s.name);
        spdlog::info("master: node '{}' finished frame {} late; it rejoins the barrier at frame {}", s.name,
                     done.frame, barrier.next_boundary());
        return;
      case FrameBarrier::Report::ignored_lagging: return;
      case FrameBarrier::Report::ignored:
        spdlog::debug("master: ignoring RenderDone {} from node '{}' (frame {} in flight)", done.frame, s.name,
                      barrier.frame());
        return;
    }
  }

  void on_barrier_timeout() {
    for (const std::uint32_t id : barrier.drop_unfinished())
      if (const NodeSession* s = sessions.find(id)) {
        node_statistics.dropped(s->name);
        spdlog::warn("master: node '{}' missed the barrier of frame {} (no RenderDone within {} ms): dropped from the "
                     "barrier; the show goes on without it",
                     s->name, barrier.frame(), options.config.barrier_timeout_ms);
      }
    complete_frame();
  }

  void complete_frame() {
    barrier_timer.cancel();
    const FrameBarrier::Release release = barrier.release();
    const std::uint64_t frame = release.frame;
    const Present present{frame};
    auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(present));
    for (const std::uint32_t id : release.present_to)
      if (NodeSession* s = sessions.find(id)) s->connection->send_encoded(encoded);
    sessions.send_to_standbys(encoded);
    spdlog::info("master: present frame {} on {} node{} ({:.1f} ms)", frame, release.present_to.size(),
                 release.present_to.size() == 1 ? "" : "s", ms_since(frame_started));
    if (recorder) {
      for (const AtmosphereTableRef& r : frame_in_flight.atmospheres) recorder->add_version(tables.version(r.table_hash));
      recorder->record(frame_in_flight);
    }
    if (options.feed) options.feed->presented(frame);
    ++presented;
    if (options.frames != 0 && presented >= options.frames) {
      stop(cat("show finished after ", presented, " frames"));
      return;
    }
    if (clock && clock->finished() && !options.feed) {
      stop(cat("show '", show->name(), "' finished after ", presented, " frames"));
      return;
    }
    if (!options.paced) {
      asio::post(io, [this] { start_frame(); });
      return;
    }
    // Pace: frame N starts no earlier than show start + N / rate.
    const auto due = show_started + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(static_cast<double>(presented) / fps));
    frame_timer.expires_at(std::max(due, Clock::now()));
    frame_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) start_frame();
    });
  }

  // ---- operator commands (docs/shows.md, "Playback"; docs/operator.md) ----------

  /// One command line from the console or the control socket; the reply line.
  /// A line that starts with "{" is a JSON command (docs/operator.md).
  /// Commands change the clock between frames, so every node gets one
  /// consistent state per frame.
  std::string on_command(std::string line) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) return "";
    if (line.front() == '{') {
      try {
        return run_operator_command(parse_operator_command_text(line), "control");
      } catch (const std::exception& e) {
        spdlog::info("master: operator (control): command refused: {}", e.what());
        return cat("error: ", e.what());
      }
    }
    if (line == "quit" || line == "stop") {
      stop("stopped by the operator");
      return "stopping";
    }
    if (!clock) {
      if (line == "status") return cat("default show at frame ", barrier.frame(), " (no show file: only status and quit)");
      return "no show is playing: only 'status' and 'quit' are available";
    }
    try {
      std::string reply = clock->apply_command(line);
      spdlog::info("master: operator: {} → {}", line, reply);
      return reply;
    } catch (const std::invalid_argument& e) {
      return cat("error: ", e.what());
    }
  }

  /// Applies one operator command from `source` ("control", "http 127.0.0.1",
  /// "osc 10.0.0.5") with a log line either way; returns the reply. Throws
  /// (std::invalid_argument, ConfigError) when the command is refused: then
  /// nothing was applied.
  std::string run_operator_command(const OperatorCommand& command, const std::string& source) {
    namespace oc = operator_command;
    try {
      std::string reply;
      if (std::holds_alternative<oc::Quit>(command)) {
        stop("stopped by the operator");
        reply = "stopping";
      } else if (const auto* exposure = std::get_if<oc::Exposure>(&command)) {
        exposure_override = exposure->exposure;
        reply = exposure->exposure ? cat("exposure ", *exposure->exposure, " from the next frame on")
                                   : std::string("the show's own exposure from the next frame on");
      } else if (const auto* set = std::get_if<oc::Set>(&command)) {
        reply = apply_set(*set);
      } else if (const auto* sun = std::get_if<oc::Sun>(&command)) {
        reply = apply_sun(*sun);
      } else if (const auto* clear = std::get_if<oc::Clear>(&command)) {
        reply = apply_clear(*clear);
      } else if (const auto* on = std::get_if<oc::Preview>(&command)) {
        reply = apply_preview(*on);
      } else if (!clock) {
        if (!std::holds_alternative<oc::Status>(command))
          throw std::invalid_argument(cat(describe(command), ": no show is playing (the default show has no clock: start "
                                                             "the master with --show FILE for play, pause, seek, rate and loop)"));
        reply = cat("default show at frame ", barrier.frame());
      } else {
        if (const auto* seek = std::get_if<oc::Seek>(&command); seek && seek->seconds > clock->duration_s())
          throw std::invalid_argument(cat("command: /seconds = ", seek->seconds, ": must be in [0, ", clock->duration_s(),
                                          "] s (the show's duration)"));
        reply = clock->apply_command(describe(command));  // the clock's own words: "seek 12.5", "loop on"
      }
      spdlog::info("master: operator ({}): {} → {}", source, describe(command), reply);
      return reply;
    } catch (const std::exception& e) {
      spdlog::info("master: operator ({}): {} refused: {}", source, describe(command), e.what());
      throw;
    }
  }

  /// An operator's `set`: checked like an atmosphere file, then prepared as a
  /// new table version in the background and switched on every node at one
  /// frame (docs/operator.md, "Live atmosphere parameters"). In a show it
  /// changes the show's parameters of the body, which then follows the
  /// show's track with the operator's changes until cleared ("set during a show").
  std::string apply_set(const operator_command::Set& set) {
    if (!edits)
      throw std::invalid_argument(cat(describe(set), ": the frames come from an offline render's feed"));
    const std::size_t index = edits->index_of(set.body);
    const Digest latest = latest_version(index);
    const AtmosphereEdits::Edit* waiting = edits->waiting(set.body);
    // The parameters the change is made to: in a show its own version's with the operator's changes so far.
    const nlohmann::json base = show ? overrides.apply(set.body, tables.version(show_version_of(index).table_hash).parameters)
                                : waiting ? waiting->loaded.parameters
                                          : tables.version(latest).parameters;
    AtmosphereEdits::Edit edit = edits->resolve(set, base);
    if (show) {
      overrides.add(set);
      overrides.set_base(set.body, show_version_of(index).table_hash);
    }
    const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(edit.loaded.model));
    if (hash == latest)
      return cat("'", set.body, "' ", edit.change, ": the tables stay version ", short_hex(hash),
                 " (the change does not shape them)");
    const std::string change = edit.change;
    edits->enqueue(std::move(edit));
    maybe_start_switch();
    const bool started_now = tables.pending() && tables.pending()->hash == hash;
    return cat("'", set.body, "' ", change, ": table version ", short_hex(hash),
               started_now ? " is being prepared" : " waits for the version before it",
               "; every node switches to it at one frame once all hold it",
               show ? " (it replaces the show's track of the body until cleared)" : "");
  }

  /// An operator's `clear` of an atmosphere: in a show, the body follows the
  /// show's track again from the next frame (every node holds the show's
  /// sets); in the default show, the scene's own atmosphere comes back as a
  /// new table version like a `set`.
  std::string clear_atmosphere(const std::string& body) {
    if (!edits) throw std::invalid_argument(cat("clear atmosphere of ", body, ": the frames come from an offline render's feed"));
    const std::size_t index = edits->index_of(body);
    const bool dropped = edits->drop(body);
    if (show) {
      const bool had = overrides.active(body) || tables.override_of(index).has_value();
      overrides.clear(body);
      if (tables.pending() && tables.pending()->ref_index == index) tables.abandon_pending();  // its set is kept when it comes
      tables.clear_override(index);
      maybe_start_switch();
      return had || dropped ? cat("'", body, "' follows the show's track again from the next frame")
                            : cat("'", body, "' has no operator changes: it follows the show's track");
    }
    AtmosphereEdits::Edit original = edits->original(body);
    const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(original.loaded.model));
    if (hash == latest_version(index)) return cat("'", body, "' has the scene's own atmosphere (table version ", short_hex(hash), ")");
    edits->enqueue(std::move(original));
    maybe_start_switch();
    return cat("'", body, "': the scene's own atmosphere, table version ", short_hex(hash),
               "; every node switches to it at one frame once all hold it");
  }

  /// An operator's `sun` (docs/operator.md, "Sun"): the show's sun replaced from the next frame on.
  std::string apply_sun(const operator_command::Sun& sun) {
    if (options.feed)
      throw std::invalid_argument(cat(describe(sun), ": the frames come from an offline render's feed"));
    const scene::SkyAngles angles = sun_override->set(sun, started ? &frame_in_flight : nullptr);
    return fmt::format("sun at elevation {}°, azimuth {}° from the next frame on, until cleared", angles.elevation_deg,
                       angles.azimuth_deg);
  }

  /// An operator's `preview`: the nodes send thumbnails with their RenderDone
  /// (every preview_interval_frames() frames) while it is on, never while off.
  std::string apply_preview(const operator_command::Preview& on) {
    if (!preview)
      throw std::invalid_argument("preview: the dome preview is served at /api/preview: start the master with --operator-port");
    preview_on = on.on;
    if (!on.on) {
      preview->clear();
      return "dome preview off: the nodes send no thumbnails";
    }
    const std::uint64_t every = preview_interval_frames();
    return cat("dome preview on: every node sends a thumbnail of each output every ",
               every == 1 ? std::string("frame") : cat(every, " frames"), " (",
               preview->layout() == DomePreview::Layout::dome ? "placed in the dome master" : "in a grid", ", ",
               preview->width_px(), "x", preview->height_px(), " px at /api/preview)");
  }

  /// Frames between two thumbnail requests: about kPreviewsPerSecond a second.
  std::uint64_t preview_interval_frames() const {
    constexpr double kPreviewsPerSecond = 2.0;
    return std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::lround(fps / kPreviewsPerSecond)));
  }

  /// The dome preview as PNG bytes (GET /api/preview), nullopt while off or empty.
  std::optional<std::string> preview_png() const {
    if (!preview_on || preview->empty()) return std::nullopt;
    const DomePreview::Picture picture = preview->compose();
    const std::vector<std::uint8_t> png = image::encode_png_rgb8(picture.width_px, picture.height_px, picture.rgb);
    return std::string(png.begin(), png.end());
  }

  /// An operator's `clear`: the show's (or scene's) own sun, exposure or atmosphere again.
  std::string apply_clear(const operator_command::Clear& clear) {
    if (clear.what == operator_command::Clear::What::atmosphere) return clear_atmosphere(clear.body);
    if (clear.what == operator_command::Clear::What::exposure) {
      exposure_override.reset();
      return "the show's own exposure from the next frame on";
    }
    sun_override->clear();
    return show ? "the show's sun track from the next frame on" : "the default show's sun from the next frame on";
  }

  /// The console's status (GET /api/status; docs/operator.md, "Status").
  nlohmann::json operator_status() const {
    return master_status(StatusSources{options.config, sessions, barrier, tables, preparer.running(), node_statistics,
                                       edits ? &*edits : nullptr, show ? &*show : nullptr, clock ? &*clock : nullptr,
                                       started, stopping, started ? &frame_in_flight : nullptr, presented, fps,
                                       exposure_override, pending_change, last_version_error,
                                       started ? std::optional(sun_override->angles_of(frame_in_flight)) : std::nullopt,
                                       sun_override->angles(), show ? &overrides : nullptr, show_versions,
                                       preview ? &*preview : nullptr, preview_on});
  }

  /// The operator console (HTTP, OSC): listening from before the tables are
  /// prepared, so a bad address or a missing token stops the master at once.
  /// Requests wait in the backlog until the networking loop runs.
  void start_operator_console() {
    const OperatorConsoleOptions& console = options.operator_console;
    const auto command = [this](const OperatorCommand& c, const std::string& source) {
      return run_operator_command(c, source);
    };
    if (console.http_port) {
      preview.emplace(options.config, warp::load_viewport_config(options.config.viewports));
      http_console.emplace(io, OperatorHttpServer::Options{console.http_host, *console.http_port, console.token},
                           OperatorHttpServer::Handlers{[this] { return operator_status(); }, command,
                                                        [this] { return preview_png(); }});
      http_console->start();
      spdlog::info("master: operator console at {} ({}; docs/operator.md)", http_console->url(),
                   console.token ? "operator token required" : "loopback only, no token");
    }
    if (console.osc_port) {
      osc.emplace(io, OscReceiver::Options{console.osc_host, *console.osc_port, console.osc_allow}, command);
      osc->start();
      spdlog::info("master: OSC on udp {}:{} (/zenith/play, /zenith/pause, /zenith/seek, /zenith/rate, /zenith/exposure, "
                   "/zenith/sun/elevation, /zenith/sun/azimuth, /zenith/atmosphere/BODY/PARAMETER; docs/operator.md)",
                   console.osc_host, osc->port());
    }
  }

  void start_operator_inputs() {
    if (options.console) {
      operator_input.read_console();
      spdlog::info("master: console commands: play, pause, toggle, seek SECONDS, rate FACTOR, loop on|off, status, quit");
    }
    if (options.control_port) {
      operator_input.listen_for_control(*options.control_port);
      spdlog::info("master: control socket on 127.0.0.1:{} (zenith show control --port {} COMMAND)",
                   *options.control_port, *options.control_port);
    }
  }

  // ---- liveness, stop -------------------------------------------------------

  void heartbeat_tick() {
    const auto now = Clock::now();
    auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(heartbeat_at(now)));
    for (const std::uint32_t id : sessions.ids()) {
      NodeSession* s = sessions.find(id);
      if (s == nullptr || !s->connection->is_open()) continue;
      switch (heartbeats.check(s->state == NodeSession::State::handshake, s->connected_at, s->connection->last_received(),
                               now)) {
        case HeartbeatMonitor::Verdict::awaiting_handshake: break;
        case HeartbeatMonitor::Verdict::handshake_overdue:
          spdlog::warn("master: closing {}: no handshake within {:.0f} ms", s->who(), heartbeats.handshake_limit_ms());
          s->connection->close("handshake timeout");
          break;
        case HeartbeatMonitor::Verdict::silent:
          spdlog::warn("master: closing {}: nothing received for {:.0f} ms", s->who(), heartbeats.silence_limit_ms());
          s->connection->close("heartbeat timeout");
          break;
        case HeartbeatMonitor::Verdict::send_heartbeat: s->connection->send_encoded(encoded); break;
      }
    }
    if (options.feed && options.feed->done() && !barrier.in_flight()) {  // the feeding side ended (or gave up)
      stop("the frame feed ended");
      return;
    }
    if (!started) maybe_start_show();
    if (started) maybe_start_switch();
    check_pending_confirmations();
    heartbeat_timer.expires_after(milliseconds(heartbeats.interval_ms()));
    heartbeat_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec && !stopping) heartbeat_tick();
    });
  }

  void stop(const std::string& reason) {
    if (stopping) return;
    stopping = true;
    if (options.feed) options.feed->master_stopped();
    spdlog::info("master: stopping: {}", reason);
    preparer.stop();  // a precompute in progress ends at its next progress report
    boost::system::error_code ec;
    acceptor.close(ec);
    operator_input.close();
    if (http_console) http_console->close();
    if (osc) osc->close();
    if (signals) signals->cancel(ec);
    heartbeat_timer.cancel();
    barrier_timer.cancel();
    frame_timer.cancel();
    // Closing may erase a session (its close handler): work on a copy.
    std::vector<std::pair<std::shared_ptr<Connection>, bool>> connections;
    sessions.for_each([&](const NodeSession& s) {
      connections.emplace_back(s.connection, s.state == NodeSession::State::handshake);
    });
    for (auto& [connection, in_handshake] : connections) {
      if (in_handshake) connection->send(Reject{RejectReason::shutting_down, "the master is stopping"});
      else connection->send(Goodbye{reason});
      connection->close_after_flush("master stopping");
    }
    // The io_context returns once every connection has flushed and closed.
  }

  int run() {
    render_flags = render::render_flags_of(render::RenderOptions{});
    fps = options.config.frame_rate_hz;
    if (options.show) {
      if (!options.atmosphere_switches.empty())
        throw std::invalid_argument(
            "atmosphere switches cannot be combined with a show: use the show's atmosphere tracks");
      show.emplace(show::load_show(*options.show));
      scene = show->scene();
      if (!options.feed) edits.emplace(scene);
      if (options.show_fps > 0.0) fps = options.show_fps;
      else if (show->kind() == show::Show::Kind::recording) fps = show->frame_rate_hz();
      clock.emplace(show->duration_s(), fps, options.loop.value_or(show->loop()));
      spdlog::info("master: playing show '{}' ({:.1f} s at {} fps, {} frames{})", show->name(), show->duration_s(), fps,
                   show->frame_count(fps), clock->looping() ? ", looping" : "");
    } else {
      scene = scene::load_scene(options.config.scene);
      edits.emplace(scene);
    }
    sun_override.emplace(scene);
    if (options.record)
      recorder = std::make_unique<show::ShowRecorder>(*options.record, show ? show->scene_path() : options.config.scene,
                                                      show ? cat(show->name(), " (recorded)") : cat(options.config.name, " session"),
                                                      fps);

    // Listen first: nodes that start now connect (the kernel queues them) and
    // are served once the tables are ready.
    const std::uint16_t port = options.port.value_or(options.config.master_port);
    tcp::resolver resolver(io);
    const tcp::endpoint endpoint = *resolver.resolve(options.config.master_host, std::to_string(port)).begin();
    acceptor.open(endpoint.protocol());
    acceptor.set_option(tcp::acceptor::reuse_address(true));
    boost::system::error_code ec;
    acceptor.bind(endpoint, ec);
    if (ec) throw std::runtime_error(cat("master: cannot listen on ", options.config.master_host, ":", port, ": ", ec.message()));
    acceptor.listen();
    start_operator_console();
    for (const AtmosphereSwitch& sw : options.atmosphere_switches) resolve_switch(sw);  // fail before any precompute
    if (options.takeover && options.takeover->last_frame) adopt_takeover();
    else prepare_tables();
    spdlog::info("master: cluster '{}' listening on {}:{} for {} node{} (heartbeat {} ms, barrier timeout {} ms, {} Hz)",
                 options.config.name, options.config.master_host, port, options.config.nodes.size(),
                 options.config.nodes.size() == 1 ? "" : "s", options.config.heartbeat_ms,
                 options.config.barrier_timeout_ms, fps);
    if (!show_start) waiting_since = Clock::now();  // a show: once its first sets are ready (maybe_start_show)
    accept();
    signals.emplace(io, SIGINT, SIGTERM);
    signals->async_wait([this](const boost::system::error_code& e, int signal) {
      if (!e) stop(cat("signal ", signal == SIGINT ? "SIGINT" : "SIGTERM"));
    });
    start_operator_inputs();
    heartbeat_tick();
    io.run();
    preparer.stop();
    if (preparation_error) std::rethrow_exception(preparation_error);
    if (recorder)
      spdlog::info("master: {} frame{} recorded in {}", recorder->frames(), recorder->frames() == 1 ? "" : "s",
                   recorder->finish().string());
    spdlog::info("master: done, {} frame{} presented", presented, presented == 1 ? "" : "s");
    return 0;
  }
};

Master::Master(MasterOptions options, SharedSecret secret)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(secret))) {}
Master::~Master() = default;
int Master::run() {
  // Whatever ends the run, a thread feeding frames must not wait for more.
  struct StopFeed {
    std::shared_ptr<FrameFeed> feed;
    ~StopFeed() {
      if (feed) feed->master_stopped();
    }
  } stop_feed{impl_->options.feed};
  return impl_->run();
}

}  // namespace zenith::cluster
