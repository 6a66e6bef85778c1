#include "render/gl/shader_cache_writes.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace zenith::render::gl {

bool shader_cache_writes_done() {
  std::error_code error;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", error)) {
    std::string name;
    if (std::ifstream comm(task.path() / "comm"); !std::getline(comm, name)) continue;  // the thread ended
    if (name.find(":disk$") == std::string::npos) continue;
    std::string stat;
    if (std::ifstream in(task.path() / "stat"); !std::getline(in, stat)) continue;
    // "TID (name) STATE …": the state follows the last ')' (a name may hold one).
    const std::size_t close = stat.rfind(')');
    if (close == std::string::npos || close + 2 >= stat.size()) continue;
    const char state = stat[close + 2];
    if (state == 'R' || state == 'D') return false;  // a write in hand, or queued and waiting for the processor
  }
  return true;
}

}  // namespace zenith::render::gl
