#pragma once
// Reading finished frames back without stalling the renderer (docs/shows.md,
// "The pipeline"): a display texture (rgba8 / rgba16 codes of the display
// pass) or a radiance texture (rgba32f) is copied into a pixel buffer object —
// the copy is queued like any GL command — and a fence marks its end; the CPU
// waits on the fence only when it needs the pixels, by which time the GPU has
// usually moved on to the next frame. The buffer is mapped once, persistently
// and coherently, so the pixels are read where the GPU put them (no copy out).
//
// Texel (x, y) lands at byte ((y · width) + x) · bytes_per_texel: rows top
// first for the renderer's textures (render_to_texture, the display pass), four
// samples a texel in this machine's byte order. Needs a current GL 4.5 context
// (ARB_buffer_storage is core there).
#include <cstddef>
#include <span>
#include <vector>

#include "render/gl/fence.h"
#include "render/gl/texture.h"

namespace zenith::render::display {

/// Bytes a texel of `texture` takes when read back: 4 (rgba8), 8 (rgba16), 16 (rgba32f).
/// Throws std::invalid_argument for the other formats.
std::size_t readback_texel_bytes(const gl::Texture& texture);
/// width · height · readback_texel_bytes.
std::size_t readback_bytes(const gl::Texture& texture);

class ReadbackBuffer {
 public:
  /// A persistently mapped buffer of `bytes` (> 0); throws std::runtime_error when GL refuses it.
  explicit ReadbackBuffer(std::size_t bytes);
  ~ReadbackBuffer();
  ReadbackBuffer(const ReadbackBuffer&) = delete;
  ReadbackBuffer& operator=(const ReadbackBuffer&) = delete;

  std::size_t size() const { return bytes_; }
  /// Queues the copy of `texture` (rgba8, rgba16 or rgba32f, 2D) to bytes
  /// [offset, offset + readback_bytes(texture)); throws std::invalid_argument
  /// when it does not fit. The pixels are not valid until wait().
  void queue_read(const gl::Texture& texture, std::size_t offset);
  /// A fence after every queued read, and a flush so that the GPU starts on them.
  void fence();
  /// Blocks until the fenced reads are complete (the fence signalled), then
  /// forgets the fence. Without a fence, returns at once.
  void wait();
  /// The mapped bytes: valid after wait(), until the next queue_read.
  std::span<const std::byte> bytes() const { return {mapped_, bytes_}; }

 private:
  unsigned buffer_ = 0;
  std::byte* mapped_ = nullptr;
  std::size_t bytes_ = 0;
  gl::Fence fence_;
};

/// Reads `texture` into `out` (resized to readback_bytes) at once, without a
/// pixel buffer: the simple path's readback, blocking until the GPU is done.
void read_texture_now(const gl::Texture& texture, std::vector<std::byte>& out);

}  // namespace zenith::render::display
