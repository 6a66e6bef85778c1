#include "cluster/node.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "apps/table_provider.h"
#include "atmosphere/lut/table_cache.h"
#include "atmosphere/model_hash.h"
#include "cluster/connection.h"
#include "cluster/frame_scene.h"
#include "cluster/table_transfer.h"
#include "render/gl/egl_context.h"
#include "render/image/image_writer.h"
#include "render/image/tone_mapping.h"
#include "render/renderer.h"
#include "render/scene/scene_loader.h"
#include "warp/blending.h"
#include "warp/viewport_config.h"

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

/// Work for the render thread.
struct Job {
  enum class Kind { warmup, render, present, stop } kind = Kind::stop;
  FrameState state;         ///< render
  std::uint64_t frame = 0;  ///< present
};

}  // namespace

struct Node::Impl {
  NodeOptions options;
  SharedSecret secret;
  scene::Scene base_scene;
  warp::ViewportConfig viewports;
  std::vector<std::size_t> outputs;  ///< indices into viewports.outputs
  atmosphere::lut::PrecomputeOptions table_options;
  std::filesystem::path node_directory;

  // ---- networking thread only ----
  asio::io_context io;
  asio::signal_set signals{io, SIGINT, SIGTERM};
  asio::steady_timer heartbeat_timer{io}, retry_timer{io};
  std::shared_ptr<Connection> connection;
  std::optional<NodeHandshake> handshake;
  TableReceiver receiver;
  std::map<Digest, const scene::Body*> needed_tables;  ///< table hash → the body whose atmosphere uses it
  std::set<Digest> stored_tables;
  bool welcomed = false, stopping = false, warmup_sent = false;
  std::uint32_t heartbeat_ms = 250;
  Clock::time_point connect_started;
  int exit_code = kNodeExitDone;
  std::string master_address;

  // ---- shared: the job queue ----
  std::mutex mutex;
  std::condition_variable wake;
  std::deque<Job> jobs;

  // ---- render thread only ----
  std::optional<render::gl::HeadlessContext> context;
  std::unique_ptr<render::Renderer> renderer;
  std::uint32_t renderer_flags = 0;
  std::optional<std::uint64_t> rendered_frame;
  std::string rendered_digest;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> partials;  ///< partial → final

  Impl(NodeOptions o, SharedSecret s) : options(std::move(o)), secret(std::move(s)) {}

