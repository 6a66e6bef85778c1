#include "cluster/master/master.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "cluster/link/connection.h"
#include "cluster/master/frame_barrier.h"
#include "cluster/master/frame_loop.h"
#include "cluster/master/heartbeat_monitor.h"
#include "cluster/master/master_desk.h"
#include "cluster/master/node_datagrams.h"
#include "cluster/master/node_listener.h"
#include "cluster/master/node_sessions.h"
#include "cluster/master/node_statistics.h"
#include "cluster/master/playback.h"
#include "cluster/master/table_preparer.h"
#include "cluster/master/table_schedule.h"
#include "cluster/master/takeover.h"
#include "cluster/operator/operator_desk.h"
#include "core/log_limiter.h"
#include "core/strings.h"
#include "core/timing.h"
#include "scene/frame_scene.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using Clock = std::chrono::steady_clock;
using core::cat;
using std::chrono::milliseconds;

/// The wiring: the parts (table_schedule.h, the operator's desk, frame_loop.h,
/// node_listener.h), the message dispatch, heartbeats, signals and stopping.
struct Master::Impl {
  MasterOptions options;
  Playback play;  ///< the show or the default show's scene, the frame rate, the recorder (load_playback)
  scene::Scene& scene = play.scene;
  std::optional<show::Show>& show = play.show;
  std::optional<show::PlaybackClock>& clock = play.clock;
  double& fps = play.fps;
  /// Why a table set of the show could not be prepared: run() rethrows it.
  std::exception_ptr preparation_error;

  asio::io_context io;
  /// Installed once the scene's tables are ready (a show's are prepared after
  /// it: SIGINT then cancels their precompute); before, SIGINT/SIGTERM end the process at once.
  std::optional<asio::signal_set> signals;
  asio::steady_timer heartbeat_timer{io};
  NodeSessions sessions;                  ///< every node connection, from accept to close
  NodeListener listener;                  ///< accepts connections as sessions in their handshake
  NodeDatagrams datagrams{io, sessions};  ///< the nodes' ClockPings answered, scheduled frames sent
  core::LogLimiters anonymous_closes;     ///< log lines of connections closed before their Hello, per kind of reason
  FrameBarrier barrier;                   ///< the frame in flight (or the next one), its participants, lagging nodes
  HeartbeatMonitor heartbeats{options.config.heartbeat_ms};  ///< when to send Heartbeats, when to close
  NodeStatistics node_statistics;                            ///< per node name, for the console's status
  FrameProgress progress;  ///< frame 0 started, stopping, frames presented, the frame in flight
  // Made once the show is loaded (make_parts):
  std::optional<TableSchedule> tables;  ///< which set each node gets and when, every version
  std::optional<MasterDesk> door;       ///< what the operator's desk may read of the parts above and ask of them
  std::optional<OperatorDesk> desk;     ///< the operator's commands and overrides, the status
  std::optional<FrameLoop> loop;        ///< frames started, held for tables, sent, presented, paced

  /// Obtains table sets on its own thread, in order; results come back to the
  /// networking thread. Last member: stopped and joined before the rest goes.
  TablePreparer preparer{[this](TableSetFile set, double seconds, bool from_cache) {
                           asio::post(io, [this, set = std::move(set), seconds, from_cache]() mutable {
                             tables->on_set_prepared(std::move(set), seconds, from_cache);
                           });
                         },
                         [this](const Digest& hash, std::exception_ptr error) {
                           asio::post(io, [this, hash, error] { tables->on_set_failed(hash, error); });
                         },
                         TablePreparer::obtain_with_delay(options.debug_table_delay_ms)};

  Impl(MasterOptions o, SharedSecret secret)
      : options(std::move(o)),
        listener(
            io, sessions, std::move(secret), options.config.name,
            [this](std::uint32_t id, Message&& m) { on_message(id, std::move(m)); },
            [this](std::uint32_t id, const std::string& reason) { on_closed(id, reason); }) {}
  ~Impl() { preparer.stop(); }

  // ---- the parts ----------------------------------------------------------------

  void make_parts() {
    TableSchedule::Actions actions;
    actions.send = [](NodeSession& s, const TableSchedule::Bytes& bytes) { s.connection->send_encoded(bytes); };
    actions.close = [](NodeSession& s, const std::string& reason) { s.connection->close(reason); };
    actions.prepare = [this](TablePreparer::Job job) { preparer.enqueue(std::move(job)); };
    actions.defer = [this](std::function<void()> f) { asio::post(io, std::move(f)); };
    actions.node_ready = [this](NodeSession& s) { become_ready(s); };
    actions.show_set_ready = [this] { loop->maybe_start(); };
    actions.started = [this] { return progress.started; };
    actions.show_failed = [this](const std::string& reason, std::exception_ptr error) {
      preparation_error = error;
      stop(reason);
    };
    tables.emplace(TableSchedule::Options{TableSchedule::request_for(options.config, options.cache_directory,
                                                                     options.cpu_precompute),
                                          options.config.barrier_timeout_ms, options.atmosphere_switches, fps,
                                          options.paced, !(show && options.feed)},
                   scene, show ? &*show : nullptr, sessions, barrier, std::move(actions));
    door.emplace(MasterDesk::Parts{
        options.config, sessions, barrier, *tables, node_statistics, progress, show ? &*show : nullptr,
        clock ? &*clock : nullptr, fps, [this] { return preparer.running(); },
        [this](const std::string& reason) { stop(reason); }, play.timecode ? &play.chased : nullptr});
    desk.emplace(*door,
                 OperatorDesk::Setup{options.config, show ? &*show : nullptr, clock ? &*clock : nullptr, fps,
                                     options.feed != nullptr, play.timecode ? &play.timecode->chase : nullptr},
                 scene);
    loop.emplace(io, FrameLoop::Parts{options, play, sessions, barrier, *tables, *desk, node_statistics, progress,
                                      datagrams, [this](const std::string& reason) { stop(reason); }});
  }

