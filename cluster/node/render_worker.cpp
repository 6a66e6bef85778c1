#include "cluster/node/render_worker.h"

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "astro/sky_data_identity.h"
#include "atmosphere/lut/table_cache.h"
#include "atmosphere/model_hash.h"
#include "cluster/node/present_schedule.h"
#include "cluster/node/thumbnail.h"
#include "core/json_reader.h"
#include "core/timing.h"
#include "image/tone_mapping.h"
#include "render/render_flags.h"
#include "scene/frame_digest.h"
#include "scene/frame_scene.h"

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
      present_priority_(setup_.options.config.realtime_presents, setup_.options.node_name),
      wake_margin_(present_handoff(setup_.options.config.frame_rate_hz) / 2) {}

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
void RenderWorker::render(const FrameState& state, std::uint64_t session, int thumbnail_edge_px,
                          std::optional<Clock::time_point> moment) {
  push(Job{Job::Kind::render,
           state,
           state.frame,
           {},
           session,
           thumbnail_edge_px,
           moment.value_or(Clock::time_point{}),
           moment.has_value()});
}
void RenderWorker::present(std::uint64_t frame, std::optional<Clock::time_point> scheduled) {
  push(Job{Job::Kind::present, {}, frame, {}, 0, 0, scheduled.value_or(Clock::now()), scheduled.has_value()});
}
void RenderWorker::stop() { push(Job{Job::Kind::stop, {}, 0, {}, 0}); }
void RenderWorker::blank() { push(Job{Job::Kind::blank, {}, 0, {}, 0}); }

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
    if (windows_) {  // keep the windows responsive between frames
      while (!wake_.wait_for(lock, milliseconds(30), [this] { return !jobs_.empty(); })) {
        lock.unlock();
        if (windows_->poll_close_request()) report_window_closed();
        windows_->redraw_if_asked(display_textures());
        lock.lock();
      }
    } else {
      wake_.wait(lock, [this] { return !jobs_.empty(); });
    }
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    if (job.kind == Job::Kind::render) {
      const auto later =
          std::find_if(jobs_.begin(), jobs_.end(), [](const Job& j) { return j.kind == Job::Kind::render; });
      if (later != jobs_.end() &&
          drop_frame_behind(later->scheduled ? std::optional(later->asked) : std::nullopt, Clock::now())) {
        if (later->scheduled)
          spdlog::warn("node '{}': skipping frame {}: frame {} is due already (rendering fell behind)",
                       setup_.options.node_name, job.frame, later->frame);
        else
          spdlog::warn("node '{}': skipping frame {}: another frame is queued after it", setup_.options.node_name,
                       job.frame);
        continue;
      }
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
        case Job::Kind::present: present_frame(job.frame, job.asked, job.scheduled); break;
        case Job::Kind::discard: writer_.discard(); break;
        case Job::Kind::blank: blank_outputs(); break;
        case Job::Kind::stop: writer_.discard(); return;
      }
    } catch (const std::exception& e) {
      spdlog::error("node '{}': {}", setup_.options.node_name, e.what());
      events_.failed(e.what());
    }
  }
}

void RenderWorker::release_gl() {
  if (windows_) {
    const render::window::PresentClock& c = windows_->clock();
    spdlog::info(
        "node '{}': presented {} frame{} in its windows, {} late (a missed vblank); Present to swap at most "
        "{:.1f} ms",
        setup_.options.node_name, c.presented(), c.presented() == 1 ? "" : "s", c.late(), c.worst_ms());
  }
  if (windows_ || context_) make_current();
  renderer_.reset();
  frames_.clear();
  encoder_ = render::display::DisplayEncoder();
  windows_.reset();
  context_.reset();
}

// ---- GL and the renderer ----------------------------------------------------

void RenderWorker::make_current() const {
  if (windows_)
    windows_->primary().make_current();
  else
    context_->make_current();
}

