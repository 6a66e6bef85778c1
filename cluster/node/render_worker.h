#pragma once
// A render node's render thread (docs/cluster.md, "Architecture"): owns the GL
// context (headless, or a window's), the renderer and the frame files. The
// networking thread hands it jobs — load a table set and warm up, render a
// FrameState, present a frame, stop — through a queue; it answers through the
// Events callbacks, called on the render thread (the node posts them onto its
// io_context).
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "atmosphere/lut/lookup_tables.h"
#include "atmosphere/lut/precompute_options.h"
#include "cluster/node/known_atmospheres.h"
#include "cluster/node/node.h"
#include "cluster/node/output_writer.h"
#include "cluster/node/present_timing.h"
#include "cluster/protocol/messages.h"
#include "render/display/display_encoder.h"
#include "render/gl/egl_context.h"
#include "render/gl/texture.h"
#include "render/renderer.h"
#include "render/window/output_windows.h"
#include "scene/scene.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {

/// Invariants: only run() touches GL, the renderer and the files; the queue
/// is the only state shared with other threads. A render job is skipped when
/// a newer one is queued behind it: under the barrier at once (the master
/// moved on), on a schedule once the newer one is due (drop_frame_behind() in
/// present_schedule.h). A job that throws
/// reports Events::failed and the worker goes on with the next job. Every
/// answer carries the `session` its job was queued with (the node's count of
/// Welcomes), so that the node can drop answers meant for a connection that
/// is gone. abandon_frames() leaves the last presented frame (files, window)
/// as it is.
class RenderWorker {
 public:
  /// The worker's answers, called on the render thread.
  struct Events {
    /// RenderDone (with the windows' present counts so far), after the frame's
    /// thumbnails when they were asked for (else none).
    std::function<void(const RenderDone& done, std::uint64_t session, std::vector<Thumbnail> thumbnails)> rendered;
    std::function<void(const Digest& table_hash, std::uint64_t session)> tables_ready;  ///< TableReady
    std::function<void(const std::string& what)> failed;
    std::function<void()> window_closed;  ///< the operator closed the node's window
  };

  /// What the worker renders and where: all references must outlive it.
  struct Setup {
    const NodeOptions& options;
    const scene::Scene& base_scene;
    const warp::ViewportConfig& viewports;
    std::vector<std::size_t> outputs;  ///< this node's outputs: indices into viewports.outputs
    const KnownAtmospheres& atmospheres;
    atmosphere::lut::PrecomputeOptions table_options;
    std::filesystem::path node_directory;  ///< presented.log (and the frames of the per-node layout)
  };

  RenderWorker(Setup setup, Events events);
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  // ---- any thread ----
  /// Tables just read from the cache with their checksums checked (the
  /// inventory a node sends after Welcome): the next prepare of that model's
  /// set takes them instead of reading the file a second time. The last
  /// kMaxOfferedTables offered are kept, until the first frame renders.
  void offer_tables(const atmosphere::AtmosphereModel& model, atmosphere::lut::LookupTables tables);
  static constexpr std::size_t kMaxOfferedTables = 4;

  // ---- any thread: queue a job ----
  /// Load table set `hash` (checksums checked) and render with it once; then Events::tables_ready.
  void prepare(const Digest& hash, std::uint64_t session);
  /// Render a frame; with `thumbnail_edge_px` > 0 also a thumbnail of every
  /// output (thumbnail.h) for the master's dome preview; `moment`: a scheduled
  /// frame's moment (when a later frame is queued behind it: drop_frame_behind()).
  void render(const FrameState& state, std::uint64_t session, int thumbnail_edge_px = 0,
              std::optional<std::chrono::steady_clock::time_point> moment = std::nullopt);
  /// Present `frame`: now (a Present of the barrier), or a scheduled frame at
  /// its moment `scheduled` (handed over up to present_handoff() before it:
  /// the render thread waits for it, at the present's priority; its lateness
  /// is measured from it).
  void present(std::uint64_t frame, std::optional<std::chrono::steady_clock::time_point> scheduled = std::nullopt);
  /// The outputs' windows show black (the link to the master is cut and the
  /// config says "link_lost": "black"); the next present shows frames again.
  void blank();
  /// The connection to the master is lost: drops the queued render and
  /// present jobs and, after the frame being rendered (if any), its partial
  /// files. The presented frames stay (files and window): the projector
  /// keeps showing the last one.
  void abandon_frames();
  /// run() returns after the jobs queued before this one.
  void stop();