  /// A standby taking over (docs/cluster.md, "Standby master"): the table
  /// versions the active master distributed instead of preparing them, and the
  /// show from the frame after the last one it sent, its show time going on
  /// at the same step (the operator's exposure kept).
  void adopt_takeover() {
    const TakeoverState& t = *options.takeover;
    tables->adopt_takeover(t);
    const FrameState& last = *t.last_frame;
    const FrameState expected = show ? show->state_at(last.show_time_s, last.frame, play.render_flags)
                                     : scene::default_show_frame(scene, last.frame, options.sun_step_deg,
                                                                 tables->tables().current(), play.render_flags);
    const Continuation c = continue_show(t, expected, fps);
    barrier.start_at(c.next_frame);
    desk->set_exposure(c.exposure);
    // The operator's fade (or blackout) stays on the domes: the frame's own fade unless the show gave it.
    if (last.fade != expected.fade) desk->hold_fade(last.fade, c.next_frame);
    if (clock) continue_clock(c, *clock);
    // A chase goes on from the last frame: held there until locked (the standby's input silent, or opened
    // late), never below it while the timecode catches up with a frame sent ahead of its moment.
    if (play.timecode) play.timecode->chase.continue_from(last.show_time_s);
  }

  // ---- connections ----------------------------------------------------------