void RenderWorker::ensure_context() {
  if (windows_ || context_) return;
  const NodeOptions& options = setup_.options;
  if (options.window) {
    std::vector<render::window::ShownOutput> shown;
    for (const std::size_t i : setup_.outputs) {
      const warp::OutputConfig& o = setup_.viewports.outputs[i];
      shown.push_back({o.name, o.width_px, o.height_px, o.window});
    }
    windows_.emplace(shown, cat("zenith node ", options.node_name));
    spdlog::info("node '{}': rendering on {} into {} window{}", options.node_name, windows_->primary().renderer(),
                 windows_->window_count(), windows_->window_count() == 1 ? "" : "s");
    // Pacing (docs/cluster.md, "Pacing and swap groups"): a swap group where the driver has one.
    if (options.config.swap_group > 0)
      spdlog::info("node '{}': {}", options.node_name, windows_->join_swap_group(options.config.swap_group));
    spdlog::info("node '{}': late presents counted from {}", options.node_name,
                 windows_->counts_vblanks() ? "the display's vblank counter (GLX_OML_sync_control)"
                 : windows_->clock().refresh_hz() > 0.0
                     ? fmt::format("the wall clock against the {} Hz refresh (no GLX_OML_sync_control)",
                                   windows_->clock().refresh_hz())
                     : std::string("nothing: no vsync or no refresh rate known; none is counted late"));
  } else {
    context_.emplace();
    spdlog::info("node '{}': rendering on {}", options.node_name, context_->renderer());
  }
  // Per output: the frame's texture, the display pass's settings and, with windows, its display texture.
  for (const std::size_t i : setup_.outputs) {
    const warp::OutputConfig& o = setup_.viewports.outputs[i];
    OutputFrame f;
    if (windows_) f.display = render::gl::Texture::create_2d(render::gl::TextureFormat::rgba8, o.width_px, o.height_px);
    f.stage.blended = has_output_stage(o);
    if (f.stage.blended)
      f.blend_mask = render::display::blend_mask_texture(warp::output_blend_mask(setup_.viewports, i));
    f.stage.black_level = o.black_level;
    if (o.window && o.window->gamma > 0.0)
      f.stage.encoding = {image::DisplayEncoding::Transfer::gamma, o.window->gamma};
    if (o.colour) f.colour = render::display::ColourProfileTextures(*o.colour);
    frames_.push_back(std::move(f));
  }
  for (OutputFrame& f : frames_) {  // after the moves: addresses are final
    if (f.blend_mask.id() != 0) f.stage.blend_mask = &f.blend_mask;
    if (!f.colour.empty()) f.stage.colour = &f.colour;
  }
}

void RenderWorker::offer_tables(const atmosphere::AtmosphereModel& model, atmosphere::lut::LookupTables tables) {
  std::lock_guard lock(offered_mutex_);
  offered_.emplace_back(atmosphere::lookup_table_hash(model), std::move(tables));
  while (offered_.size() > kMaxOfferedTables) offered_.pop_front();
}

std::optional<atmosphere::lut::LookupTables> RenderWorker::take_offered(const atmosphere::AtmosphereModel& model) {
  const std::string key = atmosphere::lookup_table_hash(model);
  std::lock_guard lock(offered_mutex_);
  for (auto it = offered_.begin(); it != offered_.end(); ++it)
    if (it->first == key) {
      atmosphere::lut::LookupTables tables = std::move(it->second);
      offered_.erase(it);
      return tables;
    }
  return std::nullopt;
}

