#include "cluster/master.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "apps/table_provider.h"
#include "atmosphere/model_hash.h"
#include "cluster/connection.h"
#include "cluster/frame_scene.h"
#include "cluster/table_transfer.h"
#include "render/scene/scene_loader.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::tcp;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

namespace {

template <typename... T>
std::string cat(const T&... parts) {
  std::ostringstream s;
  (s << ... << parts);
  return s.str();
}

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

}  // namespace

struct Master::Impl {
  /// One node's connection.
  struct Session {
    std::uint32_t id = 0;
    std::shared_ptr<Connection> connection;
    std::optional<MasterHandshake> handshake;
    enum class State { handshake, tables, ready } state = State::handshake;
    std::string name;  ///< from Hello
    std::set<Digest> tables_ready;
    bool lagging = false;  ///< dropped from a barrier; back at the next boundary once it reports
    Clock::time_point connected_at = Clock::now();
  };

  MasterOptions options;
  SharedSecret secret;
  scene::Scene scene;
  std::vector<TableSetFile> tables;
  std::vector<AtmosphereTableRef> table_refs;
  std::uint32_t render_flags = 0;

  asio::io_context io;
  tcp::acceptor acceptor{io};
  /// Installed once the tables are ready: until then SIGINT/SIGTERM end the process at once.
  std::optional<asio::signal_set> signals;
  asio::steady_timer heartbeat_timer{io}, barrier_timer{io}, frame_timer{io};
  std::map<std::uint32_t, std::unique_ptr<Session>> sessions;
  std::uint32_t next_id = 1;

  // The frame loop.
  std::uint64_t frame = 0;           ///< the frame in flight, or the next one to start
  bool in_flight = false;
  std::map<std::uint32_t, bool> participants;  ///< session id → RenderDone received
  Clock::time_point frame_started, show_started, waiting_since;
  bool started = false, stopping = false, waiting_logged = false;
  std::uint64_t presented = 0;

  Impl(MasterOptions o, SharedSecret s) : options(std::move(o)), secret(std::move(s)) {}

  // ---- preparation ----------------------------------------------------------

  void prepare_tables() {
    app::TableRequest request;
    request.options.sizes = app::table_sizes_by_name(options.config.table_sizes);
    request.options.max_orders = options.config.table_orders;
    request.backend = options.cpu_precompute ? app::PrecomputeBackend::Cpu : app::PrecomputeBackend::Gpu;
    request.cache_directory = options.cache_directory;
    request.show_progress = false;
    for (const scene::Body& body : scene.bodies) {
      if (!body.atmosphere) continue;
      const atmosphere::AtmosphereModel& model = body.atmosphere->loaded.model;
      app::ObtainedTables obtained = app::obtain_tables(model, request);
      if (obtained.cache_file.empty())
        throw std::runtime_error(cat("the tables of '", body.name, "' could not be stored in the cache: nodes get "
                                     "the cache file's bytes, so the master needs a writable cache (--cache DIR)"));
      const Digest hash = digest_from_hex(atmosphere::lookup_table_hash(model));
      tables.push_back(make_table_set_file(body.name, hash, obtained.cache_file));
      AtmosphereTableRef ref;
      ref.body_name = body.name;
      ref.table_hash = hash;
      ref.effective_from_frame = 0;
      table_refs.push_back(ref);
      spdlog::info("master: tables of '{}' ready to share: {} ({} bytes, sha256 {}…)", body.name,
                   obtained.cache_file.string(), tables.back().bytes->size(),
                   to_hex(tables.back().content_sha256).substr(0, 12));
    }
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
    auto session = std::make_unique<Session>();
    session->id = next_id++;
    session->handshake.emplace(secret, options.config.name);
    session->connection = std::make_shared<Connection>(std::move(socket), peer);
    const std::uint32_t id = session->id;
    Session* raw = session.get();
    sessions.emplace(id, std::move(session));
    spdlog::debug("master: connection from {}", peer);
    raw->connection->start([this, id](Message&& m) { on_message(id, std::move(m)); },
                           [this, id](const std::string& reason) { on_closed(id, reason); });
  }

  Session* find(std::uint32_t id) {
    auto it = sessions.find(id);
    return it == sessions.end() ? nullptr : it->second.get();
  }

