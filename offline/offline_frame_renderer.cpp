// The single-process FrameRenderer and its pipeline (offline/offline_frame_renderer.h).
#include "offline/offline_frame_renderer.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "atmosphere/model_hash.h"
#include "core/timing.h"
#include "image/image_writer.h"
#include "render/render_flags.h"
#include "scene/albedo_map.h"
#include "scene/albedo_map_cache.h"

namespace zenith::app::offline {
namespace {

using core::seconds_since;
using render::gl::Texture;
using render::gl::TextureFormat;

/// Table sets read from the cache ahead of the first frame, at most (each a thread and its tables in memory).
constexpr std::size_t kMaxTableSetsAhead = 8;

bool has(const std::vector<ImageFormat>& formats, ImageFormat f) {
  return std::find(formats.begin(), formats.end(), f) != formats.end();
}

/// Linear RGB EXR from the rgba32f radiance read back, with the output stage
/// on the values as render_to_files applies it (v·α·(1 − β) + β).
void write_exr_from_rgba(const std::filesystem::path& path, int width, int height, const float* rgba,
                         image::ExrPixelType type, const LocalOutput& output,
                         const image::ImageAttributes& attributes) {
  constexpr int kChunkRows = 16;
  const auto writer = image::open_exr_writer(path, width, height, type, attributes);
  std::vector<float> rows;
  for (int first = 0; first < height; first += kChunkRows) {
    const int count = std::min(kChunkRows, height - first);
    const std::size_t pixels = std::size_t(width) * std::size_t(count);
    rows.resize(pixels * 3);
    const float* in = rgba + std::size_t(first) * std::size_t(width) * 4;
    for (std::size_t i = 0; i < pixels; ++i)
      for (std::size_t c = 0; c < 3; ++c) rows[3 * i + c] = in[4 * i + c];
    if (output.blend) warp::apply_blend(rows, first, count, *output.blend, output.black_level);
    writer->write_rows(count, rows);
  }
  writer->finish();
}

}  // namespace

/// The memory the readback slots may take by default (--frames-in-flight sets their number instead).
constexpr std::size_t kDefaultSlotBudgetBytes = std::size_t(8) << 30;

bool is_software_renderer(const std::string& device) {
  for (const char* name : {"llvmpipe", "softpipe", "SwiftShader"})
    if (device.find(name) != std::string::npos) return true;
  return false;
}

int default_writer_threads(unsigned cpus, bool software_renderer) {
  const int n = static_cast<int>(std::max(1u, cpus));
  // llvmpipe runs at least a thread per CPU (render/gl/software_rasterizer.h) while a frame renders: it leaves none.
  return software_renderer ? 1 : n;
}

std::string describe(const StartupTimes& t) {
  const double other =
      t.total_s - t.context_s - t.precompute_s - t.tables_s - t.programs_s - t.albedo_s - t.buffers_s - t.first_frame_s;
  return fmt::format(
      "start-up {:.2f} s to the first frame: GL context {:.2f} s, tables precomputed {:.2f} s, tables loaded and "
      "uploaded {:.2f} s ({} set{}), programs {:.2f} s ({} built, {} from stored binaries), albedo maps {:.2f} s, "
      "buffers {:.2f} s ({:.1f} "
      "MiB), the first frame's rendering {:.2f} s, the rest {:.2f} s (the show's checks, the manifest)",
      t.total_s, t.context_s, t.precompute_s, t.tables_s, t.table_sets, t.table_sets == 1 ? "" : "s", t.programs_s,
      t.programs, t.programs_from_binaries, t.albedo_s, t.buffers_s,
      static_cast<double>(t.buffer_bytes) / (1024.0 * 1024.0), t.first_frame_s, std::max(0.0, other));
}

std::span<const std::byte> LocalFrameRenderer::Slot::bytes() const {
  return buffer ? buffer->bytes() : std::span<const std::byte>(memory);
}

LocalFrameRenderer::LocalFrameRenderer(const show::Show& show,
                                       std::map<scene::TableHash, show::AtmosphereVersion> versions,
                                       std::vector<LocalOutput> outputs, PipelineSettings settings,
                                       image::ColourMapping colour, render::TableRequest tables,
                                       const render::gl::ContextOptions& context)
    : show_(show),
      versions_(std::move(versions)),
      outputs_(std::move(outputs)),
      settings_(std::move(settings)),
      colour_(colour),
      tables_(std::move(tables)),
      context_(context) {
  if (settings_.formats.empty()) throw std::invalid_argument("offline render: no formats");
  if (settings_.threads < -1 || settings_.frames_in_flight < 0)
    throw std::invalid_argument("offline render: threads must be ≥ 0 (or automatic), frames in flight ≥ 1");
  const bool display = std::any_of(settings_.formats.begin(), settings_.formats.end(), is_display_format);
  if (settings_.published && !display)
    throw std::invalid_argument("--video needs a display format (png, png16 or tiff) among --format");
  startup_.context_s = seconds_since(created_);
}

LocalFrameRenderer::~LocalFrameRenderer() {
  pool_.reset();            // waits for the frames in flight: their files are written from the slots
  loading_.clear();         // waits for table sets still loading (an error before the first frame)
  albedo_loading_.clear();  // and for albedo maps
  context_.make_current();  // the GL objects belong to this context
  fenced_.clear();
  slots_.clear();
  textures_.clear();
  encoder_ = render::display::DisplayEncoder();
  renderer_.reset();
}

int LocalFrameRenderer::threads() const { return pool_ ? pool_->threads() : settings_.threads; }
int LocalFrameRenderer::frames_in_flight() const { return static_cast<int>(slots_.size()); }
int LocalFrameRenderer::allocated_slots() const {
  return static_cast<int>(
      std::count_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.buffer != nullptr; }));
}