void RenderWorker::ensure_renderer(std::uint32_t flags) {
  const NodeOptions& options = setup_.options;
  ensure_context();
  if (renderer_ && flags == renderer_flags_) return;
  renderer_.reset();
  renderer_flags_ = flags;
  const atmosphere::lut::TableCache cache(options.cache_directory);
  render::RenderOptions render_options = render::render_options_of(flags);
  // Every node's outputs take the sky-view table's path alike, whatever their
  // sizes: a small output beside a large one would otherwise show a seam.
  render_options.sky_view_table = render::sky_view_use_for_outputs(setup_.viewports.largest_output_pixels());
  // A node's frames are live: a new Moon's shadow in an eclipse, and the
  // programs of a new variant, are built on a worker thread while frames go
  // on (render/frame/eclipse_sky_table.h, render/frame/live_variants.h).
  render_options.background_shadow_builds = true;
  render_options.background_variant_builds = true;
  // A restarted node builds one tile program per shell, not one per tile kind (the same pixels).
  render_options.tile_programs = render::TilePrograms::own_once_built;
  render_options.albedo_cache_directory = options.cache_directory;
  if (!options.cache_directory.empty()) render_options.program_cache_directory = options.cache_directory / "programs";
  renderer_ =
      std::make_unique<render::Renderer>(render_options, [this, cache](const atmosphere::AtmosphereModel& model) {
        if (std::optional<atmosphere::lut::LookupTables> offered = take_offered(model)) return std::move(*offered);
        std::string problem;
        std::optional<atmosphere::lut::LookupTables> tables = cache.load(model, setup_.table_options, &problem);
        if (!tables)
          throw std::runtime_error(cat("the tables the master sent are not usable from ", cache.directory().string(),
                                       problem.empty() ? std::string() : cat(": ", problem)));
        make_current();
        return std::move(*tables);
      });
  // With windows the steady frame goes band by band into each output's display
  // pass: its first draw warmed on the renderer's warm-up thread (llvmpipe).
  if (windows_)
    renderer_->set_band_sink_warmup([this](render::gl::FirstDispatchWarmup& warmup) {
      for (const OutputFrame& f : frames_) encoder_.warm_band(warmup, f.stage, f.display);
    });
}

void RenderWorker::use_table_version(scene::Scene& scene, const std::string& body, const Digest& hash) const {
  const KnownAtmospheres::Entry& known = setup_.atmospheres.find(hash);
  for (scene::Body& b : scene.bodies)
    if (b.name == body && b.atmosphere) {
      b.atmosphere->loaded = known.loaded;
      return;
    }
  throw std::runtime_error(
      cat("FrameState names body '", body, "', which has no atmosphere in ", setup_.base_scene.source));
}

// ---- jobs -------------------------------------------------------------------

