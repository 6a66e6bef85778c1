#pragma once
// A render node's render thread (docs/cluster.md, "Architecture"): owns the GL
// context (headless, or a window's), the renderer and the frame files. The
// networking thread hands it jobs — load a table set and warm up, render a
// FrameState, present a frame, stop — through a queue; it answers through the
// Events callbacks, called on the render thread (the node posts them onto its
// io_context).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "atmosphere/lut/precompute_options.h"
#include "cluster/protocol/messages.h"
#include "cluster/node/node.h"
#include "cluster/node/known_atmospheres.h"
#include "cluster/node/output_writer.h"
#include "render/gl/egl_context.h"
#include "render/renderer.h"
#include "render/window/frame_presenter.h"
#include "render/window/window_context.h"
#include "scene/scene.h"
#include "warp/viewport_config.h"

namespace zenith::cluster {

/// Invariants: only run() touches GL, the renderer and the files; the queue
/// is the only state shared with other threads. A render job is skipped when
/// a newer one is queued behind it (the master moved on). A job that throws
/// reports Events::failed and the worker goes on with the next job. Every
/// answer carries the `session` its job was queued with (the node's count of
/// Welcomes), so that the node can drop answers meant for a connection that
/// is gone. abandon_frames() leaves the last presented frame (files, window)
/// as it is.
class RenderWorker {
 public:
  /// The worker's answers, called on the render thread.
  struct Events {
    /// RenderDone, after the frame's thumbnails when they were asked for (else none).
    std::function<void(std::uint64_t frame, double render_ms, std::uint64_t session, std::vector<Thumbnail> thumbnails)>
        rendered;
    std::function<void(const Digest& table_hash, std::uint64_t session)> tables_ready;           ///< TableReady
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

  // ---- any thread: queue a job ----
  /// Load table set `hash` (checksums checked) and render with it once; then Events::tables_ready.
  void prepare(const Digest& hash, std::uint64_t session);
  /// Render a frame; with `thumbnail_edge_px` > 0 also a thumbnail of every
  /// output (thumbnail.h) for the master's dome preview.
  void render(const FrameState& state, std::uint64_t session, int thumbnail_edge_px = 0);
  void present(std::uint64_t frame);
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
    enum class Kind { prepare, render, present, discard, stop } kind = Kind::stop;
    FrameState state;         ///< render
    std::uint64_t frame = 0;  ///< render, present
    Digest table_hash{};      ///< prepare
    std::uint64_t session = 0;  ///< render, prepare: passed back with the answer
    int thumbnail_edge_px = 0;  ///< render: > 0 for thumbnails of the frame
  };
  void push(Job job);
  Job next_job();

  void make_current() const;
  void ensure_renderer(std::uint32_t flags);
  /// The scene with body `body`'s atmosphere replaced by table version `hash`.
  void use_table_version(scene::Scene& scene, const std::string& body, const Digest& hash) const;
  void render_frame(const FrameState& state, std::uint64_t session, int thumbnail_edge_px);
  void present_frame(std::uint64_t frame);
  void prepare_tables(const Digest& hash, std::uint64_t session);
  /// Shows the presented frame in the window: the node's outputs side by side.
  void show_in_window();

  Setup setup_;
  Events events_;
  OutputWriter writer_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> jobs_;

  std::optional<render::gl::HeadlessContext> context_;
  /// With a window: the GL context is the window's, and each presented frame
  /// is shown in it (the node's outputs side by side, as written to the files).
  std::optional<render::window::WindowContext> window_;
  std::optional<render::window::FramePresenter> presenter_;
  std::vector<std::vector<float>> rendered_display_;  ///< per output: display-linear values of the rendered frame
  std::unique_ptr<render::Renderer> renderer_;
  std::uint32_t renderer_flags_ = 0;
  bool warmed_up_ = false;
};

}  // namespace zenith::cluster
