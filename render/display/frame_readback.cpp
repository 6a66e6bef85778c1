#include "render/display/frame_readback.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <limits>
#include <stdexcept>

#include "render/gl/gl_error.h"

namespace zenith::render::display {
namespace {

using gl::TextureFormat;

/// The client format and type a texture is read back as.
std::pair<GLenum, GLenum> pack_format(const gl::Texture& texture) {
  if (texture.is_3d()) throw std::invalid_argument("readback: a 3D texture");
  switch (texture.format()) {
    case TextureFormat::rgba8: return {GL_RGBA, GL_UNSIGNED_BYTE};
    case TextureFormat::rgba16: return {GL_RGBA, GL_UNSIGNED_SHORT};
    case TextureFormat::rgba32f: return {GL_RGBA, GL_FLOAT};
    default: break;
  }
  throw std::invalid_argument(fmt::format("readback: a {} texture; frames are read back from rgba8, rgba16 or rgba32f",
                                          gl::to_string(texture.format())));
}

GLsizei gl_size(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()))
    throw std::invalid_argument(fmt::format("readback: {} bytes exceed what one GL read can take", bytes));
  return static_cast<GLsizei>(bytes);
}

}  // namespace

std::size_t readback_texel_bytes(const gl::Texture& texture) {
  const GLenum type = pack_format(texture).second;
  return type == GL_UNSIGNED_BYTE ? 4 : type == GL_UNSIGNED_SHORT ? 8 : 16;
}

std::size_t readback_bytes(const gl::Texture& texture) {
  return readback_texel_bytes(texture) * static_cast<std::size_t>(texture.width()) *
         static_cast<std::size_t>(texture.height());
}

ReadbackBuffer::ReadbackBuffer(std::size_t bytes) : bytes_(bytes) {
  if (bytes == 0) throw std::invalid_argument("readback buffer of 0 bytes");
  glCreateBuffers(1, &buffer_);
  const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glNamedBufferStorage(buffer_, static_cast<GLsizeiptr>(bytes), nullptr, flags);
  mapped_ = static_cast<std::byte*>(glMapNamedBufferRange(buffer_, 0, static_cast<GLsizeiptr>(bytes), flags));
  if (mapped_ == nullptr) {
    const GLenum error = glGetError();
    glDeleteBuffers(1, &buffer_);
    throw std::runtime_error(
        fmt::format("readback: cannot map a pixel buffer of {} MiB (GL error 0x{:x})", bytes >> 20, error));
  }
}

ReadbackBuffer::~ReadbackBuffer() {
  if (buffer_ != 0) {
    glUnmapNamedBuffer(buffer_);
    glDeleteBuffers(1, &buffer_);
  }
}

void ReadbackBuffer::queue_read(const gl::Texture& texture, std::size_t offset) {
  const auto [format, type] = pack_format(texture);
  const std::size_t bytes = readback_bytes(texture);
  if (offset > bytes_ || bytes > bytes_ - offset)
    throw std::invalid_argument(
        fmt::format("readback: {} bytes at offset {} do not fit a buffer of {}", bytes, offset, bytes_));
  // Image stores of compute passes must land before the copy reads the texture.
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture.id(), 0, format, type, gl_size(bytes),
                    reinterpret_cast<void*>(static_cast<std::uintptr_t>(offset)));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  gl::check_gl_error("readback into a pixel buffer");
}

void ReadbackBuffer::fence() {
  fence_ = gl::Fence::after_issued_commands();
  glFlush();
}

void ReadbackBuffer::wait() { fence_.wait("readback"); }

void read_texture_now(const gl::Texture& texture, std::vector<std::byte>& out) {
  const auto [format, type] = pack_format(texture);
  out.resize(readback_bytes(texture));
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture.id(), 0, format, type, gl_size(out.size()), out.data());
  gl::check_gl_error("readback");
}

}  // namespace zenith::render::display
