#include "cluster/launcher/child_process.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "cluster/protocol/handshake.h"
#include "core/process.h"

namespace zenith::app {

using Clock = std::chrono::steady_clock;

bool is_local_host(const std::string& host) {
  if (host == "127.0.0.1" || host == "localhost" || host == "::1") return true;
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 && host == name;
}

std::string log_level_argument() {
  switch (spdlog::get_level()) {
    case spdlog::level::trace: return "trace";
    case spdlog::level::debug: return "debug";
    case spdlog::level::warn: return "warn";
    case spdlog::level::err: return "error";
    case spdlog::level::off: return "off";
    default: return "info";
  }
}

pid_t spawn_self(const std::vector<std::string>& args) {
  try {
    return core::spawn_process("/proc/self/exe", args);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(fmt::format("cannot start a child zenith process: {}", e.what()));
  }
}

std::optional<int> wait_for(pid_t pid, std::chrono::milliseconds timeout) { return core::wait_for_exit(pid, timeout); }

int stop_child(pid_t pid, const std::string& what, std::chrono::milliseconds grace) {
  if (auto status = wait_for(pid, grace)) return *status;
  spdlog::warn("cluster: {} still running after {} ms: SIGTERM", what, grace.count());
  ::kill(pid, SIGTERM);
  if (auto status = wait_for(pid, std::chrono::milliseconds(3000))) return *status;
  spdlog::warn("cluster: {} ignored SIGTERM: SIGKILL", what);
  ::kill(pid, SIGKILL);
  return wait_for(pid, std::chrono::milliseconds(3000)).value_or(-1);
}

void ensure_local_secret(const cluster::ClusterConfig& config) {
  if (config.secret_file) return;
  const char* value = std::getenv(config.secret_env.c_str());
  if (value != nullptr && *value != '\0') return;
  const cluster::Nonce bytes = cluster::random_nonce();
  ::setenv(config.secret_env.c_str(), cluster::to_hex(bytes).c_str(), 1);
  spdlog::info("cluster: ${} is not set: a random one-off secret is passed to the master and nodes", config.secret_env);
}

}  // namespace zenith::app
