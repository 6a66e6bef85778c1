#include "cluster/node/render_worker.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "atmosphere/lut/table_cache.h"
#include "scene/frame_scene.h"
#include "cluster/node/thumbnail.h"
#include "cluster/protocol/state_digest.h"
#include "core/json_reader.h"
#include "core/timing.h"
#include "image/tone_mapping.h"
#include "render/render_flags.h"

namespace zenith::cluster {

using config::cat;  // core/json_reader.h
using core::ms_since;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

RenderWorker::RenderWorker(Setup setup, Events events)
    : setup_(std::move(setup)),
      events_(std::move(events)),
      writer_(setup_.viewports, setup_.options.layout, setup_.options.output_directory, setup_.node_directory,
              setup_.options.config.output_format),
      rendered_display_(setup_.outputs.size()) {}

// ---- the queue --------------------------------------------------------------

void RenderWorker::push(Job job) {
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back(std::move(job));
  }
  wake_.notify_one();
}

void RenderWorker::prepare(const Digest& hash, std::uint64_t session) {
  push(Job{Job::Kind::prepare, {}, 0, hash, session});
}
void RenderWorker::render(const FrameState& state, std::uint64_t session, int thumbnail_edge_px) {
  push(Job{Job::Kind::render, state, state.frame, {}, session, thumbnail_edge_px});
}
void RenderWorker::present(std::uint64_t frame) { push(Job{Job::Kind::present, {}, frame, {}, 0}); }
void RenderWorker::stop() { push(Job{Job::Kind::stop, {}, 0, {}, 0}); }

void RenderWorker::abandon_frames() {
  {
    std::lock_guard lock(mutex_);
    std::erase_if(jobs_, [](const Job& j) { return j.kind == Job::Kind::render || j.kind == Job::Kind::present; });
    jobs_.push_back(Job{Job::Kind::discard, {}, 0, {}, 0});
  }
  wake_.notify_one();
}

RenderWorker::Job RenderWorker::next_job() {
  for (;;) {
    std::unique_lock lock(mutex_);
    if (window_) {  // keep the window responsive between frames
      while (!wake_.wait_for(lock, milliseconds(30), [this] { return !jobs_.empty(); })) {
        lock.unlock();
        window_->poll_events();
        if (window_->take_redraw_request() && presenter_->frame_width() > 0) {
          const render::window::FramebufferSize size = window_->framebuffer_size();
          presenter_->draw(image::ToneMapping::clamp, {0, size.width, size.height});
          window_->swap_buffers();
        }
        lock.lock();
      }
    } else {
      wake_.wait(lock, [this] { return !jobs_.empty(); });
    }
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    if (job.kind == Job::Kind::render &&
        std::any_of(jobs_.begin(), jobs_.end(), [](const Job& j) { return j.kind == Job::Kind::render; })) {
      spdlog::warn("node '{}': skipping frame {}: a newer frame is queued", setup_.options.node_name, job.frame);
      continue;
    }
    return job;
  }
}

void RenderWorker::run() {
  for (;;) {
    const Job job = next_job();
    try {
      switch (job.kind) {
        case Job::Kind::prepare: prepare_tables(job.table_hash, job.session); break;
        case Job::Kind::render: render_frame(job.state, job.session, job.thumbnail_edge_px); break;
        case Job::Kind::present: present_frame(job.frame); break;
        case Job::Kind::discard: writer_.discard(); break;
        case Job::Kind::stop: writer_.discard(); return;
      }
    } catch (const std::exception& e) {
      spdlog::error("node '{}': {}", setup_.options.node_name, e.what());
      events_.failed(e.what());
    }
  }
}

void RenderWorker::release_gl() {
  renderer_.reset();
  context_.reset();
}

// ---- GL and the renderer ----------------------------------------------------

void RenderWorker::make_current() const {
  if (window_) window_->make_current();
  else context_->make_current();
}

void RenderWorker::ensure_renderer(std::uint32_t flags) {
  const NodeOptions& options = setup_.options;
  if (options.window && !window_) {
    render::window::WindowOptions w;
    w.title = cat("zenith node ", options.node_name);
    w.width = 0;
    w.height = 0;
    for (const std::size_t i : setup_.outputs) {
      w.width += setup_.viewports.outputs[i].width_px;
      w.height = std::max(w.height, setup_.viewports.outputs[i].height_px);
    }
    // Fit a 1280 × 1024 screen area at first; the window can be resized (or made full screen).
    const double shrink = std::min(1.0, std::min(1280.0 / w.width, 1024.0 / w.height));
    w.width = std::max(1, static_cast<int>(w.width * shrink));
    w.height = std::max(1, static_cast<int>(w.height * shrink));
    w.swap_interval = 0;  // the cluster's barrier paces the frames
    window_.emplace(w);
    presenter_.emplace();
    spdlog::info("node '{}': rendering on {} into a window", options.node_name, window_->renderer());
  } else if (!options.window && !context_) {
    context_.emplace();
    spdlog::info("node '{}': rendering on {}", options.node_name, context_->renderer());
  }
  if (renderer_ && flags == renderer_flags_) return;
  renderer_.reset();
  renderer_flags_ = flags;
  const atmosphere::lut::TableCache cache(options.cache_directory);
  renderer_ = std::make_unique<render::Renderer>(
      render::render_options_of(flags), [this, cache](const atmosphere::AtmosphereModel& model) {
        std::string problem;
        std::optional<atmosphere::lut::LookupTables> tables = cache.load(model, setup_.table_options, &problem);
        if (!tables)
          throw std::runtime_error(cat("the tables the master sent are not usable from ", cache.directory().string(),
                                       problem.empty() ? std::string() : cat(": ", problem)));
        make_current();
        return std::move(*tables);
      });
}

