#pragma once
// Child `zenith` processes of a local cluster (`zenith cluster`, `zenith show
// render --cluster`): start, wait with a deadline, stop cleanly.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "cluster/link/cluster_config.h"

namespace zenith::app {

/// 127.0.0.1, localhost, ::1 or this machine's host name.
bool is_local_host(const std::string& host);
/// The --log-level value matching the current level, for the children.
std::string log_level_argument();
/// Starts /proc/self/exe with `args` (argv[1..]); returns the child's pid.
/// Throws std::runtime_error when it cannot be started.
pid_t spawn_self(const std::vector<std::string>& args);
/// waitpid with a deadline: the exit status (128 + signal when killed), or
/// nullopt when still running.
std::optional<int> wait_for(pid_t pid, std::chrono::milliseconds timeout);
/// Stops a child: waits `grace`, then SIGTERM, then SIGKILL; its exit status.
int stop_child(pid_t pid, const std::string& what, std::chrono::milliseconds grace);
/// A local run needs no secret set up: when the configuration's secret comes
/// from an environment variable that is unset, a fresh random one is put there
/// for this process and its children.
void ensure_local_secret(const cluster::ClusterConfig& config);

}  // namespace zenith::app