  static std::string who(const Session& s) {
    return s.name.empty() ? cat("connection from ", s.connection->peer()) : cat("node '", s.name, "' (", s.connection->peer(), ")");
  }

  void refuse(Session& s, RejectReason reason, const std::string& text) {
    spdlog::warn("master: refused {}: {}", who(s), text);
    s.connection->send(Reject{reason, text.substr(0, kMaxReasonBytes)});
    s.connection->close_after_flush(cat("refused: ", text));
  }

  void on_closed(std::uint32_t id, const std::string& reason) {
    auto it = sessions.find(id);
    if (it == sessions.end()) return;
    Session& s = *it->second;
    const bool bad_peer = reason.starts_with("protocol error") || reason.find("truncated") != std::string::npos;
    if (s.state == Session::State::ready || !s.name.empty())
      spdlog::log(stopping ? spdlog::level::info : spdlog::level::warn, "master: {} disconnected: {}", who(s), reason);
    else
      spdlog::log(bad_peer ? spdlog::level::warn : spdlog::level::info, "master: {} closed: {}", who(s), reason);
    // Release the session after the connection's handlers have returned.
    std::shared_ptr<Session> keep(it->second.release());
    sessions.erase(it);
    asio::post(io, [keep] {});
    if (in_flight && participants.erase(id) > 0) check_barrier();
  }

  void on_message(std::uint32_t id, Message&& message) {
    Session* s = find(id);
    if (s == nullptr) return;
    try {
      if (s->state == Session::State::handshake) on_handshake_message(*s, message);
      else on_running_message(*s, message);
    } catch (const HandshakeError& e) {
      refuse(*s, e.reason(), e.what());
    }
  }

  void on_handshake_message(Session& s, const Message& message) {
    if (const auto* hello = std::get_if<Hello>(&message)) {
      s.name = hello->node_name;
      const Challenge challenge = s.handshake->on_hello(*hello);  // wrong cluster / version
      if (options.config.find_node(hello->node_name) == nullptr)
        throw HandshakeError(RejectReason::unspecified,
                             cat("node '", hello->node_name, "' is not in the cluster config ", options.config.source));
      s.connection->send(challenge);
    } else if (const auto* auth = std::get_if<Authenticate>(&message)) {
      s.handshake->on_authenticate(*auth);  // wrong secret → HandshakeError
      // A node that reconnects replaces its old connection (it proved the secret).
      for (auto& [other_id, other] : sessions) {
        if (other_id != s.id && other->name == s.name && other->state != Session::State::handshake) {
          spdlog::warn("master: node '{}' reconnected from {}: closing its old connection", s.name, s.connection->peer());
          other->connection->close("replaced by a new connection of the same node");
          break;
        }
      }
      s.connection->send(s.handshake->welcome(s.id, frame, options.config.heartbeat_ms, options.config.barrier_timeout_ms));
      s.state = Session::State::tables;
      spdlog::info("master: node '{}' authenticated from {} (id {}); sending {} table set{}", s.name,
                   s.connection->peer(), s.id, tables.size(), tables.size() == 1 ? "" : "s");
      for (const TableSetFile& t : tables)
        for (const auto& f : t.frames) s.connection->send_encoded(f);
      if (tables.empty()) become_ready(s);
    } else if (std::holds_alternative<Goodbye>(message)) {
      s.connection->close(cat("Goodbye during the handshake: ", std::get<Goodbye>(message).reason));
    } else {
      throw HandshakeError(RejectReason::protocol_error,
                           cat(to_string(message_type(message)), " before the handshake completed"));
    }
  }

  void become_ready(Session& s) {
    s.state = Session::State::ready;
    s.lagging = false;
    spdlog::info("master: node '{}' is ready: it joins the barrier at the next frame boundary (frame {})", s.name,
                 in_flight ? frame + 1 : frame);
    maybe_start_show();
  }

