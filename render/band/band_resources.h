#pragma once
// The GPU memory the renderer draws a frame's bands with, kept from frame to
// frame and (re)allocated only when a size changes: the bodies buffer, the
// band's tile lists, its output buffer (one vec4 per pixel, frame_rgb.glsl),
// the G-buffer path's four images, a ray-table projection's rays, and the
// black-tile flags of a band read on the GPU. Each is bound at the binding
// render/shader_bindings.h gives it. What the CPU writes for a band's
// commands (the tile lists, the black-tile flags) goes through an upload
// stream (render/gl/upload_stream.h): no band rewrites bytes an earlier
// band's commands, perhaps not yet run, read.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "render/band/gpu_band.h"
#include "render/frame/gpu_body.h"
#include "render/frame/pass_timer.h"
#include "render/frame/tile_classification.h"
#include "render/frame/tile_culling.h"
#include "render/gl/buffer.h"
#include "render/gl/first_dispatch_warmup.h"
#include "render/gl/texture.h"
#include "render/gl/upload_stream.h"
#include "warp/projection.h"

namespace zenith::render {

/// Who reads a band's output buffer once its passes are done: the CPU
/// (read_back: a mappable buffer, which NVIDIA's driver moves into the host's
/// memory once mapped, every later store then crossing the bus) or a pass on
/// the GPU (bind_band_on_gpu: a buffer never mapped, kept in the GPU's memory).
/// A renderer that does both (a live benchmark's read-back and live frames)
/// keeps one of each.
enum class BandReader { cpu, gpu };

class BandResources {
 public:
  /// The frame's bodies into the bodies buffer (one zero body where there are none).
  void upload_bodies(std::span<const GpuBody> bodies);
  /// The frame's air shadows (render/frame/air_shadows.h's air_shadow_buffer), bound with the bodies.
  void upload_air_shadows(std::span<const std::array<float, 4>> values);
  void bind_bodies() const;

  /// Sizes the band's output for bands of `width` × `height` pixels read by
  /// `reader`: that reader's output buffer allocated where it is not, every
  /// buffer and image dropped when the size changes.
  void fit_bands(int width, int height, BandReader reader);
  int band_height() const { return band_height_; }
  /// Tiles across a band (the last one partial where the width is not a multiple of kTileSize).
  int tile_columns() const { return (band_width_ + kTileSize - 1) / kTileSize; }
  /// Zeroes the output of a band of `rows` rows (the tiles no pass will write).
  void clear_output(int rows);

  /// The band's tile lists into the upload stream; binds them and the output buffer.
  void upload_tile_lists(const BandTiles& band);
  void bind_tiles() const;

  /// Where the frame's passes put what the CPU hands a band's commands
  /// (made on first use: it needs the GL context).
  gl::UploadStream& uploads();
  /// After the frame's last band: its uploads' bytes are reused once the GPU has run it.
  void end_frame();

  /// The G-buffer path's images, allocated on first use (224 MiB of GPU
  /// memory for an 8192-pixel band of 512 rows): bound for gbuffer.comp to
  /// write, or for the atmosphere passes and resolve.comp to read (hit,
  /// albedo) and accumulate (radiance, transmittance).
  void bind_gbuffer_for_the_body_pass();
  void bind_gbuffer_for_the_atmosphere_passes();
  /// The shapes of the G-buffer images and the ray table for bands of
  /// `width` × `rows` (fit_bands' size), into `shapes`
  /// (render/gl/first_dispatch_warmup.h): before the first band allocates them.
  static void add_dispatch_shapes(gl::DispatchShapes& shapes, int width, int rows);

  /// The rays of `projection` (one without a GPU form) for the band of `rows`
  /// rows from `first_row`, bound as projection.glsl's ray table: computed on
  /// the CPU in double and uploaded once per band, then kept on the GPU until
  /// forget_rays() (a new projection) or a new band size.
  void upload_rays(const warp::Projection& projection, int first_row, int rows);
  void forget_rays() { ray_tables_.clear(); }

  /// The band's rows as RGB floats (render/band/band_readback.h), read from
  /// the output buffer; valid until the next band. "readback" in `timer`.
  std::span<const float> read_back(const BandTiles& band, PassTimer& timer);
  /// Binds the output buffer and uploads and binds the band's black-tile
  /// flags, for a pass that reads the band on the GPU (render/band/gpu_band.h).
  GpuBand bind_band_on_gpu(const BandTiles& band);
  /// After the pass that read the band on the GPU: a memory barrier, since
  /// the next band's passes and clear rewrite the output buffer and the
  /// black-tile flags that pass reads, and shader accesses to buffers are
  /// unordered across commands without one, reads before later writes too
  /// (glMemoryBarrier finishes the accesses issued before it). It did not
  /// change the H200's six stray star pixels of the texture path, nor did a
  /// fence there: the lists a band uploads now go through the upload stream
  /// (docs/night-sky.md, "Seen on NVIDIA").
  void end_band_on_gpu();

 private:
  gl::Buffer bodies_;
  gl::Buffer air_shadows_;
  std::optional<gl::UploadStream> uploads_;
  gl::UploadRange tiles_;  // the band's tile lists
  int band_width_ = 0, band_height_ = 0;
  BandReader reader_ = BandReader::cpu;
  gl::Buffer read_on_cpu_, read_on_gpu_;  // the band's output, by its reader
  gl::Buffer& output() { return reader_ == BandReader::cpu ? read_on_cpu_ : read_on_gpu_; }
  gl::Texture gbuffer_hit_, gbuffer_albedo_, radiance_sum_, transmittance_;
  std::map<int, gl::Texture> ray_tables_;  // by the band's first row
  // The rows of a band read back, kept from frame to frame: a new 50 MB vector
  // per frame (a 3840-pixel band) costs its page faults every frame.
  std::vector<float> rows_rgb_;
};

}  // namespace zenith::render