void LocalFrameRenderer::precompute_missing(const show::TablePlan& plan,
                                            const std::set<scene::TableHash>& table_hashes) {
  const auto start = std::chrono::steady_clock::now();
  auto needed = [&](const show::TablePlanEntry& e) {
    return !e.cached && table_hashes.count(e.version.table_hash) > 0;
  };
  const auto missing = std::count_if(plan.sets.begin(), plan.sets.end(), needed);
  std::ptrdiff_t done = 0;
  for (const show::TablePlanEntry& entry : plan.sets) {
    if (!needed(entry)) continue;
    ++done;
    spdlog::info("table set {}/{} (body '{}', first used by frame {}): precomputing", done, missing, entry.version.body,
                 entry.first_frame);
    const render::ObtainedTables t = render::obtain_tables(entry.version.loaded.model, tables_);
    spdlog::info("table set {}/{}: {} in {:.1f} s", done, missing,
                 t.from_cache ? "found in the cache" : "precomputed and cached", t.report.total_seconds());
  }
  context_.make_current();  // the GPU precompute may have used a context of its own
  startup_.precompute_s += seconds_since(start);
  // The sets first used earliest (the first frame's: three for a show of three
  // worlds) read from the cache at once, each on its own thread, while this
  // thread goes on to the first frame; the renderer takes them from loading_.
  std::uint64_t earliest = UINT64_MAX;
  for (const show::TablePlanEntry& e : plan.sets)
    if (table_hashes.count(e.version.table_hash) > 0) earliest = std::min(earliest, e.first_frame);
  for (const show::TablePlanEntry& e : plan.sets) {
    if (e.first_frame != earliest || table_hashes.count(e.version.table_hash) == 0) continue;
    if (loading_.size() >= kMaxTableSetsAhead) break;
    const std::string key = atmosphere::lookup_table_hash(e.version.loaded.model);
    if (loading_.contains(key)) continue;
    loading_.emplace(key, std::async(std::launch::async, [model = e.version.loaded.model, request = tables_] {
                       return render::obtain_tables(model, request);
                     }));
  }
  // The bodies' albedo maps too (a second of a start on a CPU: reading,
  // or generating, Earth's and Mars's), beside the tables.
  const std::filesystem::path albedo_cache = render::cache_directory_of(tables_);
  for (const scene::Body& body : show_.scene().bodies) {
    if (body.albedo.kind == scene::AlbedoSource::Kind::constant) continue;
    const std::string key = scene::albedo_key(body.albedo);
    if (albedo_loading_.contains(key)) continue;
    albedo_loading_.emplace(key, std::async(std::launch::async, [albedo_cache, source = body.albedo] {
                              return scene::load_albedo_map(source, albedo_cache);
                            }));
  }
}

