#include "render/gl/shader_text_hook.h"

#include <memory>
#include <mutex>
#include <utility>

namespace zenith::render::gl {
namespace {

// The installed hook, shared so that a stage being compiled keeps the one it
// started with while another thread installs the next.
struct HookSlot {
  std::mutex mutex;
  std::shared_ptr<const ShaderTextHook> hook;
};

HookSlot& hook_slot() {
  static HookSlot slot;
  return slot;
}

}  // namespace

ShaderTextHook install_shader_text_hook(ShaderTextHook hook) {
  HookSlot& slot = hook_slot();
  auto next = hook ? std::make_shared<const ShaderTextHook>(std::move(hook)) : nullptr;
  const std::lock_guard lock(slot.mutex);
  std::shared_ptr<const ShaderTextHook> previous = std::exchange(slot.hook, std::move(next));
  return previous ? *previous : ShaderTextHook();
}

std::string apply_shader_text_hook(std::string_view name, std::string text) {
  std::shared_ptr<const ShaderTextHook> hook;
  {
    HookSlot& slot = hook_slot();
    const std::lock_guard lock(slot.mutex);
    hook = slot.hook;
  }
  return hook ? (*hook)(name, std::move(text)) : text;
}

}  // namespace zenith::render::gl
