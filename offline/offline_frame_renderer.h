#pragma once
// The single-process FrameRenderer of `zenith show render`: one headless GL
// context and renderer in this process render every output of each frame
// (projection, warp, blend mask and black level), as a pipeline (docs/shows.md,
// "The pipeline"):
//
//   GL thread   frame N+1: render → display pass (tone mapping, output stage,
//               sRGB, 8/16-bit codes) → queue the readback into a pixel buffer,
//               fence   while   frame N: wait its fence, hand its pixels over
//   workers     encode and write frame N's files (PNG, TIFF, EXR), hash them
//   in order    rename them into place, feed the video proxy, report the frame
//
// Frames in flight hold one readback slot each (at most frames_in_flight
// slots, the bytes of every file's pixels: e.g. 256 MiB for an 8192² 8-bit
// frame), so the memory stays bounded whatever the length of the show. A
// slot's buffer is allocated when a frame first needs it and no allocated
// slot is free: the pipeline holds as many as its writers keep busy, not the
// most it may. threads = 0 is the simple path: read back at once, encode and
// write on this thread, one frame at a time; it writes the same bytes.
//
// The start (docs/shows.md, "Where the start goes") is logged at
// info level once the first frame is on its way: the GL context, tables
// precomputed, tables loaded and uploaded (the first frame's sets read from
// the cache on threads of their own, together), programs built (all of a
// frame's started together: render/gl/program_builds.h), buffers, the first
// frame's own rendering.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "image/colour.h"
#include "image/display_image_writer.h"
#include "offline/frame_writer_pool.h"
#include "offline/offline_render.h"
#include "offline/output_rendering.h"
#include "render/display/display_encoder.h"
#include "render/display/frame_readback.h"
#include "render/gl/egl_context.h"
#include "render/lut/table_provider.h"
#include "render/renderer.h"
#include "show/show.h"
#include "show/table_plan.h"
#include "warp/blending.h"

namespace zenith::app::offline {

/// An output as this process renders it.
struct LocalOutput {
  std::shared_ptr<const warp::Projection> projection;
  std::optional<warp::BlendMask> blend;  ///< viewport outputs
  double black_level = 0.0;              ///< with a blend
  image::ImageAttributes attributes;     ///< besides the scene's (e.g. zenith:viewport, zenith:blend)
  /// An MPCDI region's colour profile (warp/colour_profile.h): the display
  /// codes go through it; null: none. EXR keeps the radiance.
  std::shared_ptr<const warp::MpcdiColourProfile> colour;
};

/// A frame's display codes as published (the first output's), for a video proxy.
struct DisplayFrame {
  std::uint64_t frame = 0;
  int width_px = 0, height_px = 0, bits = 8;
  std::span<const std::byte> rgba;  ///< width · height · 4 samples, rows top first, native byte order
};

/// How frames become files.
struct PipelineSettings {
  std::vector<ImageFormat> formats = {ImageFormat::png};  ///< the order of each output's files
  image::ToneMapping tone = image::ToneMapping::exponential;
  image::ExrPixelType exr_type = image::ExrPixelType::half;
  int png_compression = image::kFastPngCompression;
  image::TiffCompression tiff_compression = image::TiffCompression::deflate;
  /// Encoding and writing threads: ≥ 1, 0 the simple path, −1 automatic
  /// (default_writer_threads of the GL device).
  int threads = -1;
  /// Frames whose pixels may be held at once (readback slots), ≥ 1; 0: threads + 2, at most as many as fit
  /// in 8 GiB (at least 2): 8192² 8-bit PNG 256 MiB a frame, 16-bit TIFF 512 MiB, EXR 1 GiB more.
  int frames_in_flight = 0;
  /// Called in frame order as each frame's files are in place (from a worker
  /// thread; keep it short): the video proxy. Needs a display format.
  std::function<void(const DisplayFrame&)> published;
  /// The renderer's programs one at a time, each where first used
  /// (RenderOptions::serial_compile; `--serial-compile`), to compare.
  bool serial_compile = false;
};

/// Where the start of a render went, up to the first frame on its way to the
/// writers (seconds of this process's GL thread).
struct StartupTimes {
  double context_s = 0.0;     ///< the GL context
  double precompute_s = 0.0;  ///< table sets not in the cache, precomputed and stored
  double tables_s = 0.0;      ///< the first frame's table sets: waiting for their loads, uploading
  int table_sets = 0;
  double programs_s = 0.0;  ///< building the first frame's programs (waiting for the driver included)
  int programs = 0;
  int programs_from_binaries = 0;  ///< of those, made from a stored binary (render/gl/program_binary_cache.h)
  double albedo_s = 0.0;           ///< the bodies' albedo maps: read from the cache or generated, and uploaded
  double buffers_s = 0.0;          ///< output textures, writer threads, the first readback slot
  std::size_t buffer_bytes = 0;
  double first_frame_s = 0.0;  ///< the first frame's submit, less its tables, programs and buffers
  double total_s = 0.0;        ///< from the renderer's construction to the first frame submitted
};
/// "start-up 5.31 s: GL context 0.04 s, tables precomputed 0.00 s, tables loaded 1.80 s (3 sets), …".
std::string describe(const StartupTimes& t);

/// Whether a GL renderer string names a CPU rasterizer (llvmpipe, softpipe, SwiftShader).
bool is_software_renderer(const std::string& device);
/// Writer threads for a machine of `cpus` CPUs: all of them on a GPU; on a CPU
/// rasterizer the CPUs it leaves (it runs a thread per CPU or more while a
/// frame renders, docs/rendering-performance.md), at least 1.
int default_writer_threads(unsigned cpus, bool software_renderer);

class LocalFrameRenderer final : public FrameRenderer {
 public:
  /// `versions`: every atmosphere version the frames use, by table hash.
  LocalFrameRenderer(const show::Show& show, std::map<scene::TableHash, show::AtmosphereVersion> versions,
                     std::vector<LocalOutput> outputs, PipelineSettings settings, image::ColourMapping colour,
                     render::TableRequest tables, const render::gl::ContextOptions& context);
  ~LocalFrameRenderer() override;

