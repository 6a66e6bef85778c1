#include "render/gl/buffer.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "render/gl/gl_error.h"

namespace zenith::render::gl {

Buffer::Buffer(std::size_t size_bytes) { create(size_bytes, nullptr, GL_DYNAMIC_STORAGE_BIT); }

Buffer::Buffer(std::span<const std::byte> data) { create(data.size(), data.data(), GL_DYNAMIC_STORAGE_BIT); }

Buffer Buffer::mappable(std::size_t size_bytes) {
  Buffer b;
  b.create(size_bytes, nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
  return b;
}

void Buffer::create(std::size_t size_bytes, const void* data, unsigned flags) {
  if (size_bytes == 0) throw std::invalid_argument("Buffer: size must be positive");
  check_gl_error("Buffer: an earlier GL call left an error");
  glCreateBuffers(1, &id_);
  size_ = size_bytes;
  glNamedBufferStorage(id_, static_cast<GLsizeiptr>(size_bytes), data, flags);
  if (data == nullptr) glClearNamedBufferData(id_, GL_R8, GL_RED, GL_UNSIGNED_BYTE, nullptr);  // zero-fill
  try {
    check_gl_error(fmt::format("Buffer: storage of {} bytes", size_bytes));
  } catch (...) {
    release();
    throw;
  }
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept : id_(std::exchange(other.id_, 0u)), size_(std::exchange(other.size_, 0u)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    id_ = std::exchange(other.id_, 0u);
    size_ = std::exchange(other.size_, 0u);
  }
  return *this;
}

void Buffer::release() noexcept {
  if (id_ != 0) glDeleteBuffers(1, &id_);
  id_ = 0;
  size_ = 0;
}

void Buffer::upload(std::span<const std::byte> data, std::size_t offset_bytes) {
  if (id_ == 0) throw std::logic_error("Buffer::upload on an empty buffer");
  if (offset_bytes > size_ || data.size() > size_ - offset_bytes)
    throw std::out_of_range(fmt::format("Buffer::upload: {} bytes at offset {} past the end of a {}-byte buffer",
                                        data.size(), offset_bytes, size_));
  if (data.empty()) return;
  glNamedBufferSubData(id_, static_cast<GLintptr>(offset_bytes), static_cast<GLsizeiptr>(data.size()), data.data());
  check_gl_error("Buffer::upload");
}

void Buffer::clear_to_zero(std::size_t offset_bytes, std::size_t size_bytes) {
  if (id_ == 0) throw std::logic_error("Buffer::clear_to_zero on an empty buffer");
  if (offset_bytes > size_ || size_bytes > size_ - offset_bytes)
    throw std::out_of_range(fmt::format("Buffer::clear_to_zero: {} bytes at offset {} past the end of a {}-byte buffer",
                                        size_bytes, offset_bytes, size_));
  if (size_bytes == 0) return;
  glClearNamedBufferSubData(id_, GL_R32UI, static_cast<GLintptr>(offset_bytes), static_cast<GLsizeiptr>(size_bytes),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  check_gl_error("Buffer::clear_to_zero");
}

std::vector<std::byte> Buffer::read_bytes(std::size_t offset_bytes, std::size_t size_bytes) const {
  if (id_ == 0) throw std::logic_error("Buffer::read_bytes on an empty buffer");
  if (offset_bytes > size_ || size_bytes > size_ - offset_bytes)
    throw std::out_of_range(fmt::format("Buffer::read_bytes: {} bytes at offset {} past the end of a {}-byte buffer",
                                        size_bytes, offset_bytes, size_));
  std::vector<std::byte> out(size_bytes);
  if (size_bytes == 0) return out;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(id_, static_cast<GLintptr>(offset_bytes), static_cast<GLsizeiptr>(size_bytes), out.data());
  check_gl_error("Buffer::read_bytes");
  return out;
}

std::span<const std::byte> Buffer::map_read(std::size_t size_bytes) const {
  if (id_ == 0) throw std::logic_error("Buffer::read_mapped on an empty buffer");
  if (size_bytes == 0 || size_bytes > size_)
    throw std::out_of_range(fmt::format("Buffer::read_mapped: {} bytes from a {}-byte buffer", size_bytes, size_));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const void* p = glMapNamedBufferRange(id_, 0, static_cast<GLsizeiptr>(size_bytes), GL_MAP_READ_BIT);
  if (p == nullptr) {
    check_gl_error("Buffer::read_mapped");
    throw std::runtime_error("Buffer::read_mapped: glMapNamedBufferRange failed (a buffer not made by mappable()?)");
  }
  return {static_cast<const std::byte*>(p), size_bytes};
}

void Buffer::unmap() const { glUnmapNamedBuffer(id_); }

void Buffer::read_into(std::span<std::byte> out) const {
  if (id_ == 0) throw std::logic_error("Buffer::read on an empty buffer");
  if (out.size() > size_)
    throw std::out_of_range(fmt::format("Buffer::read_into: {} bytes from a {}-byte buffer", out.size(), size_));
  if (out.empty()) return;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(id_, 0, static_cast<GLsizeiptr>(out.size()), out.data());
  check_gl_error("Buffer::read");
}

void Buffer::bind_storage(unsigned binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id_); }

void Buffer::bind_uniform(unsigned binding) const { glBindBufferBase(GL_UNIFORM_BUFFER, binding, id_); }

}  // namespace zenith::render::gl
