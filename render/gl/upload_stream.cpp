#include "render/gl/upload_stream.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "render/gl/gl_error.h"

namespace zenith::render::gl {

namespace {
std::size_t round_up(std::size_t n, std::size_t step) { return (n + step - 1) / step * step; }
}  // namespace

void UploadRange::bind_storage(unsigned binding) const {
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, buffer, static_cast<GLintptr>(offset_bytes),
                    static_cast<GLsizeiptr>(size_bytes));
}

UploadStream::UploadStream(std::size_t chunk_bytes) : chunk_bytes_(chunk_bytes) {
  if (chunk_bytes == 0) throw std::invalid_argument("UploadStream: chunk size must be positive");
  GLint alignment = 0;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  check_gl_error("UploadStream: GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT");
  alignment_ = std::max<std::size_t>(16, static_cast<std::size_t>(std::max(alignment, 1)));
}

UploadStream::Chunk& UploadStream::chunk_with_room(std::size_t bytes) {
  if (current_ < chunks_.size()) {
    Chunk& c = chunks_[current_];
    if (c.in_frame && round_up(c.used_bytes, alignment_) + bytes <= c.buffer.size()) return c;
  }
  const auto take = [&](std::size_t i) -> Chunk& {
    current_ = i;
    chunks_[i].used_bytes = 0;
    chunks_[i].in_frame = true;
    return chunks_[i];
  };
  for (std::size_t i = 0; i < chunks_.size(); ++i)
    if (!chunks_[i].in_frame && chunks_[i].buffer.size() >= bytes && chunks_[i].fence.signalled()) return take(i);
  // None free: wait for the oldest fence that frees a chunk large enough, once the stream holds as many
  // chunks as it may; else a new chunk.
  std::size_t oldest = chunks_.size();
  for (std::size_t i = 0; i < chunks_.size(); ++i)
    if (!chunks_[i].in_frame && chunks_[i].buffer.size() >= bytes &&
        (oldest == chunks_.size() || chunks_[i].fenced_at < chunks_[oldest].fenced_at))
      oldest = i;
  if (chunks_.size() >= kMaxChunks && oldest < chunks_.size()) {
    chunks_[oldest].fence.wait("an upload stream's oldest chunk");
    return take(oldest);
  }
  chunks_.emplace_back().buffer = Buffer(std::max(chunk_bytes_, bytes));
  return take(chunks_.size() - 1);
}

UploadRange UploadStream::upload(std::span<const std::byte> data) {
  const std::size_t bytes = data.empty() ? sizeof(std::uint32_t) : data.size();
  Chunk& c = chunk_with_room(bytes);
  const std::size_t offset = round_up(c.used_bytes, alignment_);
  if (!data.empty()) c.buffer.upload(data, offset);
  c.used_bytes = offset + bytes;
  return {c.buffer.id(), offset, bytes};
}

void UploadStream::end_frame() {
  for (Chunk& c : chunks_) {
    if (!c.in_frame) continue;
    c.fence = Fence::after_issued_commands();
    c.in_frame = false;
    c.fenced_at = frames_;
  }
  ++frames_;
}

}  // namespace zenith::render::gl
