#include "cluster/node/node.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <set>
#include <thread>

#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>

#include "atmosphere/lut/table_cache.h"
#include "atmosphere/named_inputs.h"
#include "cluster/link/link_exit.h"
#include "cluster/link/master_datagrams.h"
#include "cluster/link/master_link.h"
#include "cluster/node/known_atmospheres.h"
#include "cluster/node/link_check_answer.h"
#include "cluster/node/present_schedule.h"
#include "cluster/node/render_worker.h"
#include "cluster/protocol/heartbeat.h"
#include "cluster/protocol/table_transfer.h"
#include "core/log_limiter.h"
#include "core/strings.h"
#include "core/timing.h"
#include "core/wall_clock.h"
#include "render/lut/table_provider.h"
#include "scene/scene_loader.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using Clock = std::chrono::steady_clock;

namespace {

using core::cat;

/// A node's link: its configuration's masters (the port overridden), its timeouts.
MasterLink::Setup link_setup(const NodeOptions& options) {
  MasterLink::Setup setup;
  setup.cluster_name = options.config.name;
  setup.peer_name = options.node_name;
  setup.who = cat("node '", options.node_name, "'");
  setup.masters = listed_masters(options.config, options.port);
  setup.heartbeat_ms = options.config.heartbeat_ms;
  setup.rules.connect_timeout_ms = options.connect_timeout_ms;
  setup.rules.reconnect_ms = options.reconnect_ms.value_or(options.config.reconnect_ms);
  setup.rules.attempt_timeout_ms = attempt_timeout_ms_for(setup.masters.size());
  return setup;
}

}  // namespace

struct Node::Impl {
  NodeOptions options;
  scene::Scene base_scene;
  warp::ViewportConfig viewports;
  std::vector<std::size_t> outputs;  ///< indices into viewports.outputs
  /// Every atmosphere this node can render, by table hash (both threads use it).
  KnownAtmospheres atmospheres{base_scene, options.cache_directory, options.node_name};
  atmosphere::lut::PrecomputeOptions table_options;
  std::filesystem::path node_directory;

  // ---- networking thread only ----
  asio::io_context io;
  asio::signal_set signals{io, SIGINT, SIGTERM};
  /// The connection to the master: connect, handshake, heartbeats, Goodbye.
  MasterLink link;
  TableReceiver receiver;        ///< transfers of this connection (a new one starts them afresh)
  std::set<Digest> inventory;    ///< sets found valid in the cache at the last Welcome (declared to the master)
  std::set<Digest> held_tables;  ///< sets this node holds (cached or received) and may render with
  /// Counts Welcomes: the render thread's answers carry the session of their
  /// job, and only those of the current connection go to the master.
  std::uint64_t session = 0;
  bool connected = false;  ///< welcomed, and the connection not lost since
  /// The master's latest PreviewRequest: thumbnails of that frame go with its RenderDone.
  std::optional<PreviewRequest> preview_request;
  /// Scheduled frames (docs/cluster.md, "The frame schedule"): they come in
  /// datagrams (or, where none get through, as FrameSchedule + FrameState on
  /// TCP), each with its moment on the master's clock; the schedule says when
  /// to render and present them, the timer wakes the node at the next moment.
  MasterDatagrams datagrams{io, cat("node '", options.node_name, "'"),
                            [this](MasterDatagrams::ScheduledFrame&& f) { on_scheduled_frame(f.schedule, f.state); },
                            LocalClock(options.debug_clock_faults, Clock::now())};
  PresentSchedule schedule{present_handoff(options.config.frame_rate_hz)};
  asio::steady_timer present_timer{io};
  std::optional<FrameSchedule> tcp_schedule;  ///< a FrameSchedule on TCP, for the FrameState that follows it
  core::LogLimiter late_frames_log, stale_frames_log, held_tables_log, missed_log;
  std::uint64_t reported_missed = 0;  ///< schedule.missed() at the last log line
  bool scheduled_frames = false;      ///< the master schedules its frames (else: the barrier)
  /// Every 100 ms: whether the master's datagrams stopped (the link is cut).
  asio::steady_timer link_watch{io};
  bool link_watched = false, link_quiet = false, blanked = false;
  /// A link check (`zenith cluster check`): its pings, fill and report.
  LinkCheckAnswer link_check;
  asio::steady_timer link_check_timer{io};
  LinkEnd end;  // the exit code, decided by the first finish()

  // ---- the render thread: GL, the renderer, the frame files ----
  std::optional<RenderWorker> worker;  ///< set up in run(), before the threads start