image::LinearImage LocalFrameRenderer::albedo_for(const scene::AlbedoSource& source) {
  if (auto it = albedo_loading_.find(scene::albedo_key(source)); it != albedo_loading_.end()) {
    std::future<image::LinearImage> loading = std::move(it->second);
    albedo_loading_.erase(it);
    return loading.get();
  }
  return scene::load_albedo_map(source, render::cache_directory_of(tables_));
}

atmosphere::lut::LookupTables LocalFrameRenderer::tables_for(const atmosphere::AtmosphereModel& model) {
  if (auto it = loading_.find(atmosphere::lookup_table_hash(model)); it != loading_.end()) {
    std::future<render::ObtainedTables> loading = std::move(it->second);
    loading_.erase(it);
    return loading.get().tables;
  }
  render::ObtainedTables t = render::obtain_tables(model, tables_);
  context_.make_current();  // a precompute may have used a context of its own
  return std::move(t.tables);
}

render::Renderer& LocalFrameRenderer::renderer_for(std::uint32_t render_flags) {
  if (!renderer_ || render_flags != render_flags_) {
    // A recording may change flags between frames: a renderer per run of equal flags.
    context_.make_current();
    renderer_.reset();
    render::RenderOptions options = render::render_options_of(render_flags);
    options.colour = colour_;
    options.serial_compile = settings_.serial_compile;
    // A cold start builds one tile program per shell, not one per tile kind (the same pixels).
    options.tile_programs = render::TilePrograms::own_once_built;
    options.albedo_cache_directory = render::cache_directory_of(tables_);
    options.program_cache_directory = render::program_cache_directory_of(tables_);
    renderer_ = std::make_unique<render::Renderer>(
        options, [this](const atmosphere::AtmosphereModel& model) { return tables_for(model); });
    renderer_->set_albedo_source([this](const scene::AlbedoSource& source) { return albedo_for(source); });
    renderer_->set_band_sink_warmup([this](render::gl::FirstDispatchWarmup& warmup) { warm_display_pass(warmup); });
    render_flags_ = render_flags;
  }
  return *renderer_;
}

void LocalFrameRenderer::start_pipeline() {
  context_.make_current();
  const std::vector<ImageFormat>& f = settings_.formats;
  const bool want8 = has(f, ImageFormat::png), want16 = has(f, ImageFormat::png16) || has(f, ImageFormat::tiff),
             want_radiance = has(f, ImageFormat::exr);
  slot_bytes_ = 0;
  for (const LocalOutput& out : outputs_) {
    const int w = out.projection->width(), h = out.projection->height();
    OutputTextures& t = textures_.emplace_back();
    Region& r = regions_.emplace_back();
    const auto place = [&](Texture& texture, TextureFormat format, std::size_t& offset) {
      texture = Texture::create_2d(format, w, h);
      offset = slot_bytes_;
      slot_bytes_ += render::display::readback_bytes(texture);
    };
    if (want_radiance) place(t.radiance, TextureFormat::rgba32f, r.radiance);
    if (want8) place(t.display8, TextureFormat::rgba8, r.display8);
    if (want16) place(t.display16, TextureFormat::rgba16, r.display16);
    if (out.blend) t.blend_mask = render::display::blend_mask_texture(*out.blend);
    if (out.colour) t.colour = render::display::ColourProfileTextures(*out.colour);
  }
  int threads = settings_.threads;
  if (threads < 0)
    threads = default_writer_threads(std::thread::hardware_concurrency(), is_software_renderer(device()));
  // By default a frame per writer, one on the GPU and one being handed over, within kDefaultSlotBudgetBytes.
  int in_flight = settings_.frames_in_flight;
  if (in_flight <= 0) {
    const auto fit =
        static_cast<int>(std::min<std::size_t>(64, kDefaultSlotBudgetBytes / std::max<std::size_t>(1, slot_bytes_)));
    in_flight = std::max(2, std::min(threads + 2, fit));
  }
  // The slots' buffers are allocated as frames need them (acquire_slot).
  slots_.resize(threads == 0 ? 1 : static_cast<std::size_t>(in_flight));
  slot_frames_.resize(slots_.size());
  pool_ = std::make_unique<FrameWriterPool>(threads);
  for (const OutputTextures& t : textures_)
    for (const Texture* x : {&t.radiance, &t.display8, &t.display16})
      if (x->id() != 0) startup_.buffer_bytes += render::display::readback_bytes(*x);
  spdlog::info("pipeline: {} writer thread{}, at most {} frame{} in flight of {:.1f} MiB each (allocated as needed)",
               threads, threads == 1 ? "" : "s", slots_.size(), slots_.size() == 1 ? "" : "s",
               static_cast<double>(slot_bytes_) / (1024.0 * 1024.0));
}