  void push(Job job) {
    {
      std::lock_guard lock(mutex);
      jobs.push_back(std::move(job));
    }
    wake.notify_one();
  }

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
      if (needed_tables.empty()) request_warmup();
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
        if (!stored_tables.count(ref.table_hash))
          throw std::runtime_error(cat("FrameState ", fs->frame, " uses table set ", to_hex(ref.table_hash).substr(0, 12),
                                       "… for '", ref.body_name, "', which this node does not hold"));
      push(Job{Job::Kind::render, *fs, fs->frame});
    } else if (const auto* p = std::get_if<Present>(&message)) {
      push(Job{Job::Kind::present, {}, p->frame});
    } else if (const auto* a = std::get_if<TableAnnounce>(&message)) {
      if (!needed_tables.count(a->table_hash))
        throw std::runtime_error(cat("TableAnnounce of table set ", to_hex(a->table_hash).substr(0, 12),
                                     "…, which no atmosphere of the scene uses (do master and node read the same scene?)"));
      receiver.on_announce(*a);
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
    const scene::Body* body = needed_tables.at(hash);
    const atmosphere::lut::TableCache cache(options.cache_directory);
    const auto path = cache.path_for(atmosphere::lut::table_set_key(body->atmosphere->loaded.model, table_options));
    write_file_atomically(path, bytes);
    stored_tables.insert(hash);
    spdlog::info("node '{}': tables of '{}' received ({} bytes, SHA-256 verified) and cached as {}", options.node_name,
                 body->name, bytes.size(), path.string());
    if (stored_tables.size() == needed_tables.size()) request_warmup();
  }

  /// Every table set is cached: the render thread loads them and renders once
  /// (shaders, uploads), then TableReady tells the master this node can join.
  void request_warmup() {
    if (warmup_sent) return;
    warmup_sent = true;
    push(Job{Job::Kind::warmup, {}, 0});
  }

  void send_tables_ready() {
    if (stopping || !connection) return;
    for (const auto& [hash, body] : needed_tables) connection->send(TableReady{hash});
    spdlog::info("node '{}': ready; joining the barrier at the next frame boundary", options.node_name);
  }

  void heartbeat_tick() {
    if (stopping || !connection) return;
    // Before Welcome the master may still be preparing tables: the connect timeout applies.
    const double silent_limit_ms = welcomed ? 3.0 * heartbeat_ms : static_cast<double>(options.connect_timeout_ms);
    if (ms_since(connection->last_received()) > silent_limit_ms) {
      spdlog::error("node '{}': nothing from the master at {} for {:.0f} ms{}: the master is gone; exiting",
                    options.node_name, master_address, silent_limit_ms, welcomed ? " (3 heartbeats)" : " (no Welcome)");
      stopping = true;
      connection->close("heartbeat timeout");
      finish(kNodeExitMasterLost);
      return;
    }
    if (welcomed)
      connection->send(Heartbeat{static_cast<std::uint64_t>(
          std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count())});
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
    push(Job{Job::Kind::stop, {}, 0});
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

  // =========================================================================
  // Render thread.

  void ensure_renderer(std::uint32_t flags) {
    if (!context) {
      context.emplace();
      spdlog::info("node '{}': rendering on {}", options.node_name, context->renderer());
    }
    if (renderer && flags == renderer_flags) return;
    renderer.reset();
    renderer_flags = flags;
    const atmosphere::lut::TableCache cache(options.cache_directory);
    renderer = std::make_unique<render::Renderer>(
        render_options_of(flags), [this, cache](const atmosphere::AtmosphereModel& model) {
          std::string problem;
          std::optional<atmosphere::lut::LookupTables> tables = cache.load(model, table_options, &problem);
          if (!tables)
            throw std::runtime_error(cat("the tables the master sent are not usable from ", cache.directory().string(),
                                         problem.empty() ? std::string() : cat(": ", problem)));
          context->make_current();
          return std::move(*tables);
        });
  }

  std::filesystem::path frame_path(const warp::OutputConfig& o, std::uint64_t frame) const {
    return node_directory / o.name / fmt::format("frame-{:06d}.{}", frame, options.config.output_format);
  }

  void write_output(const warp::OutputConfig& o, std::size_t index, const scene::Scene& scene,
                    const std::filesystem::path& path) {
    std::vector<float> rgb = renderer->render_image(scene, *o.projection);
    const image::ImageAttributes attributes = {
        {"zenith:scene", scene.name},
        {"zenith:projection", o.projection->describe()},
        {"zenith:exposure", fmt::format("{}", scene.camera.exposure)},
        {"zenith:viewport", fmt::format("{}#{}", viewports.source, o.name)},
    };
    const bool blended = o.blend.mode != warp::BlendMode::none || o.black_level != 0.0;
    if (options.config.output_format == "exr") {
      if (blended) warp::apply_blend(rgb, 0, o.height_px, warp::output_blend_mask(viewports, index), o.black_level);
      image::write_exr(path, o.width_px, o.height_px, rgb, image::ExrPixelType::half, attributes);
      return;
    }
    if (!blended) {
      image::write_png(path, o.width_px, o.height_px, rgb, image::ToneMapping::exponential, attributes);
      return;
    }
    // As `zenith render --viewport`: tone map, then the output stage, then sRGB (docs/viewports.md).
    for (float& v : rgb) v = image::tone_map(v, image::ToneMapping::exponential);
    warp::apply_blend(rgb, 0, o.height_px, warp::output_blend_mask(viewports, index), o.black_level);
    image::write_png(path, o.width_px, o.height_px, rgb, image::ToneMapping::clamp, attributes);
  }

  void discard_partials() {
    std::error_code ec;
    for (const auto& [partial, final_path] : partials) std::filesystem::remove(partial, ec);
    partials.clear();
    rendered_frame.reset();
  }

  void render_frame(const FrameState& state) {
    discard_partials();
    const auto t0 = Clock::now();
    scene::Scene scene = base_scene;
    apply_frame_state(state, scene);
    ensure_renderer(state.render_flags);
    for (const std::size_t i : outputs) {
      const warp::OutputConfig& o = viewports.outputs[i];
      std::filesystem::path final_path = frame_path(o, state.frame);
      std::filesystem::path partial = final_path;
      partial += ".partial";
      std::filesystem::create_directories(final_path.parent_path());
      write_output(o, i, scene, partial);
      partials.emplace_back(partial, final_path);
    }
    rendered_frame = state.frame;
    rendered_digest = state_digest(state);
    const double render_ms = ms_since(t0);
    spdlog::debug("node '{}': frame {} rendered in {:.1f} ms", options.node_name, state.frame, render_ms);
    report_render_done(state.frame, render_ms);
  }

  void present_frame(std::uint64_t frame) {
    if (rendered_frame != frame) {
      spdlog::warn("node '{}': Present {} for a frame this node has not rendered; ignored", options.node_name, frame);
      return;
    }
    for (const auto& [partial, final_path] : partials) std::filesystem::rename(partial, final_path);
    partials.clear();
    rendered_frame.reset();
    std::ofstream log(node_directory / "presented.log", std::ios::app);
    log << "frame " << frame << " state " << rendered_digest << "\n";
    spdlog::debug("node '{}': presented frame {}", options.node_name, frame);
  }

  void warmup() {
    ensure_renderer(render_flags_of(render::RenderOptions{}));
    const auto t0 = Clock::now();
    for (const std::size_t i : outputs) renderer->render_image(base_scene, *viewports.outputs[i].projection);
    spdlog::info("node '{}': tables loaded and shaders ready ({:.0f} ms)", options.node_name, ms_since(t0));
    asio::post(io, [this] { send_tables_ready(); });
  }

  void render_loop() {
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex);
        wake.wait(lock, [this] { return !jobs.empty(); });
        job = std::move(jobs.front());
        jobs.pop_front();
        if (job.kind == Job::Kind::render &&
            std::any_of(jobs.begin(), jobs.end(), [](const Job& j) { return j.kind == Job::Kind::render; })) {
          spdlog::warn("node '{}': skipping frame {}: a newer frame is queued", options.node_name, job.frame);
          continue;
        }
      }
      try {
        switch (job.kind) {
          case Job::Kind::warmup: warmup(); break;
          case Job::Kind::render: render_frame(job.state); break;
          case Job::Kind::present: present_frame(job.frame); break;
          case Job::Kind::stop: discard_partials(); return;
        }
      } catch (const std::exception& e) {
        spdlog::error("node '{}': {}", options.node_name, e.what());
        report_failure(e.what());
      }
    }
  }

  // =========================================================================

  int run() {
    const ClusterNodeConfig* me = options.config.find_node(options.node_name);
    if (me == nullptr)
      throw std::invalid_argument(cat("node '", options.node_name, "' is not in ", options.config.source));
    base_scene = scene::load_scene(options.config.scene);
    viewports = warp::load_viewport_config(options.config.viewports);
    for (const std::string& name : me->outputs) outputs.push_back(viewports.index_of(name));
    table_options.sizes = app::table_sizes_by_name(options.config.table_sizes);
    table_options.max_orders = options.config.table_orders;
    for (const scene::Body& body : base_scene.bodies)
      if (body.atmosphere)
        needed_tables.emplace(digest_from_hex(atmosphere::lookup_table_hash(body.atmosphere->loaded.model)), &body);
    node_directory = options.output_directory / options.node_name;
    std::filesystem::create_directories(node_directory);
    heartbeat_ms = options.config.heartbeat_ms;

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
        push(Job{Job::Kind::stop, {}, 0});
      }
    });
    render_loop();
    // The network thread ends once the connection flushed and closed.
    asio::post(io, [this] {
      if (!finished) finish(exit_code);
    });
    network.join();
    renderer.reset();
    context.reset();
    return exit_code;
  }
};

Node::Node(NodeOptions options, SharedSecret secret)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(secret))) {}
Node::~Node() = default;
int Node::run() { return impl_->run(); }

}  // namespace zenith::cluster