  // ---- the render thread ----
  /// Runs jobs until stop(); keeps a window responsive between them.
  void run();
  /// Releases the renderer and the headless GL context (after run()).
  void release_gl();

 private:
  struct Job {
    enum class Kind { prepare, render, present, discard, blank, stop } kind = Kind::stop;
    FrameState state;           ///< render
    std::uint64_t frame = 0;    ///< render, present
    Digest table_hash{};        ///< prepare
    std::uint64_t session = 0;  ///< render, prepare: passed back with the answer
    int thumbnail_edge_px = 0;  ///< render: > 0 for thumbnails of the frame
    /// When the frame was asked for: a scheduled frame's moment (`scheduled`;
    /// render, present), or the Present's arrival under the barrier (present).
    std::chrono::steady_clock::time_point asked{};
    bool scheduled = false;
  };
  void push(Job job);
  Job next_job();

  void make_current() const;
  /// The GL context (the windows' or a headless one) and, per output, its textures and display pass.
  void ensure_context();
  void ensure_renderer(std::uint32_t flags);
  /// The scene with body `body`'s atmosphere replaced by table version `hash`.
  void use_table_version(scene::Scene& scene, const std::string& body, const Digest& hash) const;
  void render_frame(const FrameState& state, std::uint64_t session, int thumbnail_edge_px);
  void present_frame(std::uint64_t frame, std::chrono::steady_clock::time_point asked, bool scheduled);
  /// One line of presents.csv: the frame, when it was presented (the swap
  /// queued, or its files renamed into place), when it was asked for (the
  /// scheduled moment, or the Present's arrival), when the render thread woke
  /// for it (from its sleep before the moment; after the moment where a render
  /// held the thread) and when it had asked to wake (the moment less the wake
  /// margin; 0 under the barrier), in ns of the steady clock (CLOCK_MONOTONIC:
  /// on one machine every process's, so nodes in network namespaces compare
  /// exactly).
  void note_present_time(std::uint64_t frame, const MomentWake& wake, std::chrono::steady_clock::time_point presented,
                         std::chrono::steady_clock::time_point asked, bool scheduled);
  void prepare_tables(const Digest& hash, std::uint64_t session);
  void blank_outputs();
  /// Output k's radiance read back as RGB rows for its file (width · height · 3 floats).
  std::vector<float> read_back_radiance(std::size_t k) const;
  /// Events::window_closed, once.
  void report_window_closed();
  /// The display textures the windows draw, per output.
  std::vector<const render::gl::Texture*> display_textures() const;

  /// One output of this node on the GPU: the rendered frame
  /// (Renderer::render_to_texture) and, with windows, what its projector is
  /// sent (the display pass).
  struct OutputFrame {
    render::gl::Texture radiance;                   ///< rgba32f, linear radiance × exposure (allocated on first use)
    render::gl::Texture display;                    ///< rgba8, encoded for the display (windows only)
    render::gl::Texture blend_mask;                 ///< r32f α where the output blends
    render::display::ColourProfileTextures colour;  ///< an MPCDI region's colour profile, uploaded once
    render::display::OutputStage stage;
  };

  Setup setup_;
  Events events_;
  OutputWriter writer_;
  PresentPriority present_priority_;
  WakeMargin wake_margin_;  ///< how early the render thread wakes before a moment

  std::mutex mutex_;
  /// offer_tables: by atmosphere::lookup_table_hash, oldest first.
  std::mutex offered_mutex_;
  std::deque<std::pair<std::string, atmosphere::lut::LookupTables>> offered_;
  std::optional<atmosphere::lut::LookupTables> take_offered(const atmosphere::AtmosphereModel& model);
  std::condition_variable wake_;
  std::deque<Job> jobs_;

  std::optional<render::gl::HeadlessContext> context_;
  /// With windows: the GL context is the first window's, and each presented
  /// frame's display textures are drawn in them (render/window/output_windows.h).
  std::optional<render::window::OutputWindows> windows_;
  std::vector<OutputFrame> frames_;  ///< per output of this node
  render::display::DisplayEncoder encoder_;
  std::unique_ptr<render::Renderer> renderer_;
  std::uint32_t renderer_flags_ = 0;
  bool warmed_up_ = false;
  std::uint64_t warm_up_late_ = 0;  ///< whether the windows' first present was late (not reported)
  bool close_reported_ = false;
  std::ofstream present_times_;  ///< presents.csv in the node's directory, opened at the first present
};

}  // namespace zenith::cluster