std::size_t LocalFrameRenderer::acquire_slot() {
  const bool pipelined = pool_->threads() > 0;
  for (;;) {
    std::optional<std::size_t> unallocated;
    {
      std::unique_lock lock(slot_mutex_);
      // A free slot that holds its buffer already; else one whose buffer is not allocated yet.
      for (std::size_t i = 0; i < slots_.size(); ++i) {
        if (slots_[i].busy) continue;
        if (!pipelined || slots_[i].buffer) {
          slots_[i].busy = true;
          return i;
        }
        if (!unallocated) unallocated = i;
      }
      if (unallocated) {
        slots_[*unallocated].busy = true;
      } else if (fenced_.empty()) {  // every slot is with the writers: wait for one
        slot_freed_.wait(
            lock, [&] { return std::any_of(slots_.begin(), slots_.end(), [](const Slot& s) { return !s.busy; }); });
        continue;
      }
    }
    if (unallocated) {
      const auto start = std::chrono::steady_clock::now();
      slots_[*unallocated].buffer = std::make_unique<render::display::ReadbackBuffer>(slot_bytes_);
      if (!started_) {
        startup_.buffers_s += seconds_since(start);
        startup_.buffer_bytes += slot_bytes_;
      }
      spdlog::debug("pipeline: readback slot {} allocated ({} of at most {})", *unallocated, allocated_slots(),
                    slots_.size());
      return *unallocated;
    }
    // The newest frame still waits for its fence: hand it over (its slot frees once written).
    hand_off(fenced_.front());
    fenced_.pop_front();
  }
}

render::display::OutputStage LocalFrameRenderer::output_stage(std::size_t o, const scene::FadeState& fade) const {
  const LocalOutput& out = outputs_[o];
  const OutputTextures& t = textures_[o];
  render::display::OutputStage stage;
  stage.tone = settings_.tone;
  stage.blended = out.blend.has_value();
  stage.blend_mask = out.blend ? &t.blend_mask : nullptr;
  stage.black_level = out.blend ? out.black_level : 0.0;
  stage.fade = {fade.level, {fade.colour.x, fade.colour.y, fade.colour.z}};
  stage.colour = t.colour.empty() ? nullptr : &t.colour;
  return stage;
}

void LocalFrameRenderer::warm_display_pass(render::gl::FirstDispatchWarmup& warmup) {
  for (std::size_t o = 0; o < outputs_.size(); ++o) {
    const OutputTextures& t = textures_[o];
    const render::display::OutputStage stage = output_stage(o, {});
    for (const Texture* display : {&t.display8, &t.display16}) {
      if (display->id() == 0) continue;
      if (t.radiance.id() != 0)
        encoder_.warm_encode(warmup, t.radiance, stage, *display);
      else
        encoder_.warm_band(warmup, stage, *display);
    }
  }
}

