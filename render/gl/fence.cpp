#include "render/gl/fence.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "render/gl/gl_error.h"

namespace zenith::render::gl {

Fence Fence::after_issued_commands() {
  void* sync = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  if (sync == nullptr) throw std::runtime_error("glFenceSync made no fence");
  return Fence(sync);
}

Fence::~Fence() { release(); }

Fence::Fence(Fence&& other) noexcept : sync_(std::exchange(other.sync_, nullptr)) {}

Fence& Fence::operator=(Fence&& other) noexcept {
  if (this != &other) {
    release();
    sync_ = std::exchange(other.sync_, nullptr);
  }
  return *this;
}

void Fence::release() noexcept {
  if (sync_ != nullptr) glDeleteSync(static_cast<GLsync>(sync_));
  sync_ = nullptr;
}

bool Fence::signalled() const {
  if (sync_ == nullptr) return true;
  const GLenum status = glClientWaitSync(static_cast<GLsync>(sync_), 0, 0);
  if (status == GL_WAIT_FAILED) throw std::runtime_error("testing a GL fence failed");
  return status != GL_TIMEOUT_EXPIRED;
}

void Fence::wait(std::string_view what) {
  if (sync_ == nullptr) return;
  for (;;) {
    const GLenum status = glClientWaitSync(static_cast<GLsync>(sync_), GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
    if (status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED) break;
    if (status == GL_WAIT_FAILED) {
      check_gl_error(fmt::format("waiting for {}", what));
      throw std::runtime_error(fmt::format("{}: waiting for the GPU's fence failed", what));
    }
  }
  release();
}

}  // namespace zenith::render::gl
