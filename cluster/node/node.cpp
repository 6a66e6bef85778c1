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
#include "cluster/link/master_link.h"
#include "cluster/node/known_atmospheres.h"
#include "cluster/node/render_worker.h"
#include "cluster/protocol/heartbeat.h"
#include "cluster/protocol/table_transfer.h"
#include "core/strings.h"
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
  LinkEnd end;  // the exit code, decided by the first finish()

  // ---- the render thread: GL, the renderer, the frame files ----
  std::optional<RenderWorker> worker;  ///< set up in run(), before the threads start

  Impl(NodeOptions o, SharedSecret secret)
      : options(std::move(o)),
        link(io, link_setup(options), std::move(secret),
             MasterLink::Events{[this](const Welcome&) { on_welcomed(); }, [this](const std::string&) { on_lost(); },
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
  void on_welcomed() {
    ++session;
    connected = true;
    receiver = TableReceiver{};
    send_inventory();
  }

  /// The connection is lost (MasterLink reconnects): forget the frame in
  /// flight and the transfers of that connection; the last presented frame
  /// stays on the outputs and in the window.
  void on_lost() {
    connected = false;
    preview_request.reset();
    receiver = TableReceiver{};
    worker->abandon_frames();
  }

  /// A message of the master after Welcome (MasterLink: not Heartbeat, not Goodbye).
  void on_master_message(const Message& message) {
    if (const auto* fs = std::get_if<FrameState>(&message)) {
      for (const AtmosphereTableRef& ref : fs->atmospheres)
        if (!held_tables.count(ref.table_hash) || ref.effective_from_frame > fs->frame)
          throw std::runtime_error(cat("FrameState ", fs->frame, " uses table set ",
                                       to_hex(ref.table_hash).substr(0, 12), "… (effective from frame ",
                                       ref.effective_from_frame, ") for '", ref.body_name,
                                       "', which this node does not hold or may not use yet"));
      const bool thumbnails = preview_request && preview_request->frame == fs->frame;
      worker->render(*fs, session, thumbnails ? preview_request->edge_px : 0);
      if (thumbnails) preview_request.reset();
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
      if (!cache.load(known.loaded.model, table_options, &problem)) {
        spdlog::warn("node '{}': cached tables {} are not usable ({}); the master will send them again",
                     options.node_name, path.string(), problem);
        continue;
      }
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
    worker->stop();
  }

  /// Render thread → networking thread: the frame's thumbnails (when the
  /// master asked for them), then its RenderDone.
  void report_render_done(const RenderDone& done, std::uint64_t of_session, std::vector<Thumbnail> thumbnails) {
    asio::post(io, [this, done, of_session, thumbnails = std::move(thumbnails)]() mutable {
      if (!connected || of_session != session) return;
      for (Thumbnail& t : thumbnails) link.send(std::move(t));
      link.send(done);
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