void LocalFrameRenderer::render_outputs(const scene::Scene& scene, const scene::FadeState& fade, Slot& slot) {
  render::Renderer& renderer = renderer_for(render_flags_);
  const auto note_startup = [&] {  // the first frame's share of tables and programs
    if (started_) return;
    const render::FrameStats& f = renderer.last_frame();
    startup_.tables_s += f.tables_s;
    startup_.table_sets += f.table_sets_uploaded;
    startup_.programs_s += f.programs_s;
    startup_.programs += f.programs_built;
    startup_.programs_from_binaries += f.programs_from_binaries;
    startup_.albedo_s += f.albedo_s;
  };
  for (std::size_t o = 0; o < outputs_.size(); ++o) {
    const LocalOutput& out = outputs_[o];
    OutputTextures& t = textures_[o];
    const Region& r = regions_[o];
    const render::display::OutputStage stage = output_stage(o, fade);
    if (t.radiance.id() != 0) {  // EXR wanted: the radiance texture, then the display pass from it
      renderer.render_to_texture(scene, *out.projection, t.radiance);
      note_startup();
      if (t.display8.id() != 0) encoder_.encode(t.radiance, stage, t.display8);
      if (t.display16.id() != 0) encoder_.encode(t.radiance, stage, t.display16);
    } else {  // display codes only: each band straight from the renderer's buffer
      renderer.render_on_gpu(scene, *out.projection, [&](const render::GpuBand& band) {
        if (t.display8.id() != 0) encoder_.encode_band(band, stage, t.display8);
        if (t.display16.id() != 0) encoder_.encode_band(band, stage, t.display16);
      });
      note_startup();
    }
    const auto read = [&](const Texture& texture, std::size_t offset) {
      if (texture.id() == 0) return;
      if (slot.buffer) {
        slot.buffer->queue_read(texture, offset);
      } else {
        std::vector<std::byte> pixels;
        render::display::read_texture_now(texture, pixels);
        std::memcpy(slot.memory.data() + offset, pixels.data(), pixels.size());
      }
    };
    read(t.radiance, r.radiance);
    read(t.display8, r.display8);
    read(t.display16, r.display16);
  }
}

FrameWriterPool::Frame LocalFrameRenderer::files_of(std::size_t index) {
  const std::uint64_t frame = slot_frames_[index].frame;
  const std::vector<std::vector<std::filesystem::path>>& files = slot_frames_[index].files;
  FrameWriterPool::Frame job;
  job.frame = frame;
  for (std::size_t o = 0; o < outputs_.size(); ++o)
    for (std::size_t k = 0; k < settings_.formats.size(); ++k) {
      const ImageFormat format = settings_.formats[k];
      job.files.push_back(
          {files[o][k], [this, index, o, format](const std::filesystem::path& staging) {
             const LocalOutput& out = outputs_[o];
             const Region& r = regions_[o];
             const std::span<const std::byte> bytes = slots_[index].bytes();
             const int w = out.projection->width(), h = out.projection->height();
             const std::size_t pixels = std::size_t(w) * std::size_t(h);
             const image::ImageAttributes& attributes = slot_frames_[index].attributes[o];
             switch (format) {
               case ImageFormat::png:
                 image::write_png_display(staging, w, h, 8, bytes.subspan(r.display8, pixels * 4),
                                          settings_.png_compression, attributes);
                 break;
               case ImageFormat::png16:
                 image::write_png_display(staging, w, h, 16, bytes.subspan(r.display16, pixels * 8),
                                          settings_.png_compression, attributes);
                 break;
               case ImageFormat::tiff:
                 image::write_tiff16_display(
                     staging, w, h, {reinterpret_cast<const std::uint16_t*>(bytes.data() + r.display16), pixels * 4},
                     settings_.tiff_compression, attributes);
                 break;
               case ImageFormat::exr:
                 write_exr_from_rgba(staging, w, h, reinterpret_cast<const float*>(bytes.data() + r.radiance),
                                     settings_.exr_type, out, attributes);
                 break;
             }
           }});
    }
  if (settings_.published)
    job.published = [this, index, frame] {
      const LocalOutput& out = outputs_[0];
      const Region& r = regions_[0];
      const bool eight = r.display8 != SIZE_MAX;
      const int w = out.projection->width(), h = out.projection->height();
      const std::size_t bytes = std::size_t(w) * std::size_t(h) * (eight ? 4 : 8);
      settings_.published(
          {frame, w, h, eight ? 8 : 16, slots_[index].bytes().subspan(eight ? r.display8 : r.display16, bytes)});
    };
  job.released = [this, index] {
    std::lock_guard lock(slot_mutex_);
    slots_[index].busy = false;
    slot_freed_.notify_all();
  };
  return job;
}

void LocalFrameRenderer::hand_off(std::size_t index) {
  Slot& slot = slots_[index];
  if (slot.buffer) slot.buffer->wait();
  pool_->submit(files_of(index));
}

