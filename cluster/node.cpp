#include "core/json_reader.h"
#include "cluster/node.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <set>
#include <thread>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "render/lut/table_provider.h"
#include "atmosphere/lut/table_cache.h"
#include "cluster/connection.h"
#include "cluster/frame_scene.h"
#include "cluster/heartbeat.h"
#include "cluster/node/known_atmospheres.h"
#include "cluster/node/render_worker.h"
#include "cluster/table_transfer.h"
#include "scene/scene_loader.h"
#include "warp/viewport_config.h"
#include "core/timing.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::tcp;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

namespace {

using config::cat;  // core/json_reader.h

using core::ms_since;

}  // namespace

struct Node::Impl {
  NodeOptions options;
  SharedSecret secret;
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
  asio::steady_timer heartbeat_timer{io}, retry_timer{io};
  std::shared_ptr<Connection> connection;
  std::optional<NodeHandshake> handshake;
  TableReceiver receiver;
  std::set<Digest> inventory;     ///< sets found valid in the cache at Welcome (declared to the master)
  std::set<Digest> held_tables;   ///< sets this node holds (cached or received) and may render with
  bool welcomed = false, stopping = false;
  std::uint32_t heartbeat_ms = 250;
  Clock::time_point connect_started;
  int exit_code = kNodeExitDone;
  std::string master_address;

  // ---- the render thread: GL, the renderer, the frame files ----
  std::optional<RenderWorker> worker;  ///< set up in run(), before the threads start

  Impl(NodeOptions o, SharedSecret s) : options(std::move(o)), secret(std::move(s)) {}

  // =========================================================================
  // Networking thread.

  void connect() {
    const std::uint16_t port = options.port.value_or(options.config.master_port);
    master_address = cat(options.config.master_host, ":", port);
    auto socket = std::make_shared<tcp::socket>(io);
    tcp::resolver resolver(io);
    boost::system::error_code ec;
    const auto endpoints = resolver.resolve(options.config.master_host, std::to_string(port), ec);
    if (ec) {
      spdlog::error("node '{}': cannot resolve the master's host {}: {}", options.node_name, master_address, ec.message());
      finish(kNodeExitMasterLost);
      return;
    }
    asio::async_connect(*socket, endpoints, [this, socket](const boost::system::error_code& e, const tcp::endpoint&) {
      if (stopping) return;
      if (e) {
        if (ms_since(connect_started) > options.connect_timeout_ms) {
          spdlog::error("node '{}': cannot reach the master at {} within {} ms ({}): exiting", options.node_name,
                        master_address, options.connect_timeout_ms, e.message());
          finish(kNodeExitMasterLost);
          return;
        }
        retry_timer.expires_after(milliseconds(200));
        retry_timer.async_wait([this](const boost::system::error_code& te) {
          if (!te && !stopping) connect();
        });
        return;
      }
      on_connected(std::move(*socket));
    });
  }

  void on_connected(tcp::socket socket) {
    connection = std::make_shared<Connection>(std::move(socket), cat("master ", master_address));
    connection->start([this](Message&& m) { on_message(std::move(m)); },
                      [this](const std::string& reason) { on_closed(reason); });
    handshake.emplace(secret, options.config.name, options.node_name);
    connection->send(handshake->start());
    spdlog::info("node '{}': connected to the master at {}", options.node_name, master_address);
    heartbeat_tick();
  }

  void on_closed(const std::string& reason) {
    if (stopping) return;
    spdlog::error("node '{}': lost the connection to the master at {} without a Goodbye ({}): the master is gone; "
                  "exiting",
                  options.node_name, master_address, reason);
    finish(kNodeExitMasterLost);
  }

  void say_goodbye_and_finish(const std::string& reason, int code) {
    if (connection && connection->is_open()) {
      connection->send(Goodbye{reason.substr(0, kMaxReasonBytes)});
      stopping = true;  // the close handler must not report a lost master
      connection->close_after_flush(reason);
    }
    finish(code);
  }

  void on_message(Message&& message) {
    if (stopping) return;
    try {
      if (!welcomed) on_handshake_message(message);
      else on_running_message(message);
    } catch (const HandshakeError& e) {
      spdlog::error("node '{}': the master at {} failed to authenticate: {}", options.node_name, master_address, e.what());
      say_goodbye_and_finish(cat("authentication failed: ", e.what()), kNodeExitRefused);
    } catch (const std::exception& e) {
      spdlog::error("node '{}': closing the connection to the master: {}", options.node_name, e.what());
      say_goodbye_and_finish(cat("error: ", e.what()), kNodeExitFailed);
    }
  }