void RenderWorker::render_frame(const FrameState& state, std::uint64_t session, int thumbnail_edge_px) {
  writer_.discard();
  {  // the sets the show starts with are prepared by now; a later one is read from its file then
    std::lock_guard lock(offered_mutex_);
    offered_.clear();
  }
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
  // The frame stays on the GPU: rendered into each output's texture, encoded
  // for its display there; only files and thumbnails read pixels back.
  for (std::size_t k = 0; k < setup_.outputs.size(); ++k) {
    const std::size_t i = setup_.outputs[k];
    const warp::OutputConfig& o = setup_.viewports.outputs[i];
    OutputFrame& f = frames_[k];
    // The operator's fade, part of the frame's state: every node shows it at this frame.
    f.stage.fade = {state.fade.level, {state.fade.colour.x, state.fade.colour.y, state.fade.colour.z}};
    const bool radiance_read = thumbnail_edge_px > 0 || setup_.options.write_frames;
    if ((radiance_read || !windows_) && f.radiance.id() == 0)  // allocated on first use (an 8K master: 1 GiB)
      f.radiance = render::gl::Texture::create_2d(render::gl::TextureFormat::rgba32f, o.width_px, o.height_px);
    if (radiance_read) {
      renderer_->render_to_texture(scene, *o.projection, f.radiance);
      if (windows_) encoder_.encode(f.radiance, f.stage, f.display);  // what the projector shows
    } else if (windows_) {  // the steady live frame: band by band straight into what the projector shows
      renderer_->render_on_gpu(scene, *o.projection,
                               [&](const render::GpuBand& band) { encoder_.encode_band(band, f.stage, f.display); });
    } else {
      renderer_->render_to_texture(scene, *o.projection, f.radiance);  // headless, nothing asked: the frame stays here
    }
    if (thumbnail_edge_px > 0)  // only for a frame the master asked thumbnails of
      thumbnails.push_back(
          make_thumbnail(state.frame, o.name, encoder_.thumbnail(f.radiance, f.stage, thumbnail_edge_px)));
    if (setup_.options.write_frames) {
      const image::ImageAttributes attributes = {
          {"zenith:scene", scene.name},
          {"zenith:projection", o.projection->describe()},
          {"zenith:exposure", fmt::format("{}", scene.camera.exposure)},
          {"zenith:viewport", fmt::format("{}#{}", setup_.viewports.source, o.name)},
      };
      writer_.write(i, state.frame, read_back_radiance(k), attributes, state.fade);
    }
  }
  // The stars and the Moon's face: every node draws them from the data the
  // master named (their identity, docs/protocol.md: FrameState's sky fields;
  // astro/sky_data_identity.h), or the quadrants differ.
  const render::FrameStats& drawn = renderer_->last_frame();
  const std::string stars =
      drawn.night_sky.catalogue_identity.empty()
          ? ""
          : astro::sky_data_identity(drawn.night_sky.catalogue_identity, drawn.night_sky.moon_map_identity);
  if (state.sky.star_catalogue != Digest{} && !stars.empty() && stars != to_hex(state.sky.star_catalogue))
    throw std::runtime_error(cat("FrameState.sky.star_catalogue is ", to_hex(state.sky.star_catalogue).substr(0, 16),
                                 "…, but this node's stars and Moon map are ", stars.substr(0, 16),
                                 "… (another stellarium-data or magnitude limit than the master's)"));
  // RenderDone means ready to present: the GPU has finished the frame.
  glFinish();
  writer_.finish_frame({state.frame, scene::frame_digest(state), tables, state.show_time_s, state.fade});
  const double render_ms = ms_since(t0);
  spdlog::debug("node '{}': frame {} rendered in {:.1f} ms", setup_.options.node_name, state.frame, render_ms);
  RenderDone done{state.frame, render_ms};
  if (windows_) {  // how the presents so far went (render/window/present_clock.h)
    done.presents = windows_->clock().presented();
    done.late_presents = windows_->clock().late() - warm_up_late_;
    done.present_ms = windows_->clock().last_ms();
  }
  events_.rendered(done, session, std::move(thumbnails));
}

void RenderWorker::report_window_closed() {
  if (close_reported_) return;  // the node is leaving already
  close_reported_ = true;
  spdlog::info("node '{}': window closed: leaving the cluster", setup_.options.node_name);
  events_.window_closed();
}

std::vector<float> RenderWorker::read_back_radiance(std::size_t k) const {
  const std::vector<float> rgba = frames_[k].radiance.read();
  std::vector<float> rgb(rgba.size() / 4 * 3);
  for (std::size_t p = 0; p < rgba.size() / 4; ++p)
    for (std::size_t c = 0; c < 3; ++c) rgb[3 * p + c] = rgba[4 * p + c];
  return rgb;
}

std::vector<const render::gl::Texture*> RenderWorker::display_textures() const {
  std::vector<const render::gl::Texture*> displays;
  for (const OutputFrame& f : frames_) displays.push_back(&f.display);
  return displays;
}