  /// The GL renderer's name ("llvmpipe (LLVM 15.0.7, 256 bits)", ...).
  const std::string& device() const { return context_.renderer(); }
  /// The writer threads and readback slots in use (settled by the first frame: −1/0 resolved).
  int threads() const;
  int frames_in_flight() const;
  int allocated_slots() const;
  /// Obtains every set of `plan` among `table_hashes` that is not cached yet
  /// (precomputed and stored in the cache), with a line per set, then starts
  /// loading the sets first used earliest (the first frame's) from the cache,
  /// each on a thread of its own; the renderer takes those when the first
  /// frame needs them and loads any other when a frame first needs it.
  void precompute_missing(const show::TablePlan& plan, const std::set<scene::TableHash>& table_hashes);

  /// submit_frame and finish_frames: the frame's files are complete on return.
  void render_frame(const scene::FrameDescription& state,
                    const std::vector<std::vector<std::filesystem::path>>& files) override;
  void submit_frame(const scene::FrameDescription& state,
                    const std::vector<std::vector<std::filesystem::path>>& files) override;
  std::vector<FinishedFrame> take_finished() override;
  void finish_frames() override;

 private:
  /// Where a slot holds one output's pixels (SIZE_MAX: not read back).
  struct Region {
    std::size_t display8 = SIZE_MAX, display16 = SIZE_MAX, radiance = SIZE_MAX;
  };
  struct Slot {
    std::unique_ptr<render::display::ReadbackBuffer> buffer;  ///< the pipeline's
    std::vector<std::byte> memory;                            ///< the simple path's
    bool busy = false;
    std::span<const std::byte> bytes() const;
  };
  /// An output's textures on the GPU.
  struct OutputTextures {
    render::gl::Texture radiance, display8, display16, blend_mask;
    render::display::ColourProfileTextures colour;  ///< the output's LUTs, uploaded once
  };

  render::Renderer& renderer_for(std::uint32_t render_flags);
  /// The renderer's TableSource: a set loading ahead (precompute_missing), else obtained now.
  atmosphere::lut::LookupTables tables_for(const atmosphere::AtmosphereModel& model);
  /// The renderer's AlbedoMapSource: a map loading ahead (precompute_missing), else loaded now.
  image::LinearImage albedo_for(const scene::AlbedoSource& source);
  void start_pipeline();       // the first frame: threads, slots, regions
  std::size_t acquire_slot();  // a free slot (allocated when none allocated is free); waits for one
  void log_startup(double submit_s);
  void hand_off(std::size_t slot);  // waits its fence, queues its files
  /// Every output of one frame into its slot; `fade` on the display codes (EXR keeps the radiance).
  void render_outputs(const scene::Scene& scene, const scene::FadeState& fade, Slot& slot);
  /// Output `o`'s display pass at `fade`.
  render::display::OutputStage output_stage(std::size_t o, const scene::FadeState& fade) const;
  /// Queues every output's display pass on the renderer's warm-up thread
  /// (Renderer::set_band_sink_warmup): its first draw's code generated there.
  void warm_display_pass(render::gl::FirstDispatchWarmup& warmup);
  /// The pool's work for the frame in `slot` (slot_frames_): a task per file, the video, the slot's release.
  FrameWriterPool::Frame files_of(std::size_t slot);

  const std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();
  const show::Show& show_;
  std::map<scene::TableHash, show::AtmosphereVersion> versions_;
  std::vector<LocalOutput> outputs_;
  PipelineSettings settings_;
  image::ColourMapping colour_;
  render::TableRequest tables_;
  render::gl::HeadlessContext context_;
  std::unique_ptr<render::Renderer> renderer_;  ///< for render_flags_
  std::uint32_t render_flags_ = 0;
  render::display::DisplayEncoder encoder_;
  std::vector<OutputTextures> textures_;
  std::vector<Region> regions_;
  std::size_t slot_bytes_ = 0;
  /// Table sets being read from the cache ahead of the first frame, by atmosphere::lookup_table_hash.
  std::map<std::string, std::future<render::ObtainedTables>> loading_;
  /// The show's albedo maps read from their cache (or generated) beside them, by scene::albedo_key.
  std::map<std::string, std::future<image::LinearImage>> albedo_loading_;
  StartupTimes startup_;
  bool started_ = false;  ///< the first frame was submitted

  std::mutex slot_mutex_;
  std::condition_variable slot_freed_;
  std::vector<Slot> slots_;
  std::deque<std::size_t> fenced_;  ///< slots rendered and fenced, not yet handed to the pool
  /// The files of each slot's frame, by slot (the state the pool's tasks read).
  struct SlotFrame {
    std::uint64_t frame = 0;
    std::vector<std::vector<std::filesystem::path>> files;
    std::vector<image::ImageAttributes> attributes;
  };
  std::vector<SlotFrame> slot_frames_;
  /// Frames handed to the pool wait here for their files (declared last: destroyed first).
  std::unique_ptr<FrameWriterPool> pool_;
};

}  // namespace zenith::app::offline