void RenderWorker::use_table_version(scene::Scene& scene, const std::string& body, const Digest& hash) const {
  const KnownAtmospheres::Entry& known = setup_.atmospheres.find(hash);
  for (scene::Body& b : scene.bodies)
    if (b.name == body && b.atmosphere) {
      b.atmosphere->loaded = known.loaded;
      return;
    }
  throw std::runtime_error(cat("FrameState names body '", body, "', which has no atmosphere in ",
                               setup_.base_scene.source));
}

// ---- jobs -------------------------------------------------------------------

void RenderWorker::render_frame(const FrameState& state, std::uint64_t session, int thumbnail_edge_px) {
  writer_.discard();
  if (setup_.options.debug_render_delay_ms > 0)
    std::this_thread::sleep_for(milliseconds(setup_.options.debug_render_delay_ms));  // test hook: a slow node
  const auto t0 = Clock::now();
  scene::Scene scene = setup_.base_scene;
  scene::apply_frame(state, scene);
  std::string tables;
  for (const AtmosphereTableRef& ref : state.atmospheres) {
    use_table_version(scene, ref.body_name, ref.table_hash);
    tables += cat(tables.empty() ? "" : ",", ref.body_name, "=", to_hex(ref.table_hash).substr(0, 16));
  }
  if (tables.empty()) tables = "-";
  ensure_renderer(state.render_flags);
  std::vector<Thumbnail> thumbnails;
  for (std::size_t k = 0; k < setup_.outputs.size(); ++k) {
    const std::size_t i = setup_.outputs[k];
    const warp::OutputConfig& o = setup_.viewports.outputs[i];
    std::vector<float> rgb = renderer_->render_image(scene, *o.projection);
    const image::ImageAttributes attributes = {
        {"zenith:scene", scene.name},
        {"zenith:projection", o.projection->describe()},
        {"zenith:exposure", fmt::format("{}", scene.camera.exposure)},
        {"zenith:viewport", fmt::format("{}#{}", setup_.viewports.source, o.name)},
    };
    if (window_) rendered_display_[k] = writer_.display_image(i, rgb);  // what the projector shows
    if (thumbnail_edge_px > 0)  // only for a frame the master asked thumbnails of
      thumbnails.push_back(make_thumbnail(state.frame, o.name, window_ ? rendered_display_[k] : writer_.display_image(i, rgb),
                                          o.width_px, o.height_px, thumbnail_edge_px));
    writer_.write(i, state.frame, std::move(rgb), attributes);
  }
  writer_.finish_frame({state.frame, state_digest(state), tables, state.show_time_s});
  const double render_ms = ms_since(t0);
  spdlog::debug("node '{}': frame {} rendered in {:.1f} ms", setup_.options.node_name, state.frame, render_ms);
  events_.rendered(state.frame, render_ms, session, std::move(thumbnails));
}

void RenderWorker::present_frame(std::uint64_t frame) {
  if (!writer_.present(frame)) {
    spdlog::warn("node '{}': Present {} for a frame this node has not rendered; ignored", setup_.options.node_name,
                 frame);
    return;
  }
  if (window_) show_in_window();
  spdlog::debug("node '{}': presented frame {}", setup_.options.node_name, frame);
}

/// Renders with the set once: every output the first time (shaders), then the
/// first output only (table upload).
void RenderWorker::prepare_tables(const Digest& hash, std::uint64_t session) {
  ensure_renderer(render::render_flags_of(render::RenderOptions{}));
  const auto t0 = Clock::now();
  scene::Scene scene = setup_.base_scene;
  const KnownAtmospheres::Entry& known = setup_.atmospheres.find(hash);
  use_table_version(scene, known.body, hash);
  for (const std::size_t i : setup_.outputs) {
    renderer_->render_image(scene, *setup_.viewports.outputs[i].projection);
    if (warmed_up_) break;
  }
  warmed_up_ = true;
  spdlog::info("node '{}': tables of '{}' version {} loaded and rendered once ({:.0f} ms)", setup_.options.node_name,
               known.body, short_hex(hash), ms_since(t0));
  events_.tables_ready(hash, session);
}

void RenderWorker::show_in_window() {
  int width = 0, height = 0;
  for (const std::size_t i : setup_.outputs) {
    width += setup_.viewports.outputs[i].width_px;
    height = std::max(height, setup_.viewports.outputs[i].height_px);
  }
  std::vector<float> picture(static_cast<std::size_t>(width) * height * 3, 0.0f);
  int x0 = 0;
  for (std::size_t k = 0; k < setup_.outputs.size(); ++k) {
    const warp::OutputConfig& o = setup_.viewports.outputs[setup_.outputs[k]];
    const std::vector<float>& display = rendered_display_[k];
    for (int y = 0; y < o.height_px && !display.empty(); ++y)
      std::copy_n(display.begin() + static_cast<std::ptrdiff_t>(y) * o.width_px * 3, o.width_px * 3,
                  picture.begin() + (static_cast<std::ptrdiff_t>(y) * width + x0) * 3);
    x0 += o.width_px;
  }
  window_->make_current();
  const render::window::FramebufferSize size = window_->framebuffer_size();
  presenter_->present(picture, width, height, image::ToneMapping::clamp, {0, size.width, size.height});
  window_->swap_buffers();
  window_->poll_events();
  if (window_->should_close()) {
    spdlog::info("node '{}': window closed: leaving the cluster", setup_.options.node_name);
    events_.window_closed();
  }
}

}  // namespace zenith::cluster