void RenderWorker::present_frame(std::uint64_t frame, Clock::time_point asked, bool scheduled) {
  // A scheduled frame: wait for its moment — asleep, then awake for the wake
  // margin — and present at once, ahead of any normal thread on the machine
  // (present_timing.h).
  std::optional<PresentPriority::Raised> raised;
  MomentWake wake{Clock::time_point{}, Clock::now()};
  if (scheduled) {
    raised.emplace(present_priority_.raise());
    wake = wait_for_moment(asked, wake_margin_);
  }
  // The act first — the swap (the projectors), else the frame files renamed
  // into place — and its time; then the bookkeeping, at normal priority: a log
  // line's file system call (a slow disk, the journal's commit) is no part of
  // when the frame was shown.
  if (windows_) {
    // A driver may spin in the swap until the vertical blank (yielding, which
    // does not yield to normal threads once real-time): the swap is queued at
    // normal priority, promptly, since the thread is already running.
    raised.reset();
    windows_->present(display_textures(), asked);
  }
  const bool rendered = writer_.present(frame);
  const Clock::time_point presented = Clock::now();
  raised.reset();
  if (windows_) {
    // The windows' first swap is part of the warm-up (the driver's buffers, the
    // compositor): a late first present is not counted (frame_pacer.h).
    if (windows_->clock().presented() == 1) warm_up_late_ = windows_->clock().late();
    if (windows_->poll_close_request()) report_window_closed();
  }
  if (!rendered) {
    spdlog::warn("node '{}': Present {} for a frame this node has not rendered; ignored", setup_.options.node_name,
                 frame);
    return;
  }
  writer_.log_presented();
  note_present_time(frame, wake, presented, asked, scheduled);
  spdlog::debug("node '{}': presented frame {}", setup_.options.node_name, frame);
}

void RenderWorker::note_present_time(std::uint64_t frame, const MomentWake& wake, Clock::time_point presented,
                                     Clock::time_point asked, bool scheduled) {
  const auto ns = [](Clock::time_point t) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
  };
  if (!present_times_.is_open()) {
    const std::filesystem::path path = setup_.node_directory / "presents.csv";
    const bool fresh = !std::filesystem::exists(path);
    present_times_.open(path, std::ios::app);
    if (fresh) present_times_ << "frame,presented_ns,asked_ns,scheduled,woke_ns,wake_asked_ns\n";
  }
  present_times_ << frame << ',' << ns(presented) << ',' << ns(asked) << ',' << (scheduled ? 1 : 0) << ','
                 << ns(wake.woke) << ',' << ns(wake.asked) << '\n';
  present_times_.flush();  // read while the show runs (tests, benchmarks)
}

void RenderWorker::blank_outputs() {
  if (!windows_) return;  // headless: no projector to blank (the files keep the last frame)
  make_current();
  const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  for (OutputFrame& f : frames_)
    if (f.display.id() != 0) glClearTexImage(f.display.id(), 0, GL_RGBA, GL_FLOAT, black);
  windows_->present(display_textures(), Clock::now());
}

/// Renders with the set once: every output the first time (shaders), then the
/// first output only (table upload). Only the set's own body is in that
/// scene: the others' sets may still be on their way (a slow link), and the
/// programs are every body's.
void RenderWorker::prepare_tables(const Digest& hash, std::uint64_t session) {
  ensure_renderer(render::render_flags_of(render::RenderOptions{}));
  const auto t0 = Clock::now();
  scene::Scene scene = setup_.base_scene;
  const KnownAtmospheres::Entry& known = setup_.atmospheres.find(hash);
  std::erase_if(scene.bodies, [&](const scene::Body& b) { return b.name != known.body; });
  use_table_version(scene, known.body, hash);
  for (std::size_t k = 0; k < setup_.outputs.size(); ++k) {
    OutputFrame& f = frames_[k];
    const warp::Projection& projection = *setup_.viewports.outputs[setup_.outputs[k]].projection;
    if (windows_)  // as a steady frame: the display pass's programs too
      renderer_->render_on_gpu(scene, projection,
                               [&](const render::GpuBand& band) { encoder_.encode_band(band, f.stage, f.display); });
    else
      renderer_->render_on_gpu(scene, projection, [](const render::GpuBand&) {});
    if (warmed_up_) break;
  }
  glFinish();
  warmed_up_ = true;
  spdlog::info("node '{}': tables of '{}' version {} loaded and rendered once ({:.0f} ms)", setup_.options.node_name,
               known.body, short_hex(hash), ms_since(t0));
  events_.tables_ready(hash, session);
}

}  // namespace zenith::cluster
