#include "core/json_reader.h"
#include "cluster/node.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
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

#include "render/lut/table_provider.h"
#include "atmosphere/lut/table_cache.h"
#include "atmosphere/model_hash.h"
#include "atmosphere/parameters.h"
#include "cluster/connection.h"
#include "cluster/frame_scene.h"
#include "cluster/heartbeat.h"
#include "cluster/node/known_atmospheres.h"
#include "cluster/table_transfer.h"
#include "render/gl/egl_context.h"
#include "image/image_writer.h"
#include "image/tone_mapping.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "render/window/frame_presenter.h"
#include "render/window/window_context.h"
#include "warp/blending.h"
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

/// Work for the render thread.
struct Job {
  enum class Kind { prepare, render, present, stop } kind = Kind::stop;
  FrameState state;         ///< render
  std::uint64_t frame = 0;  ///< present
  Digest table_hash{};      ///< prepare: load this table set, render once, then TableReady
};


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

  // ---- shared: the job queue ----
  std::mutex mutex;
  std::condition_variable wake;
  std::deque<Job> jobs;

  // ---- render thread only ----
  std::optional<render::gl::HeadlessContext> context;
  /// With --window: the GL context is a window's, and each presented frame is
  /// shown in it (the node's outputs side by side, as written to the files).
  std::optional<render::window::WindowContext> window;
  std::optional<render::window::FramePresenter> presenter;
  std::vector<std::vector<float>> rendered_display;  ///< per output: display-linear values of the rendered frame
  std::unique_ptr<render::Renderer> renderer;
  std::uint32_t renderer_flags = 0;
  std::optional<std::uint64_t> rendered_frame;
  std::string rendered_digest, rendered_tables;
  double rendered_show_time_s = 0.0;
  bool warmed_up = false;
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
      push(Job{Job::Kind::render, *fs, fs->frame, {}});
    } else if (const auto* p = std::get_if<Present>(&message)) {
      push(Job{Job::Kind::present, {}, p->frame, {}});
    } else if (const auto* a = std::get_if<TableAnnounce>(&message)) {
      if (!atmospheres.knows(a->table_hash))
        throw std::runtime_error(cat("TableAnnounce of table set ", to_hex(a->table_hash).substr(0, 12),
                                     "…, which no atmosphere this node knows uses (the scene's, the presets, the atmosphere "
                                     "files it was given: do master and node read the same scene and files?)"));
      if (inventory.count(a->table_hash)) {
        // Declared in the inventory: the master sends no chunks; use the cached copy.
        held_tables.insert(a->table_hash);
        push(Job{Job::Kind::prepare, {}, 0, a->table_hash});
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
    push(Job{Job::Kind::prepare, {}, 0, hash});
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
    push(Job{Job::Kind::stop, {}, 0, {}});
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

  void make_current() const {
    if (window) window->make_current();
    else context->make_current();
  }

  void ensure_renderer(std::uint32_t flags) {
    if (options.window && !window) {
      render::window::WindowOptions w;
      w.title = cat("zenith node ", options.node_name);
      w.width = 0;
      w.height = 0;
      for (const std::size_t i : outputs) {
        w.width += viewports.outputs[i].width_px;
        w.height = std::max(w.height, viewports.outputs[i].height_px);
      }
      // Fit a 1280 × 1024 screen area at first; the window can be resized (or made full screen).
      const double shrink = std::min(1.0, std::min(1280.0 / w.width, 1024.0 / w.height));
      w.width = std::max(1, static_cast<int>(w.width * shrink));
      w.height = std::max(1, static_cast<int>(w.height * shrink));
      w.swap_interval = 0;  // the cluster's barrier paces the frames
      window.emplace(w);
      presenter.emplace();
      spdlog::info("node '{}': rendering on {} into a window", options.node_name, window->renderer());
    } else if (!options.window && !context) {
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
          make_current();
          return std::move(*tables);
        });
  }

  std::filesystem::path frame_path(const warp::OutputConfig& o, std::uint64_t frame) const {
    if (options.layout == FrameFileLayout::offline)  // apps/offline_render.h: frame_file_path()
      return options.output_directory / o.name / fmt::format("{}.{:06d}.{}", o.name, frame, options.config.output_format);
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
    if (window) {  // what the projector shows: tone mapped, then the output stage (docs/viewports.md)
      std::vector<float>& display = rendered_display[index_in_node(index)];
      display = rgb;
      for (float& v : display) v = image::tone_map(v, image::ToneMapping::exponential);
      if (blended) warp::apply_blend(display, 0, o.height_px, warp::output_blend_mask(viewports, index), o.black_level);
    }
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

  std::size_t index_in_node(std::size_t viewport_index) const {
    return static_cast<std::size_t>(std::find(outputs.begin(), outputs.end(), viewport_index) - outputs.begin());
  }

  /// Shows the presented frame in the window: the node's outputs side by side.
  void show_in_window() {
    int width = 0, height = 0;
    for (const std::size_t i : outputs) {
      width += viewports.outputs[i].width_px;
      height = std::max(height, viewports.outputs[i].height_px);
    }
    std::vector<float> picture(static_cast<std::size_t>(width) * height * 3, 0.0f);
    int x0 = 0;
    for (std::size_t k = 0; k < outputs.size(); ++k) {
      const warp::OutputConfig& o = viewports.outputs[outputs[k]];
      const std::vector<float>& display = rendered_display[k];
      for (int y = 0; y < o.height_px && !display.empty(); ++y)
        std::copy_n(display.begin() + static_cast<std::ptrdiff_t>(y) * o.width_px * 3, o.width_px * 3,
                    picture.begin() + (static_cast<std::ptrdiff_t>(y) * width + x0) * 3);
      x0 += o.width_px;
    }
    window->make_current();
    const render::window::FramebufferSize size = window->framebuffer_size();
    presenter->present(picture, width, height, image::ToneMapping::clamp, {0, size.width, size.height});
    window->swap_buffers();
    window->poll_events();
    if (window->should_close()) {
      spdlog::info("node '{}': window closed: leaving the cluster", options.node_name);
      asio::post(io, [this] { say_goodbye_and_finish("the node's window was closed", kNodeExitDone); });
    }
  }

  void discard_partials() {
    std::error_code ec;
    for (const auto& [partial, final_path] : partials) std::filesystem::remove(partial, ec);
    partials.clear();
    rendered_frame.reset();
  }

  /// The scene with body `body`'s atmosphere replaced by table version `hash`.
  void use_table_version(scene::Scene& scene, const std::string& body, const Digest& hash) const {
    const KnownAtmospheres::Entry& known = atmospheres.find(hash);
    for (scene::Body& b : scene.bodies)
      if (b.name == body && b.atmosphere) {
        b.atmosphere->loaded = known.loaded;
        return;
      }
    throw std::runtime_error(cat("FrameState names body '", body, "', which has no atmosphere in ", base_scene.source));
  }

  void render_frame(const FrameState& state) {
    discard_partials();
    if (options.debug_render_delay_ms > 0)
      std::this_thread::sleep_for(milliseconds(options.debug_render_delay_ms));  // test hook: a slow node
    const auto t0 = Clock::now();
    scene::Scene scene = base_scene;
    apply_frame_state(state, scene);
    rendered_tables.clear();
    for (const AtmosphereTableRef& ref : state.atmospheres) {
      use_table_version(scene, ref.body_name, ref.table_hash);
      rendered_tables += cat(rendered_tables.empty() ? "" : ",", ref.body_name, "=", to_hex(ref.table_hash).substr(0, 16));
    }
    if (rendered_tables.empty()) rendered_tables = "-";
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
    rendered_show_time_s = state.show_time_s;
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
    if (window) show_in_window();
    log << "frame " << frame << " state " << rendered_digest << " tables " << rendered_tables << " show_time_s "
        << fmt::format("{}", rendered_show_time_s) << "\n";
    spdlog::debug("node '{}': presented frame {}", options.node_name, frame);
  }

  /// Loads table set `hash` (TableCache::load checks every part's checksum)
  /// and renders with it once: every output the first time (shaders), then
  /// the first output only (table upload). Then TableReady.
  void prepare(const Digest& hash) {
    ensure_renderer(render_flags_of(render::RenderOptions{}));
    const auto t0 = Clock::now();
    scene::Scene scene = base_scene;
    use_table_version(scene, atmospheres.find(hash).body, hash);
    for (const std::size_t i : outputs) {
      renderer->render_image(scene, *viewports.outputs[i].projection);
      if (warmed_up) break;
    }
    warmed_up = true;
    spdlog::info("node '{}': tables of '{}' version {} loaded and rendered once ({:.0f} ms)", options.node_name,
                 atmospheres.find(hash).body, short_hex(hash), ms_since(t0));
    asio::post(io, [this, hash] { send_table_ready(hash); });
  }

  void render_loop() {
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex);
        if (window) {  // keep the window responsive between frames
          while (!wake.wait_for(lock, milliseconds(30), [this] { return !jobs.empty(); })) {
            lock.unlock();
            window->poll_events();
            if (window->take_redraw_request() && presenter->frame_width() > 0) {
              const render::window::FramebufferSize size = window->framebuffer_size();
              presenter->draw(image::ToneMapping::clamp, {0, size.width, size.height});
              window->swap_buffers();
            }
            lock.lock();
          }
        } else {
          wake.wait(lock, [this] { return !jobs.empty(); });
        }
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
          case Job::Kind::prepare: prepare(job.table_hash); break;
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
    base_scene = scene::load_scene(options.scene ? *options.scene : options.config.scene);
    viewports = warp::load_viewport_config(options.config.viewports);
    for (const std::string& name : me->outputs) outputs.push_back(viewports.index_of(name));
    rendered_display.resize(outputs.size());
    table_options.sizes = render::table_sizes_by_name(options.config.table_sizes);
    table_options.max_orders = options.config.table_orders;
    atmospheres.add_scene_and_candidates(options.atmosphere_files);
    atmospheres.load_kept_definitions();
    node_directory = options.layout == FrameFileLayout::offline
                         ? options.output_directory / "nodes" / options.node_name
                         : options.output_directory / options.node_name;
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
        push(Job{Job::Kind::stop, {}, 0, {}});
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
