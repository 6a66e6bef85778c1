#pragma once
// Data the CPU hands to GPU commands it has issued but the GPU may not have
// run yet — a band's tile lists, black-tile flags and star lists — written so
// that no upload ever rewrites bytes a queued command still reads.
//
// Each upload takes bytes of its own in a chunk (a shader storage buffer),
// bound as a range at its offset; end_frame() lays a fence after the frame's
// commands, and a chunk is filled again only once the fence laid after its
// last frame has signalled. Nothing waits while a chunk is free; with none
// free (the GPU more than a few frames behind) a new one is made, up to
// kMaxChunks, past which the oldest fence is waited for.
//
// Why not one buffer per kind rewritten band after band (glNamedBufferSubData
// over the bytes the previous band's commands read): that leaves the wait for
// those reads to the driver. On NVIDIA (H200, driver 580) a frame drawn band
// by band on the GPU, the CPU never waiting, lit pixels the read-back frame
// did not, while the read-back path (whose CPU waits for every band), one
// band, and a glFinish after every pass all agreed (docs/night-sky.md, "Seen
// on NVIDIA"): the signature of an upload landing before the reads it should
// have waited for.
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

#include "render/gl/buffer.h"
#include "render/gl/fence.h"

namespace zenith::render::gl {

/// Bytes of an UploadStream chunk: what a shader reads at a binding.
struct UploadRange {
  unsigned buffer = 0;
  std::size_t offset_bytes = 0, size_bytes = 0;
  /// Binds the range to `layout(binding = N) buffer` (GL_SHADER_STORAGE_BUFFER).
  void bind_storage(unsigned binding) const;
};

class UploadStream {
 public:
  /// Chunks of at least `chunk_bytes` (> 0) each. Needs a current GL 4.5 context.
  explicit UploadStream(std::size_t chunk_bytes = std::size_t{4} << 20);
  UploadStream(const UploadStream&) = delete;
  UploadStream& operator=(const UploadStream&) = delete;

  /// A copy of `data` in bytes no queued command reads. Empty data gives a
  /// range of one word (a storage binding's size must be positive), unread.
  UploadRange upload(std::span<const std::byte> data);
  template <class T>
  requires std::is_trivially_copyable_v<T> UploadRange upload(std::span<const T> data) {
    return upload(std::as_bytes(data));
  }

  /// After the frame's last command that reads its uploads: a fence, after
  /// which the chunks the frame filled are free again.
  void end_frame();

  /// Chunks made so far (a bound on the memory the stream holds: chunk size × this).
  std::size_t chunks() const { return chunks_.size(); }

  /// Past this many chunks the stream waits for the oldest fence instead of
  /// making another.
  static constexpr std::size_t kMaxChunks = 16;

 private:
  struct Chunk {
    Buffer buffer;
    std::size_t used_bytes = 0;
    bool in_frame = false;             // filled by the frame in progress
    Fence fence;                       // laid after its last frame; empty: free
    unsigned long long fenced_at = 0;  // end_frame count when fenced: the oldest is waited for first
  };
  /// A chunk of the frame in progress with `bytes` free after alignment.
  Chunk& chunk_with_room(std::size_t bytes);

  std::size_t chunk_bytes_;
  std::size_t alignment_ = 256;  // GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, at least 16
  std::vector<Chunk> chunks_;
  std::size_t current_ = 0;  // the chunk being filled, if in_frame
  unsigned long long frames_ = 0;
};

}  // namespace zenith::render::gl
