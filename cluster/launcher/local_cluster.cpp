#include "cluster/launcher/local_cluster.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "cluster/launcher/child_process.h"
#include "cluster/launcher/dome_stitch.h"
#include "cluster/launcher/launcher_signals.h"
#include "cluster/launcher/restart_limit.h"

namespace zenith::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// "exit status 3", "killed by signal 9 (Killed)": a child's end, for logs.
std::string describe_exit(int status) {
  if (status > 128 && status < 128 + 65)
    return fmt::format("killed by signal {} ({})", status - 128, ::strsignal(status - 128));
  return fmt::format("exit status {}", status);
}

/// A node process of the local cluster (or its standby master) and its restarts.
struct LocalNode {
  std::string name;
  std::vector<std::string> args;
  pid_t pid = -1;
  std::optional<int> status;  ///< set once it ended for good
  RestartLimit limit;
};

}  // namespace

void run_local_cluster(const LocalClusterOptions& o) {
  const cluster::ClusterConfig& config = o.config;
  const std::string config_path = o.config_path.string();
  ensure_local_secret(config);
  mark_children_as_launched();  // they get SIGTERM if this process dies, kill -9 included
  ForwardedSignals signals;     // SIGINT, SIGTERM, SIGHUP: logged and forwarded to the master
  const std::string level = log_level_argument();
  std::vector<std::string> common = {"--cluster", config_path};
  if (o.port) common.insert(common.end(), {"--port", std::to_string(*o.port)});
  const auto restart_limit = [&] {
    return RestartLimit(o.max_restarts, std::chrono::milliseconds(std::llround(o.restart_window_s * 1000.0)));
  };

  std::vector<std::string> master_args = {"--log-level", level, "master"};
  master_args.insert(master_args.end(), common.begin(), common.end());
  master_args.insert(master_args.end(), o.master_options.begin(), o.master_options.end());
  // The master says through a pipe when it listens: only then are the nodes
  // started, so if it cannot bind (another cluster's master holds the port)
  // none of them joins that other master.
  ReadyPipe ready;
  std::vector<std::string> with_ready = master_args;
  with_ready.insert(std::find(with_ready.begin(), with_ready.end(), "master") + 1,
                    {"--ready-fd", std::to_string(ready.write_end())});
  pid_t master = spawn_self(with_ready);
  ready.close_write_end();
  spdlog::info("cluster: master started (pid {})", master);
  int stop_signal = 0;
  std::optional<int> early_exit;
  if (!ready.wait([&] {
        stop_signal = signals.take();
        early_exit = wait_for(master, std::chrono::milliseconds(0));
        return stop_signal != 0 || early_exit.has_value();
      })) {
    if (stop_signal != 0 && !early_exit) {
      spdlog::warn("cluster: {} received before the master listened: stopping it (SIGTERM)", ::strsignal(stop_signal));
      ::kill(master, SIGTERM);
    }
    const int status = early_exit ? *early_exit : stop_child(master, "the master", std::chrono::milliseconds(5000));
    throw std::runtime_error(stop_signal != 0 ? fmt::format("stopped by {}", ::strsignal(stop_signal))
                                              : fmt::format("the master could not start ({}; see its log lines above): "
                                                            "no node was started",
                                                            describe_exit(status)));
  }
  // The standby master, when the config has one on this machine: the master's
  // arguments but the recording (one file, the active master's).
  std::optional<LocalNode> standby;
  if (config.standby && is_local_host(config.standby->host)) {
    std::vector<std::string> args = master_args;
    const auto record = std::find(args.begin(), args.end(), "--record");
    if (record != args.end()) args.erase(record, record + 2);
    args.insert(std::find(args.begin(), args.end(), "master") + 1, "--standby");
    const pid_t pid = spawn_self(args);
    standby = LocalNode{"standby", std::move(args), pid, std::nullopt, restart_limit()};
    spdlog::info("cluster: standby master started (pid {}; it takes over on {} if the master dies)", pid,
                 config.standby->text());
  } else if (config.standby) {
    spdlog::info("cluster: the standby master runs on {}: start it there with `zenith master --standby --cluster {}`",
                 config.standby->host, config_path);
  }

  std::vector<LocalNode> nodes;
  for (const auto& node : config.nodes) {
    if (!is_local_host(node.host)) {
      spdlog::info("cluster: node '{}' runs on {}: start it there with `zenith node --cluster {} --name {}`", node.name,
                   node.host, config_path, node.name);
      continue;
    }
    // The master may precompute tables for minutes before its Welcome (paper sizes on a CPU GL): wait for it.
    std::vector<std::string> args = {"--log-level",          level,   "node", "--name", node.name,
                                     "--connect-timeout-ms", "900000"};
    if (o.frame_directory) args.insert(args.end(), {"--out", o.frame_directory->string()});
    args.insert(args.end(), common.begin(), common.end());
    if (o.scene) args.insert(args.end(), {"--scene", o.scene->string()});
    if (o.windows) args.push_back("--window");
    if (o.cache_directory) args.insert(args.end(), {"--cache", (*o.cache_directory / "nodes" / node.name).string()});
    const pid_t pid = spawn_self(args);
    nodes.push_back(LocalNode{node.name, std::move(args), pid, std::nullopt, restart_limit()});
    spdlog::info("cluster: node '{}' started (pid {})", node.name, pid);
  }
  if (o.restart_nodes)
    spdlog::info("cluster: a local node that dies is restarted, at most {} time{} within {} s", o.max_restarts,
                 o.max_restarts == 1 ? "" : "s", o.restart_window_s);

  // Wait for the master; if every local node ends first (they could not join), stop it.
  int status = -1;
  std::optional<Clock::time_point> nodes_ended_at;
  for (;;) {
    if (const int signal = signals.take(); signal != 0) {
      spdlog::warn("cluster: {} received: forwarding SIGTERM to the master{} (its Goodbye stops the nodes)",
                   ::strsignal(signal), standby && !standby->status ? " and the standby" : "");
      stop_signal = signal;
      ::kill(master, SIGTERM);
      if (standby && !standby->status) ::kill(standby->pid, SIGTERM);
    }
    if (auto s = wait_for(master, std::chrono::milliseconds(200))) {
      // Killed (a crash, kill -9): the standby takes over and is the master
      // now. A master that exits with an error status reported it (a bad
      // option, a port in use): the cluster ends as without a standby.
      if (*s > 128 && standby && !standby->status && stop_signal == 0) {
        spdlog::warn("cluster: the master died ({}): the standby master (pid {}) takes over", describe_exit(*s),
                     standby->pid);
        master = standby->pid;
        standby.reset();
        continue;
      }
      status = *s;
      break;
    }
    if (standby && !standby->status) {
      if (const std::optional<int> ended = wait_for(standby->pid, std::chrono::milliseconds(0))) {
        if (o.restart_nodes && RestartLimit::died(*ended) && standby->limit.allow(Clock::now())) {
          standby->pid = spawn_self(standby->args);
          spdlog::warn("cluster: the standby master died ({}): restarted it (pid {}); it follows the master again",
                       describe_exit(*ended), standby->pid);
        } else {
          standby->status = ended;
          spdlog::warn("cluster: the standby master ended ({}): no takeover if the master dies", describe_exit(*ended));
        }
      }
    }
    for (LocalNode& n : nodes) {
      if (n.status) continue;
      const std::optional<int> ended = wait_for(n.pid, std::chrono::milliseconds(0));
      if (!ended) continue;
      if (o.restart_nodes && RestartLimit::died(*ended)) {
        if (n.limit.allow(Clock::now())) {
          n.pid = spawn_self(n.args);
          spdlog::warn("cluster: node '{}' died ({}): restarted it (pid {}; restart {}, {} of at most {} within {} s)",
                       n.name, describe_exit(*ended), n.pid, n.limit.total(), n.limit.recent(Clock::now()),
                       n.limit.max_restarts(), o.restart_window_s);
          continue;
        }
        spdlog::error(
            "cluster: node '{}' died ({}) after {} restarts within {} s: giving up on it, it stays down "
            "(--max-restarts {}, --restart-window-s {})",
            n.name, describe_exit(*ended), n.limit.max_restarts(), o.restart_window_s, o.max_restarts,
            o.restart_window_s);
      }
      n.status = ended;
    }
    if (!nodes.empty() &&
        std::all_of(nodes.begin(), nodes.end(), [](const LocalNode& n) { return n.status.has_value(); })) {
      // Nodes that exited 0 said goodbye to the master's Goodbye: its own exit follows within moments.
      if (!nodes_ended_at) nodes_ended_at = Clock::now();
      const bool clean = std::all_of(nodes.begin(), nodes.end(), [](const LocalNode& n) { return *n.status == 0; });
      if (after_nodes_ended(clean, std::chrono::duration_cast<std::chrono::milliseconds>(
                                       Clock::now() - *nodes_ended_at)) == NodesEndedVerdict::wait_for_master)
        continue;
      spdlog::error("cluster: every local node has exited; stopping the master");
      ::kill(master, SIGTERM);
      stop_child(master, "the master", std::chrono::milliseconds(5000));
      if (standby && !standby->status) {
        ::kill(standby->pid, SIGTERM);
        stop_child(standby->pid, "the standby master", std::chrono::milliseconds(5000));
      }
      throw std::runtime_error("the nodes exited before the show ended (see their log lines above)");
    }
  }
  // The master's Goodbye ends the nodes and the standby; stop any that linger.
  if (standby && !standby->status) {
    if (status != 0) ::kill(standby->pid, SIGTERM);
    stop_child(standby->pid, "the standby master", std::chrono::milliseconds(5000));
  }
  int failed_nodes = 0;
  for (const LocalNode& n : nodes) {
    const int exit_status =
        n.status ? *n.status : stop_child(n.pid, fmt::format("node '{}'", n.name), std::chrono::milliseconds(5000));
    if (exit_status != 0) {
      spdlog::warn("cluster: node '{}' ended with {}", n.name, describe_exit(exit_status));
      ++failed_nodes;
    }
  }
  if (stop_signal != 0)
    throw std::runtime_error(fmt::format("stopped by {} (master {})", ::strsignal(stop_signal), describe_exit(status)));
  if (status != 0) throw std::runtime_error(fmt::format("the master exited with status {}", status));
  spdlog::info("cluster: master and {} node{} stopped{}", nodes.size(), nodes.size() == 1 ? "" : "s",
               failed_nodes ? fmt::format(" ({} with an error)", failed_nodes) : std::string());
  if (o.frame_directory && o.stitch_frame && config.output_format == "png") {
    const fs::path target = *o.frame_directory / "stitched" / fmt::format("frame-{:06d}.png", *o.stitch_frame);
    if (const std::optional<StitchedDome> dome = stitch_dome(config, *o.frame_directory, *o.stitch_frame, target))
      fmt::print("stitched {} ({}x{} from {} tiles)\n", target.string(), dome->width_px, dome->height_px, dome->tiles);
  }
  if (failed_nodes)
    throw std::runtime_error(fmt::format("{} node{} failed", failed_nodes, failed_nodes == 1 ? "" : "s"));
}

}  // namespace zenith::app