void LocalFrameRenderer::submit_frame(const scene::FrameDescription& state,
                                      const std::vector<std::vector<std::filesystem::path>>& files) {
  if (files.size() != outputs_.size())
    throw std::invalid_argument(
        fmt::format("render_frame: files for {} outputs, the renderer has {}", files.size(), outputs_.size()));
  for (const auto& output_files : files)
    if (output_files.size() != settings_.formats.size())
      throw std::invalid_argument(fmt::format("render_frame: {} files an output, the pipeline writes {} formats",
                                              output_files.size(), settings_.formats.size()));
  const auto submit_start = std::chrono::steady_clock::now();
  if (!pool_) {
    start_pipeline();
    startup_.buffers_s += seconds_since(submit_start);
  }
  for (const auto& output_files : files)
    for (const std::filesystem::path& path : output_files)
      if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  scene::Scene scene = show_.scene();
  show::apply_state(state, versions_, scene);
  renderer_for(state.render_flags);
  const std::size_t index = acquire_slot();
  Slot& slot = slots_[index];
  try {
    if (!slot.buffer) slot.memory.resize(slot_bytes_);
    render_outputs(scene, state.fade, slot);
  } catch (...) {
    std::lock_guard lock(slot_mutex_);
    slot.busy = false;
    throw;
  }
  std::vector<image::ImageAttributes> attributes;
  for (const LocalOutput& out : outputs_) {
    image::ImageAttributes& a = attributes.emplace_back(image_attributes(scene, *out.projection));
    a.insert(a.end(), out.attributes.begin(), out.attributes.end());
    a.emplace_back("zenith:frame", fmt::format("{}", state.frame));
    a.emplace_back("zenith:show_time_s", fmt::format("{}", state.show_time_s));
    if (state.fade.level > 0.0)  // EXR keeps the radiance: the fade is named, applied to the display codes only
      a.emplace_back("zenith:fade", fmt::format("level {} colour {} {} {}", state.fade.level, state.fade.colour.x,
                                                state.fade.colour.y, state.fade.colour.z));
  }
  SlotFrame& sf = slot_frames_[index];
  sf.frame = state.frame;
  sf.files = files;
  sf.attributes = std::move(attributes);
  if (!started_) log_startup(seconds_since(submit_start));
  if (!slot.buffer) {  // the simple path: written before returning
    hand_off(index);
    return;
  }
  slot.buffer->fence();
  fenced_.push_back(index);
  // Keep the newest frame on the GPU; the older ones go to the writers as their fences signal.
  while (fenced_.size() > 1) {
    const std::size_t oldest = fenced_.front();
    fenced_.pop_front();
    hand_off(oldest);
  }
}

void LocalFrameRenderer::log_startup(double submit_s) {
  started_ = true;
  startup_.first_frame_s =
      std::max(0.0, submit_s - startup_.tables_s - startup_.programs_s - startup_.albedo_s - startup_.buffers_s);
  startup_.total_s = seconds_since(created_);
  spdlog::info("{}", describe(startup_));
  if (renderer_) spdlog::info("renderer's programs: {}", renderer_->program_builds_summary());
}

std::vector<FinishedFrame> LocalFrameRenderer::take_finished() {
  std::vector<FinishedFrame> result;
  if (!pool_) return result;
  for (WrittenFrame& w : pool_->take_written()) result.push_back({w.frame, std::move(w.file_sha256)});
  return result;
}

void LocalFrameRenderer::finish_frames() {
  if (!pool_) return;
  context_.make_current();
  while (!fenced_.empty()) {
    const std::size_t oldest = fenced_.front();
    fenced_.pop_front();
    hand_off(oldest);
  }
  pool_->finish();
  spdlog::info("pipeline: {} of at most {} readback slots allocated ({:.1f} MiB)", allocated_slots(), slots_.size(),
               static_cast<double>(allocated_slots() * slot_bytes_) / (1024.0 * 1024.0));
}

void LocalFrameRenderer::render_frame(const scene::FrameDescription& state,
                                      const std::vector<std::vector<std::filesystem::path>>& files) {
  submit_frame(state, files);
  finish_frames();
}

}  // namespace zenith::app::offline