  Impl(NodeOptions o, SharedSecret secret)
      : options(std::move(o)),
        link(io, link_setup(options), std::move(secret),
             MasterLink::Events{[this](const Welcome& w) { on_welcomed(w); }, [this](const std::string&) { on_lost(); },
                                [this](const Message& m) { on_master_message(m); },
                                [this](int code) { finish(code); }}) {}

  // =========================================================================
  // Networking thread.

  void say_goodbye_and_finish(const std::string& reason, int code) {
    link.say_goodbye(reason);
    finish(code);
  }

  /// Welcomed (first, or again after a loss): a new session; the inventory
  /// tells the master which tables not to send again.
  void on_welcomed(const Welcome& welcome) {
    ++session;
    connected = true;
    receiver = TableReceiver{};
    send_inventory();
    // Datagrams go to the master's port number over UDP (docs/cluster.md, "Setting up the network").
    if (const auto master = link.master_endpoint(); master && link.datagram_key())
      datagrams.start(asio::ip::udp::endpoint(master->address(), master->port()), welcome.node_id, *link.datagram_key(),
                      welcome.master_time_ns, Clock::now());
    if (!link_watched) watch_link();
  }

  /// The master's datagrams (its clock answers, every 100 ms) stopped for
  /// 0.5 s: the link is cut. Logged once; once the scheduled frames ran out,
  /// the projectors show black where the config says "link_lost": "black"
  /// (else they hold the last frame). Logged again when datagrams come back.
  void watch_link() {
    link_watched = true;
    const auto now = Clock::now();
    const std::optional<Clock::time_point> heard = datagrams.last_heard();
    const bool quiet = scheduled_frames && heard && now - *heard > std::chrono::milliseconds(500);
    if (quiet && !link_quiet)
      spdlog::warn(
          "node '{}': nothing from the master for 0.5 s (link cut?): its scheduled frames play out, then "
          "the projectors {}",
          options.node_name, options.config.black_when_link_lost ? "show black" : "hold the last frame");
    if (!quiet && link_quiet) spdlog::info("node '{}': the master's datagrams come again", options.node_name);
    link_quiet = quiet;
    if (quiet && options.config.black_when_link_lost && !blanked && !schedule.wake_at() && schedule.pending() == 0) {
      worker->blank();
      blanked = true;
      spdlog::warn(
          "node '{}': its scheduled frames ran out: showing black until frames come again "
          "(timing.link_lost)",
          options.node_name);
    }
    link_watch.expires_after(std::chrono::milliseconds(100));
    link_watch.async_wait([this](const boost::system::error_code& ec) {
      if (!ec && !end.finished) watch_link();
    });
  }

  /// The connection is lost (MasterLink reconnects): forget the frame in
  /// flight and the transfers of that connection; the last presented frame
  /// stays on the outputs and in the window.
  void on_lost() {
    connected = false;
    preview_request.reset();
    receiver = TableReceiver{};
    datagrams.stop();
    tcp_schedule.reset();
    link_check = LinkCheckAnswer{};  // a check of that connection: the master gave up on it
    link_check_timer.cancel();
    // Scheduled frames stay: the master decided them, and each is shown at
    // its moment (a standby taking over goes on after the last one it saw).
    // A barrier's frame in flight is never presented: its Present cannot come.
    if (!scheduled_frames) worker->abandon_frames();
  }

  /// A scheduled frame (a datagram's, or FrameSchedule + FrameState on TCP):
  /// into the schedule at its moment on this node's clock. A frame whose
  /// tables this node does not hold yet is skipped (the projector keeps the
  /// last frame): a datagram may overtake the TableAnnounce on TCP.
  void on_scheduled_frame(const FrameSchedule& when, const FrameState& state) {
    if (!connected) return;
    scheduled_frames = true;
    const auto now = Clock::now();
    for (const AtmosphereTableRef& ref : state.atmospheres)
      if (!held_tables.count(ref.table_hash) || ref.effective_from_frame > state.frame) {
        if (const auto more = held_tables_log.admit(now))
          spdlog::warn(
              "node '{}': skipping scheduled frame {}: it uses table set {} of '{}', which this node does "
              "not hold yet{}",
              options.node_name, state.frame, short_hex(ref.table_hash), ref.body_name, *more);
        return;
      }
    const Clock::time_point moment = datagrams.to_local(when.present_at_ns);
    const PresentSchedule::Arrival arrival = schedule.on_frame(state, moment, now);
    if (arrival == PresentSchedule::Arrival::taken) blanked = false;
    if (arrival == PresentSchedule::Arrival::stale)
      if (const auto more = stale_frames_log.admit(now))
        spdlog::info(
            "node '{}': frame {} arrived after frame {} was presented: ignored (the network delayed or "
            "reordered its datagram){}",
            options.node_name, state.frame, schedule.last_presented().value_or(0), *more);
    if (arrival == PresentSchedule::Arrival::late)
      if (const auto more = late_frames_log.admit(now))
        spdlog::warn(
            "node '{}': frame {} arrived {:.1f} ms after its moment: dropped (the projector keeps the last "
            "frame){}",
            options.node_name, state.frame, core::ms_between(moment, now), *more);
    pump_schedule();
  }

