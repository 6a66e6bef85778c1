#pragma once
// A GL buffer object for shader storage (SSBO) or uniform (UBO) blocks.
// Needs a current GL 4.5 context (direct state access).
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

namespace zenith::render::gl {

class Buffer {
 public:
  Buffer() = default;  ///< no buffer (id 0)
  /// `size_bytes` > 0 bytes, zero-filled.
  explicit Buffer(std::size_t size_bytes);
  /// A buffer holding a copy of `data` (non-empty).
  explicit Buffer(std::span<const std::byte> data);
  template <class T>
  requires std::is_trivially_copyable_v<T>
  static Buffer from(std::span<const T> data) { return Buffer(std::as_bytes(data)); }
  /// `size_bytes` > 0 bytes, zero-filled, that the CPU can map for reading (read_mapped).
  static Buffer mappable(std::size_t size_bytes);

  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  /// Writes `data` at `offset_bytes`; throws std::out_of_range past the end.
  void upload(std::span<const std::byte> data, std::size_t offset_bytes = 0);
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void upload(std::span<const T> data, std::size_t offset_bytes = 0) { upload(std::as_bytes(data), offset_bytes); }

  /// Zeros `size_bytes` bytes from `offset_bytes` (a multiple of 4 each; on the
  /// GPU, no upload); throws std::out_of_range past the end.
  void clear_to_zero(std::size_t offset_bytes, std::size_t size_bytes);

  /// `size_bytes` bytes from `offset_bytes`. Issues
  /// glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT) first, so shader stores of
  /// earlier dispatches are visible.
  std::vector<std::byte> read_bytes(std::size_t offset_bytes, std::size_t size_bytes) const;
  /// The whole buffer as elements of T (trailing bytes that fill no whole T are not read).
  template <class T>
  requires std::is_trivially_copyable_v<T> std::vector<T> read()
  const {
    std::vector<T> out(size_ / sizeof(T));
    read_into(std::as_writable_bytes(std::span<T>(out)));
    return out;
  }

  /// The first out.size() bytes into `out` (out.size() <= size()), after
  /// glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT): no intermediate copy.
  void read_into(std::span<std::byte> out) const;
  /// Maps the first `size_bytes` for reading (after the same barrier; waits for
  /// the commands that write them), calls `read` with them and unmaps: the
  /// caller converts straight from the buffer's memory (a software renderer's
  /// buffers are in system memory: no copy at all). Buffers from mappable() only.
  template <class F>
  void read_mapped(std::size_t size_bytes, F&& read) const {
    const std::span<const std::byte> bytes = map_read(size_bytes);
    try {
      read(bytes);
    } catch (...) {
      unmap();
      throw;
    }
    unmap();
  }

  /// Binds the whole buffer to `layout(binding = N) buffer` (GL_SHADER_STORAGE_BUFFER).
  void bind_storage(unsigned binding) const;
  /// Binds the whole buffer to `layout(binding = N) uniform` (GL_UNIFORM_BUFFER).
  void bind_uniform(unsigned binding) const;

  unsigned id() const { return id_; }
  std::size_t size() const { return size_; }

 private:
  void create(std::size_t size_bytes, const void* data, unsigned flags);
  std::span<const std::byte> map_read(std::size_t size_bytes) const;
  void unmap() const;
  void release() noexcept;

  unsigned id_ = 0;
  std::size_t size_ = 0;
};

}  // namespace zenith::render::gl
