#include "render/gl/software_rasterizer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

namespace zenith::render::gl {

std::optional<int> software_rasterizer_threads_for(unsigned cpus) {
  if (cpus == 0 || cpus > 8) return std::nullopt;
  return static_cast<int>(2 * cpus);
}

std::string default_software_rasterizer_threads() {
  static std::once_flag once;
  static std::string setting;
  std::call_once(once, [] {
    if (const char* user = std::getenv("LP_NUM_THREADS"); user != nullptr && *user != '\0') {
      setting = std::string(user) + " (LP_NUM_THREADS)";
      return;
    }
    const std::optional<int> threads = software_rasterizer_threads_for(std::thread::hardware_concurrency());
    if (!threads) {
      setting = "Mesa's default";
      return;
    }
    setenv("LP_NUM_THREADS", std::to_string(*threads).c_str(), 0);
    setting = std::to_string(*threads) + " (set by zenith)";
  });
  return setting;
}

bool renderer_is_software(std::string_view gl_renderer) {
  std::string lower(gl_renderer);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (std::string_view cpu : {"llvmpipe", "softpipe", "swrast", "swr", "software rasterizer"})
    if (lower.find(cpu) != std::string::npos) return true;
  return false;
}

bool current_renderer_is_software() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer != nullptr && renderer_is_software(renderer);
}

}  // namespace zenith::render::gl