  void on_handshake_message(const Message& message) {
    if (const auto* c = std::get_if<Challenge>(&message)) {
      connection->send(handshake->on_challenge(*c));
    } else if (const auto* w = std::get_if<Welcome>(&message)) {
      handshake->on_welcome(*w);  // throws when the master does not know the secret
      welcomed = true;
      heartbeat_ms = w->heartbeat_interval_ms;
      spdlog::info("node '{}': welcomed by the master as id {} at frame {} (heartbeat {} ms, barrier timeout {} ms)",
                   options.node_name, w->node_id, w->current_frame, w->heartbeat_interval_ms, w->barrier_timeout_ms);
      send_inventory();
    } else if (const auto* r = std::get_if<Reject>(&message)) {
      spdlog::error("node '{}': the master refused the connection ({}): {}", options.node_name,
                    static_cast<int>(r->reason), r->text);
      stopping = true;
      connection->close("rejected");
      finish(kNodeExitRefused);
    } else if (const auto* g = std::get_if<Goodbye>(&message)) {
      spdlog::error("node '{}': the master said goodbye during the handshake: {}", options.node_name, g->reason);
      stopping = true;
      connection->close("goodbye");
      finish(kNodeExitRefused);
    } else {
      throw std::runtime_error(cat(to_string(message_type(message)), " from the master before Welcome"));
    }
  }

  void on_running_message(const Message& message) {
    if (const auto* fs = std::get_if<FrameState>(&message)) {
      for (const AtmosphereTableRef& ref : fs->atmospheres)
        if (!held_tables.count(ref.table_hash) || ref.effective_from_frame > fs->frame)
          throw std::runtime_error(cat("FrameState ", fs->frame, " uses table set ", to_hex(ref.table_hash).substr(0, 12),
                                       "… (effective from frame ", ref.effective_from_frame, ") for '", ref.body_name,
                                       "', which this node does not hold or may not use yet"));
      worker->render(*fs);
    } else if (const auto* p = std::get_if<Present>(&message)) {
      worker->present(p->frame);
    } else if (const auto* a = std::get_if<TableAnnounce>(&message)) {
      if (!atmospheres.knows(a->table_hash))
        throw std::runtime_error(cat("TableAnnounce of table set ", to_hex(a->table_hash).substr(0, 12),
                                     "…, which no atmosphere this node knows uses (the scene's, the presets, the atmosphere "
                                     "files it was given: do master and node read the same scene and files?)"));
      if (inventory.count(a->table_hash)) {
        // Declared in the inventory: the master sends no chunks; use the cached copy.
        held_tables.insert(a->table_hash);
        worker->prepare(a->table_hash);
      } else {
        receiver.on_announce(*a);
      }
    } else if (const auto* d = std::get_if<AtmosphereDefinition>(&message)) {
      atmospheres.define(*d, true);
    } else if (const auto* c = std::get_if<TableChunk>(&message)) {
      if (std::optional<std::vector<std::uint8_t>> bytes = receiver.on_chunk(*c)) store_tables(c->table_hash, *bytes);
    } else if (std::holds_alternative<Heartbeat>(message)) {
    } else if (const auto* g = std::get_if<Goodbye>(&message)) {
      spdlog::info("node '{}': the master said goodbye: {}", options.node_name, g->reason);
      stopping = true;
      connection->close("goodbye");
      finish(kNodeExitDone);
    } else {
      throw std::runtime_error(cat(to_string(message_type(message)), " is not sent by a master"));
    }
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
    worker->prepare(hash);
  }

  /// Right after Welcome: a TableReady for every set this node knows that its
  /// cache holds and that loads with valid checksums, then a Heartbeat that
  /// ends the inventory. The master sends such sets as a bare TableAnnounce.
  void send_inventory() {
    const atmosphere::lut::TableCache cache(options.cache_directory);
    for (const auto& [hash, known] : atmospheres.snapshot()) {
      const auto path = cache.path_for(atmosphere::lut::table_set_key(known.loaded.model, table_options));
      std::error_code ec;
      if (!std::filesystem::exists(path, ec)) continue;
      std::string problem;
      if (!cache.load(known.loaded.model, table_options, &problem)) {
        spdlog::warn("node '{}': cached tables {} are not usable ({}); the master will send them again",
                     options.node_name, path.string(), problem);
        continue;
      }
      inventory.insert(hash);
      connection->send(TableReady{hash});
    }
    connection->send(heartbeat_at(Clock::now()));
    spdlog::info("node '{}': {} table set{} already in the cache", options.node_name, inventory.size(),
                 inventory.size() == 1 ? "" : "s");
  }

