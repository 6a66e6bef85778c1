#include "render/gl/software_rasterizer.h"

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

}  // namespace zenith::render::gl