  void on_closed(std::uint32_t id, const std::string& reason) {
    NodeSession* found = sessions.find(id);
    if (found == nullptr) return;
    const NodeSession& s = *found;
    const bool bad_peer = reason.starts_with("protocol error") || reason.find("truncated") != std::string::npos;
    if (s.state != NodeSession::State::handshake)  // authenticated: every loss is news
      spdlog::log(progress.stopping ? spdlog::level::info : spdlog::level::warn, "master: {} disconnected: {}", s.who(),
                  reason);
    else if (const std::optional<std::string> more =
                 anonymous_closes.admit(core::LogLimiters::kind_of(reason), core::LogLimiter::Clock::now()))
      spdlog::log(bad_peer ? spdlog::level::warn : spdlog::level::info, "master: {} closed: {}{}", s.who(), reason,
                  *more);  // not authenticated: a flood of them is a line a second per kind of reason
    // Release the session after the connection's handlers have returned.
    asio::post(io, [keep = sessions.take(id)] {});
    loop->on_node_left(id);
    tables->on_node_left();  // it may have been the last node without the pending version
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
      sessions.refuse(*s, e.reason(), e.what());
    }
  }

  void become_ready(NodeSession& s) {
    s.state = NodeSession::State::ready;
    node_statistics.joined(s.name);
    const double seconds = std::chrono::duration<double>(Clock::now() - s.inventory_done_at).count();
    node_statistics.tables_received(s.name, s.table_bytes_sent, seconds);
    const double mb = static_cast<double>(s.table_bytes_sent) / 1e6;
    spdlog::info(
        "master: node '{}' is ready: {:.1f} MB of tables sent to it, received and loaded in {:.2f} s ({:.0f} Mbit/s); "
        "it joins at the next frame boundary (frame {})",
        s.name, mb, seconds, seconds > 0 ? 8 * mb / seconds : 0.0, barrier.next_boundary());
    loop->maybe_start();
  }

  /// After the handshake. A standby master (docs/cluster.md, "Standby master"):
  /// its first Heartbeat ends an empty inventory, so it is sent every set a
  /// node would be, then every new set, FrameState and Present; it sends only
  /// Heartbeats and Goodbye, and never joins the barrier. A node: its cache
  /// inventory (TableReady) up to its first other message, then confirmations,
  /// RenderDone and thumbnails.
  void on_running_message(NodeSession& s, const Message& message) {
    const bool standby = s.role == PeerRole::standby;
    if (!s.inventory_done) {
      if (const auto* held = std::get_if<TableReady>(&message); held && !standby) {
        s.cached.insert(held->table_hash);  // any set, even one this show does not use
        return;
      }
      if (!standby || std::holds_alternative<Heartbeat>(message)) tables->finish_inventory(s);
    }
    if (const auto* goodbye = std::get_if<Goodbye>(&message)) {
      spdlog::info("master: {} said goodbye: {}", standby ? std::string("the standby") : cat("node '", s.name, "'"),
                   core::escaped(goodbye->reason));
      s.connection->close(cat("Goodbye: ", core::escaped(goodbye->reason)));
    } else if (std::holds_alternative<Heartbeat>(message)) {
      // Nothing more to do: every message, a heartbeat too, already renewed the
      // connection's last_received() that the heartbeat check reads.
    } else if (standby) {
      s.close_for_protocol_violation(cat(to_string(message_type(message)), " is not sent by a standby master"));
    } else if (const auto* ready = std::get_if<TableReady>(&message)) {
      if (!tables->on_table_ready(s, ready->table_hash))
        s.close_for_protocol_violation("TableReady for a table set that was never sent");
    } else if (const auto* done = std::get_if<RenderDone>(&message)) {
      loop->on_render_done(s, *done);
    } else if (const auto* thumbnail = std::get_if<Thumbnail>(&message)) {
      try {
        desk->add_thumbnail(s.name, *thumbnail);
      } catch (const std::invalid_argument& e) {
        s.close_for_protocol_violation(e.what());
      }
    } else {
      s.close_for_protocol_violation(cat(to_string(message_type(message)), " is not sent by nodes"));
    }
  }

  // ---- liveness, stop -------------------------------------------------------

  void heartbeat_tick() {
    sessions.check_heartbeats(heartbeats, Clock::now());
    datagrams.check_links(Clock::now(), options.config.black_when_link_lost);
    if (options.feed && options.feed->done() && !barrier.in_flight())  // the feeding side ended (or gave up)
      return stop("the frame feed ended");
    if (!progress.started) loop->maybe_start();
    if (progress.started) tables->maybe_start_switch();
    tables->check_confirmations();
    heartbeat_timer.expires_after(milliseconds(heartbeats.interval_ms()));
    heartbeat_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec && !progress.stopping) heartbeat_tick();
    });
  }

  /// Each windowed node's late presents (a missed vblank), as of its last RenderDone.
  void log_late_presents() const {
    std::string line;
    for (const ClusterNodeConfig& node : options.config.nodes) {
      const NodeStatistics::Counts c = node_statistics.of(node.name);
      if (c.presents > 0) line += cat(line.empty() ? "" : ", ", node.name, " ", c.late_presents, " of ", c.presents);
    }
    if (!line.empty()) spdlog::info("master: late presents per node (as of its last RenderDone): {}", line);
  }

  void stop(const std::string& reason) {
    if (progress.stopping) return;
    progress.stopping = true;
    if (options.feed) options.feed->master_stopped();
    spdlog::info("master: stopping: {}", reason);
    log_late_presents();
    preparer.stop();  // a precompute in progress ends at its next progress report
    if (tables) tables->stop();
    boost::system::error_code ec;
    listener.close();
    datagrams.close();
    if (desk) desk->close();
    if (signals) signals->cancel(ec);
    heartbeat_timer.cancel();
    if (loop) loop->stop();
    sessions.say_goodbye(reason);  // the io_context returns once every connection has flushed and closed
  }

  int run() {
    load_playback(options, play);
    make_parts();
    // Listen first: nodes that start now connect (the kernel queues them) and
    // are served once the tables are ready.
    const std::uint16_t port = options.port.value_or(options.config.master_port);
    listener.listen(options.config.master_host, port);
    datagrams.open(options.config.master_host, port);  // UDP, the same port number
    listener.limit_unauthenticated(options.config.max_unauthenticated_connections);
    desk->start_console(io, options.operator_console);
    if (options.on_listening) options.on_listening();  // `zenith cluster` starts its nodes now
    tables->check_switches();                          // fail before any precompute
    if (options.takeover && options.takeover->last_frame)
      adopt_takeover();
    else
      tables->prepare_initial([](const TablePreparer::Job& job) { return TablePreparer::obtain_set(job, nullptr); });
    spdlog::info(
        "master: cluster '{}' listening on {}:{} for {} node{} (heartbeat {} ms, barrier timeout {} ms, {} Hz)",
        options.config.name, options.config.master_host, port, options.config.nodes.size(),
        options.config.nodes.size() == 1 ? "" : "s", options.config.heartbeat_ms, options.config.barrier_timeout_ms,
        fps);
    if (!tables->prepares_show_sets())
      loop->start_waiting();  // a show: once its first sets are ready (maybe_start_show)
    listener.start();
    signals.emplace(io, SIGINT, SIGTERM);
    signals->async_wait([this](const boost::system::error_code& e, int signal) {
      if (!e) stop(cat("signal ", signal == SIGINT ? "SIGINT" : "SIGTERM"));
    });
    desk->start_inputs(io, options.console, options.control_port);
    heartbeat_tick();
    io.run();
    preparer.stop();
    if (preparation_error) std::rethrow_exception(preparation_error);
    if (play.recorder)
      spdlog::info("master: {} frame{} recorded in {}", play.recorder->frames(),
                   play.recorder->frames() == 1 ? "" : "s", play.recorder->finish().string());
    spdlog::info("master: done, {} frame{} presented", progress.presented, progress.presented == 1 ? "" : "s");
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
