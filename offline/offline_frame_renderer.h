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
// Frames in flight hold one readback slot each (frames_in_flight slots, the
// bytes of every file's pixels: e.g. 256 MiB for an 8192² 8-bit frame), so the
// memory stays bounded whatever the length of the show. threads = 0 is the
// simple path: read back at once, encode and write on this thread, one frame
// at a time; it writes the same bytes.
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
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
};

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
  /// Bytes one readback slot holds (every output's pixels of one frame): the
  /// pipeline holds frames_in_flight() of them.
  std::size_t slot_bytes() const;
  /// Obtains every set of `plan` among `table_hashes` that is not cached yet
  /// (precomputed and stored in the cache), with a line per set; the renderer
  /// then loads each from the cache when a frame first needs it.
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
  void start_pipeline();            // the first frame: threads, slots, regions
  std::size_t acquire_slot();       // waits until the next slot is free
  void hand_off(std::size_t slot);  // waits its fence, queues its files
  /// Every output of one frame into its slot; `fade` on the display codes (EXR keeps the radiance).
  void render_outputs(const scene::Scene& scene, const scene::FadeState& fade, Slot& slot);
  /// The pool's work for the frame in `slot` (slot_frames_): a task per file, the video, the slot's release.
  FrameWriterPool::Frame files_of(std::size_t slot);

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

  std::mutex slot_mutex_;
  std::condition_variable slot_freed_;
  std::vector<Slot> slots_;
  std::deque<std::size_t> fenced_;  ///< slots rendered and fenced, not yet handed to the pool
  std::size_t next_slot_ = 0;
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
