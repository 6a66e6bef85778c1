#pragma once
// A point in the GL command stream the CPU can test or wait for
// (glFenceSync): the commands issued before it are complete once it has
// signalled. Move-only; it deletes its sync object. Needs a current GL
// context to be made, tested, waited for and destroyed.
#include <string_view>

namespace zenith::render::gl {

class Fence {
 public:
  Fence() = default;  ///< none: signalled, nothing to wait for
  /// After every command issued so far; throws std::runtime_error where GL makes none.
  static Fence after_issued_commands();
  ~Fence();
  Fence(Fence&& other) noexcept;
  Fence& operator=(Fence&& other) noexcept;
  Fence(const Fence&) = delete;
  Fence& operator=(const Fence&) = delete;

  bool empty() const { return sync_ == nullptr; }
  /// Whether the GPU has passed it, without waiting (an empty fence has).
  bool signalled() const;
  /// Blocks until it has signalled, flushing the commands before it, a second
  /// at a time so that a lost GPU shows as an error (naming `what`) rather
  /// than a hang; then the fence is empty.
  void wait(std::string_view what);

 private:
  explicit Fence(void* sync) : sync_(sync) {}
  void release() noexcept;
  void* sync_ = nullptr;  // GLsync
};

}  // namespace zenith::render::gl