  /// Does what the schedule says is due now (render the next frame, present
  /// the current one), then sleeps until its next moment.
  void pump_schedule() {
    const auto now = Clock::now();
    while (std::optional<PresentSchedule::Step> step = schedule.next(now)) {
      if (step->kind == PresentSchedule::Step::Kind::render) {
        const bool thumbnails = preview_request && preview_request->frame == step->frame;
        worker->render(step->state, session, thumbnails ? preview_request->edge_px : 0, step->present_at);
        if (thumbnails) preview_request.reset();
      } else {
        worker->present(step->frame, step->present_at);
      }
    }
    // At most a line a second, with the running total: a node that cannot
    // keep up misses a frame now and then, and must not flood its log.
    if (schedule.missed() > reported_missed && missed_log.admit(now)) {
      spdlog::warn(
          "node '{}': {} scheduled frame{} not presented so far (they came too late, or not at all; last "
          "presented {})",
          options.node_name, schedule.missed(), schedule.missed() == 1 ? "" : "s",
          schedule.last_presented().value_or(0));
      reported_missed = schedule.missed();
    }
    if (const std::optional<Clock::time_point> wake = schedule.wake_at()) {
      present_timer.expires_at(*wake);
      present_timer.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) pump_schedule();
      });
    }
  }

  /// A message of the master after Welcome (MasterLink: not Heartbeat, not Goodbye).
  void on_master_message(const Message& message) {
    if (const auto* next = std::get_if<FrameSchedule>(&message)) {
      tcp_schedule = *next;  // for the FrameState that follows it
    } else if (const auto* fs = std::get_if<FrameState>(&message); fs && tcp_schedule) {
      if (tcp_schedule->frame != fs->frame)
        throw std::runtime_error(
            cat("FrameSchedule of frame ", tcp_schedule->frame, " followed by FrameState ", fs->frame));
      const FrameSchedule when = *tcp_schedule;
      tcp_schedule.reset();
      on_scheduled_frame(when, *fs);
    } else if (fs) {
      for (const AtmosphereTableRef& ref : fs->atmospheres)
        if (!held_tables.count(ref.table_hash) || ref.effective_from_frame > fs->frame)
          throw std::runtime_error(cat("FrameState ", fs->frame, " uses table set ",
                                       to_hex(ref.table_hash).substr(0, 12), "… (effective from frame ",
                                       ref.effective_from_frame, ") for '", ref.body_name,
                                       "', which this node does not hold or may not use yet"));
      const bool thumbnails = preview_request && preview_request->frame == fs->frame;
      worker->render(*fs, session, thumbnails ? preview_request->edge_px : 0);
      if (thumbnails) preview_request.reset();
    } else if (const auto* check = std::get_if<LinkCheck>(&message)) {
      start_link_check(*check);
    } else if (const auto* fill = std::get_if<LinkFill>(&message)) {
      link_check.on_fill(*fill, Clock::now());
      datagrams.end_probe();
      maybe_report_link_check();
    } else if (const auto* request = std::get_if<PreviewRequest>(&message)) {
      preview_request = *request;  // for the FrameState that follows it
    } else if (const auto* p = std::get_if<Present>(&message)) {
      worker->present(p->frame);
    } else if (const auto* a = std::get_if<TableAnnounce>(&message)) {
      if (!atmospheres.knows(a->table_hash))
        throw std::runtime_error(
            cat("TableAnnounce of table set ", to_hex(a->table_hash).substr(0, 12),
                "…, which no atmosphere this node knows uses (the scene's, the presets, the atmosphere "
                "files it was given: do master and node read the same scene and files?)"));
      if (inventory.count(a->table_hash)) {
        // Declared in the inventory: the master sends no chunks; use the cached copy.
        held_tables.insert(a->table_hash);
        worker->prepare(a->table_hash, session);
      } else {
        receiver.on_announce(*a);
      }
    } else if (const auto* d = std::get_if<AtmosphereDefinition>(&message)) {
      atmospheres.define(*d, true);
    } else if (const auto* c = std::get_if<TableChunk>(&message)) {
      if (std::optional<std::vector<std::uint8_t>> bytes = receiver.on_chunk(*c)) store_tables(c->table_hash, *bytes);
    } else {
      throw std::runtime_error(cat(to_string(message_type(message)), " is not sent by a master"));
    }
  }

  /// `zenith cluster check` (docs/cluster.md, "Checking the network"): pings
  /// at the check's rate for its duration, then its fill, then the report.
  void start_link_check(const LinkCheck& check) {
    const auto now = Clock::now();
    link_check.start(check, now);
    datagrams.start_probe(std::chrono::microseconds(check.ping_interval_us), link_check.pings_until());
    spdlog::info("node '{}': link check: pinging the master every {:.1f} ms for {:.1f} s, then {} bytes to take",
                 options.node_name, check.ping_interval_us / 1e3, check.duration_ms / 1e3, check.fill_bytes);
    link_check_timer.expires_at(link_check.pings_until());
    link_check_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) maybe_report_link_check();
    });
  }

  void maybe_report_link_check() {
    const auto now = Clock::now();
    if (!link_check.complete(now)) return;
    // The wall clock against the steady one at one moment (the master compares its own pair).
    const core::WallAtSteady clocks = core::wall_at_steady();
    const std::int64_t local_ns =
        datagrams.local_clock().read_ns(Clock::time_point(std::chrono::nanoseconds(clocks.steady_ns)));
    const LinkReport report = link_check.report(datagrams.probe().summary(), datagrams.clock(), local_ns,
                                                static_cast<std::uint64_t>(std::max<std::int64_t>(clocks.wall_ns, 0)));
    link.send(report);
    const auto ms = [](std::uint64_t ns) { return static_cast<double>(ns) / 1e6; };
    spdlog::info(
        "node '{}': link check done: {} of {} pings answered, round trip {:.3f} / {:.3f} / {:.3f} ms (least, "
        "median, 99th percentile); {} bytes in {:.3f} s",
        options.node_name, report.pongs_received, report.pings_sent, ms(report.round_trip_min_ns),
        ms(report.round_trip_p50_ns), ms(report.round_trip_p99_ns), report.fill_bytes, ms(report.fill_ns) / 1e3);
  }

  void store_tables(const Digest& hash, const std::vector<std::uint8_t>& bytes) {
    const KnownAtmospheres::Entry& known = atmospheres.find(hash);
    const atmosphere::lut::TableCache cache(options.cache_directory);
    const auto path = cache.path_for(atmosphere::lut::table_set_key(known.loaded.model, table_options));
    write_file_atomically(path, bytes);
    held_tables.insert(hash);
    spdlog::info("node '{}': tables of '{}' version {} received ({} bytes, SHA-256 verified) and cached as {}",
                 options.node_name, known.body, short_hex(hash), bytes.size(), path.string());
    // The render thread loads them and renders once (shaders, uploads); then TableReady.
    worker->prepare(hash, session);
  }

  /// Right after Welcome: a TableReady for every set this node knows that its
  /// cache holds and that loads with valid checksums, then a Heartbeat that
  /// ends the inventory. The master sends such sets as a bare TableAnnounce.
  void send_inventory() {
    inventory.clear();
    const atmosphere::lut::TableCache cache(options.cache_directory);
    for (const auto& [hash, known] : atmospheres.snapshot()) {
      const auto path = cache.path_for(atmosphere::lut::table_set_key(known.loaded.model, table_options));
      std::error_code ec;
      if (!std::filesystem::exists(path, ec)) continue;
      std::string problem;
      std::optional<atmosphere::lut::LookupTables> tables = cache.load(known.loaded.model, table_options, &problem);
      if (!tables) {
        spdlog::warn("node '{}': cached tables {} are not usable ({}); the master will send them again",
                     options.node_name, path.string(), problem);
        continue;
      }
      // Checked and in memory: the render thread's prepare takes them, not the file again.
      worker->offer_tables(known.loaded.model, std::move(*tables));
      inventory.insert(hash);
      link.send(TableReady{hash});
    }
    link.send(heartbeat_at(Clock::now()));
    spdlog::info("node '{}': {} table set{} already in the cache", options.node_name, inventory.size(),
                 inventory.size() == 1 ? "" : "s");
  }

  void send_table_ready(const Digest& hash, std::uint64_t of_session) {
    if (!connected || of_session != session || !link.send(TableReady{hash})) return;
    spdlog::info("node '{}': table version {} ready", options.node_name, short_hex(hash));
  }

  /// Ends the node with `code` (first call wins): stops timers, lets queued
  /// frames flush, tells the render thread to stop after its queued jobs.
  void finish(int code) {
    if (!end.finish(code, signals)) return;
    link.stop();
    datagrams.stop();
    present_timer.cancel();
    link_watch.cancel();
    link_check_timer.cancel();
    worker->stop();
  }

  /// Render thread → networking thread: the frame's thumbnails (when the
  /// master asked for them), then its RenderDone.
  void report_render_done(const RenderDone& done, std::uint64_t of_session, std::vector<Thumbnail> thumbnails) {
    asio::post(io, [this, done, of_session, thumbnails = std::move(thumbnails)]() mutable {
      if (!connected || of_session != session) return;
      RenderDone report = done;
      report.missed_frames = schedule.missed();
      for (Thumbnail& t : thumbnails) link.send(std::move(t));
      link.send(report);
    });
  }
  void report_failure(const std::string& what) {
    asio::post(io, [this, what] { say_goodbye_and_finish(cat("node failed: ", what), kNodeExitFailed); });
  }

  int run() {
    const ClusterNodeConfig* me = options.config.find_node(options.node_name);
    if (me == nullptr)
      throw std::invalid_argument(cat("node '", options.node_name, "' is not in ", options.config.source));
    base_scene = scene::load_scene(options.scene ? *options.scene : options.config.scene);
    viewports = warp::load_viewport_config(options.config.viewports);
    for (const std::string& name : me->outputs) outputs.push_back(viewports.index_of(name));
    atmosphere::apply_table_set(options.config.table_sizes, table_options);
    table_options.max_orders = options.config.table_orders;
    atmospheres.add_scene_and_candidates(options.atmosphere_files);
    atmospheres.load_kept_definitions();
    node_directory = options.layout == FrameFileLayout::offline ? options.output_directory / "nodes" / options.node_name
                                                                : options.output_directory / options.node_name;
    std::filesystem::create_directories(node_directory);
    if (const LocalClock::Faults& f = options.debug_clock_faults; f.any())
      spdlog::warn(
          "node '{}': rehearsing a misbehaving clock: it runs {:+.1f} ppm off{} (only as its clock "
          "synchronisation reads it; the machine's time is untouched)",
          options.node_name, f.drift_ppm,
          f.steps()
              ? fmt::format(" and jumps {:+.3f} ms every {:.3f} s, then back", static_cast<double>(f.step_ns) / 1e6,
                            std::chrono::duration<double>(f.step_every).count())
              : std::string());
    worker.emplace(
        RenderWorker::Setup{options, base_scene, viewports, outputs, atmospheres, table_options, node_directory},
        RenderWorker::Events{
            [this](const RenderDone& done, std::uint64_t of_session, std::vector<Thumbnail> thumbnails) {
              report_render_done(done, of_session, std::move(thumbnails));
            },
            [this](const Digest& hash, std::uint64_t of_session) {
              asio::post(io, [this, hash, of_session] { send_table_ready(hash, of_session); });
            },
            [this](const std::string& what) { report_failure(what); },
            [this] {
              asio::post(io, [this] { say_goodbye_and_finish("the node's window was closed", kNodeExitDone); });
            }});

    signals.async_wait([this](const boost::system::error_code& ec, int signal) {
      if (ec || end.finished) return;
      spdlog::info("node '{}': {} received: leaving the cluster", options.node_name,
                   signal == SIGINT ? "SIGINT" : "SIGTERM");
      say_goodbye_and_finish("node stopped by a signal", kNodeExitDone);
    });
    link.start();
    std::thread network([this] {
      try {
        io.run();
      } catch (const std::exception& e) {
        spdlog::error("node '{}': networking failed: {}", options.node_name, e.what());
        end.exit_code = kNodeExitFailed;
        worker->stop();
      }
    });
    worker->run();
    // The network thread ends once the connection flushed and closed.
    asio::post(io, [this] {
      if (!end.finished) finish(end.exit_code);
    });
    network.join();
    worker->release_gl();
    return end.exit_code;
  }
};

Node::Node(NodeOptions options, SharedSecret secret)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(secret))) {}
Node::~Node() = default;
int Node::run() { return impl_->run(); }

}  // namespace zenith::cluster