  void on_running_message(Session& s, const Message& message) {
    std::visit(
        [&](const auto& m) {
          using T = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<T, Heartbeat>) {
          } else if constexpr (std::is_same_v<T, TableReady>) {
            const bool known = std::any_of(tables.begin(), tables.end(),
                                           [&](const TableSetFile& t) { return t.table_hash == m.table_hash; });
            if (!known) {
              protocol_violation(s, "TableReady for a table set that was never sent");
              return;
            }
            s.tables_ready.insert(m.table_hash);
            if (s.state == Session::State::tables && s.tables_ready.size() == tables.size()) become_ready(s);
          } else if constexpr (std::is_same_v<T, RenderDone>) {
            on_render_done(s, m);
          } else if constexpr (std::is_same_v<T, Goodbye>) {
            spdlog::info("master: node '{}' said goodbye: {}", s.name, m.reason);
            s.connection->close(cat("Goodbye: ", m.reason));
          } else {
            protocol_violation(s, cat(to_string(message_type(message)), " is not sent by nodes"));
          }
        },
        message);
  }

  void protocol_violation(Session& s, const std::string& what) {
    spdlog::warn("master: closing {}: {}", who(s), what);
    s.connection->send(Goodbye{cat("protocol error: ", what).substr(0, kMaxReasonBytes)});
    s.connection->close_after_flush(cat("protocol error: ", what));
  }

  // ---- the frame loop -------------------------------------------------------

  std::size_t ready_count() const {
    return static_cast<std::size_t>(std::count_if(sessions.begin(), sessions.end(), [](const auto& p) {
      return p.second->state == Session::State::ready;
    }));
  }

  void maybe_start_show() {
    if (started || stopping) return;
    const std::size_t ready = ready_count();
    const bool waited = ms_since(waiting_since) >= options.wait_for_nodes_ms;
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
    participants.clear();
    for (auto& [id, s] : sessions)
      if (s->state == Session::State::ready && !s->lagging && s->connection->is_open()) participants.emplace(id, false);
    if (participants.empty()) {
      if (!waiting_logged) spdlog::warn("master: no node is ready for frame {}; waiting", frame);
      waiting_logged = true;
      frame_timer.expires_after(milliseconds(20));
      frame_timer.async_wait([this](const boost::system::error_code& ec) {
        if (!ec) start_frame();
      });
      return;
    }
    waiting_logged = false;
    const FrameState state = default_show_frame(scene, frame, options.sun_step_deg, table_refs, render_flags);
    auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(state));
    for (const auto& [id, done] : participants) sessions.at(id)->connection->send_encoded(encoded);
    in_flight = true;
    frame_started = Clock::now();
    spdlog::debug("master: frame {} sent to {} node{}", frame, participants.size(), participants.size() == 1 ? "" : "s");
    barrier_timer.expires_after(milliseconds(options.config.barrier_timeout_ms));
    const std::uint64_t this_frame = frame;
    barrier_timer.async_wait([this, this_frame](const boost::system::error_code& ec) {
      if (!ec && in_flight && frame == this_frame) on_barrier_timeout();
    });
  }

  void on_render_done(Session& s, const RenderDone& done) {
    if (s.lagging) {
      // A node dropped from an earlier barrier reports: it is back at the next boundary.
      if (done.frame < frame || !in_flight) {
        s.lagging = false;
        spdlog::info("master: node '{}' finished frame {} late; it rejoins the barrier at frame {}", s.name,
                     done.frame, in_flight ? frame + 1 : frame);
      }
      return;
    }
    auto it = participants.find(s.id);
    if (!in_flight || it == participants.end() || done.frame != frame) {
      spdlog::debug("master: ignoring RenderDone {} from node '{}' (frame {} in flight)", done.frame, s.name, frame);
      return;
    }
    it->second = true;
    check_barrier();
  }

  void check_barrier() {
    if (!in_flight) return;
    if (!std::all_of(participants.begin(), participants.end(), [](const auto& p) { return p.second; })) return;
    complete_frame();
  }

  void on_barrier_timeout() {
    for (auto& [id, done] : participants) {
      if (done) continue;
      Session* s = find(id);
      if (s == nullptr) continue;
      s->lagging = true;
      spdlog::warn("master: node '{}' missed the barrier of frame {} (no RenderDone within {} ms): dropped from the "
                   "barrier; the show goes on without it",
                   s->name, frame, options.config.barrier_timeout_ms);
    }
    std::erase_if(participants, [](const auto& p) { return !p.second; });
    complete_frame();
  }

  void complete_frame() {
    barrier_timer.cancel();
    in_flight = false;
    const Present present{frame};
    auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(present));
    for (const auto& [id, done] : participants)
      if (Session* s = find(id)) s->connection->send_encoded(encoded);
    spdlog::info("master: present frame {} on {} node{} ({:.1f} ms)", frame, participants.size(),
                 participants.size() == 1 ? "" : "s", ms_since(frame_started));
    participants.clear();
    ++frame;
    ++presented;
    if (options.frames != 0 && presented >= options.frames) {
      stop(cat("show finished after ", presented, " frames"));
      return;
    }
    // Pace: frame N starts no earlier than show start + N / rate.
    const auto due = show_started + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(static_cast<double>(presented) /
                                                                      options.config.frame_rate_hz));
    frame_timer.expires_at(std::max(due, Clock::now()));
    frame_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) start_frame();
    });
  }

  // ---- liveness, stop -------------------------------------------------------

  void heartbeat_tick() {
    const auto now = Clock::now();
    const double silent_limit_ms = 3.0 * options.config.heartbeat_ms;
    const double handshake_limit_ms = std::max(5000.0, silent_limit_ms);
    const Heartbeat beat{static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count())};
    auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(beat));
    std::vector<std::uint32_t> ids;
    for (auto& [id, s] : sessions) ids.push_back(id);
    for (const std::uint32_t id : ids) {
      Session* s = find(id);
      if (s == nullptr || !s->connection->is_open()) continue;
      if (s->state == Session::State::handshake) {
        if (ms_since(s->connected_at) > handshake_limit_ms) {
          spdlog::warn("master: closing {}: no handshake within {:.0f} ms", who(*s), handshake_limit_ms);
          s->connection->close("handshake timeout");
        }
        continue;
      }
      if (ms_since(s->connection->last_received()) > silent_limit_ms) {
        spdlog::warn("master: closing {}: nothing received for {:.0f} ms (3 heartbeats)", who(*s), silent_limit_ms);
        s->connection->close("heartbeat timeout");
        continue;
      }
      s->connection->send_encoded(encoded);
    }
    if (!started) maybe_start_show();
    heartbeat_timer.expires_after(milliseconds(options.config.heartbeat_ms));
    heartbeat_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec && !stopping) heartbeat_tick();
    });
  }

  void stop(const std::string& reason) {
    if (stopping) return;
    stopping = true;
    spdlog::info("master: stopping: {}", reason);
    boost::system::error_code ec;
    acceptor.close(ec);
    if (signals) signals->cancel(ec);
    heartbeat_timer.cancel();
    barrier_timer.cancel();
    frame_timer.cancel();
    // Closing may erase a session (its close handler): work on a copy.
    std::vector<std::pair<std::shared_ptr<Connection>, bool>> connections;
    for (auto& [id, s] : sessions) connections.emplace_back(s->connection, s->state == Session::State::handshake);
    for (auto& [connection, in_handshake] : connections) {
      if (in_handshake) connection->send(Reject{RejectReason::shutting_down, "the master is stopping"});
      else connection->send(Goodbye{reason});
      connection->close_after_flush("master stopping");
    }
    // The io_context returns once every connection has flushed and closed.
  }

  int run() {
    scene = scene::load_scene(options.config.scene);
    render_flags = render_flags_of(render::RenderOptions{});

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
    prepare_tables();
    spdlog::info("master: cluster '{}' listening on {}:{} for {} node{} (heartbeat {} ms, barrier timeout {} ms, {} Hz)",
                 options.config.name, options.config.master_host, port, options.config.nodes.size(),
                 options.config.nodes.size() == 1 ? "" : "s", options.config.heartbeat_ms,
                 options.config.barrier_timeout_ms, options.config.frame_rate_hz);
    waiting_since = Clock::now();
    accept();
    signals.emplace(io, SIGINT, SIGTERM);
    signals->async_wait([this](const boost::system::error_code& e, int signal) {
      if (!e) stop(cat("signal ", signal == SIGINT ? "SIGINT" : "SIGTERM"));
    });
    heartbeat_tick();
    io.run();
    spdlog::info("master: done, {} frame{} presented", presented, presented == 1 ? "" : "s");
    return 0;
  }
};

Master::Master(MasterOptions options, SharedSecret secret)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(secret))) {}
Master::~Master() = default;
int Master::run() { return impl_->run(); }

}  // namespace zenith::cluster