  void send_table_ready(const Digest& hash) {
    if (stopping || !connection) return;
    connection->send(TableReady{hash});
    spdlog::info("node '{}': table version {} ready", options.node_name, short_hex(hash));
  }

  void heartbeat_tick() {
    if (stopping || !connection) return;
    // Before Welcome the master may still be preparing tables: the connect timeout applies.
    const double silent_limit_ms = welcomed ? silence_limit_ms(heartbeat_ms) : static_cast<double>(options.connect_timeout_ms);
    if (ms_since(connection->last_received()) > silent_limit_ms) {
      spdlog::error("node '{}': nothing from the master at {} for {:.0f} ms{}: the master is gone; exiting",
                    options.node_name, master_address, silent_limit_ms, welcomed ? "" : " (no Welcome)");
      stopping = true;
      connection->close("heartbeat timeout");
      finish(kNodeExitMasterLost);
      return;
    }
    if (welcomed)
      connection->send(heartbeat_at(Clock::now()));
    heartbeat_timer.expires_after(milliseconds(heartbeat_ms));
    heartbeat_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) heartbeat_tick();
    });
  }

  /// Ends the node with `code` (first call wins): stops timers, lets queued
  /// frames flush, tells the render thread to stop after its queued jobs.
  void finish(int code) {
    static_cast<void>(code);
    if (finished) return;
    finished = true;
    stopping = true;
    exit_code = code;
    boost::system::error_code ec;
    signals.cancel(ec);
    heartbeat_timer.cancel();
    retry_timer.cancel();
    if (connection && connection->is_open()) connection->close_after_flush("node stopping");
    worker->stop();
  }
  bool finished = false;

  /// Render thread → networking thread.
  void report_render_done(std::uint64_t frame, double render_ms) {
    asio::post(io, [this, frame, render_ms] {
      if (!stopping && connection) connection->send(RenderDone{frame, render_ms});
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
    table_options.sizes = render::table_sizes_by_name(options.config.table_sizes);
    table_options.max_orders = options.config.table_orders;
    atmospheres.add_scene_and_candidates(options.atmosphere_files);
    atmospheres.load_kept_definitions();
    node_directory = options.layout == FrameFileLayout::offline
                         ? options.output_directory / "nodes" / options.node_name
                         : options.output_directory / options.node_name;
    std::filesystem::create_directories(node_directory);
    heartbeat_ms = options.config.heartbeat_ms;
    worker.emplace(RenderWorker::Setup{options, base_scene, viewports, outputs, atmospheres, table_options, node_directory},
                   RenderWorker::Events{
                       [this](std::uint64_t frame, double render_ms) { report_render_done(frame, render_ms); },
                       [this](const Digest& hash) { asio::post(io, [this, hash] { send_table_ready(hash); }); },
                       [this](const std::string& what) { report_failure(what); },
                       [this] {
                         asio::post(io, [this] { say_goodbye_and_finish("the node's window was closed", kNodeExitDone); });
                       }});

    signals.async_wait([this](const boost::system::error_code& ec, int signal) {
      if (ec || finished) return;
      spdlog::info("node '{}': {} received: leaving the cluster", options.node_name, signal == SIGINT ? "SIGINT" : "SIGTERM");
      say_goodbye_and_finish("node stopped by a signal", kNodeExitDone);
    });
    connect_started = Clock::now();
    connect();
    std::thread network([this] {
      try {
        io.run();
      } catch (const std::exception& e) {
        spdlog::error("node '{}': networking failed: {}", options.node_name, e.what());
        exit_code = kNodeExitFailed;
        worker->stop();
      }
    });
    worker->run();
    // The network thread ends once the connection flushed and closed.
    asio::post(io, [this] {
      if (!finished) finish(exit_code);
    });
    network.join();
    worker->release_gl();
    return exit_code;
  }
};

Node::Node(NodeOptions options, SharedSecret secret)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(secret))) {}
Node::~Node() = default;
int Node::run() { return impl_->run(); }

}  // namespace zenith::cluster
