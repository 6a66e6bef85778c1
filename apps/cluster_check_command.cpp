// `zenith cluster check` (docs/cluster.md, "Checking the network"): run on
// the master's PC before a show, with the nodes' services running and no
// master: each node's round trips, losses each way, throughput, clock and a
// verdict against the cluster's frame rate and lookahead; `--json` for scripts.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "apps/commands.h"
#include "apps/default_configs.h"
#include "cluster/check/link_check.h"
#include "cluster/check/link_check_report.h"
#include "cluster/link/cluster_config.h"
#include "cluster/protocol/handshake.h"

namespace zenith::app {
namespace {

struct CheckArgs {
  std::string cluster;
  std::optional<int> port;
  double seconds = 5.0, ping_interval_ms = 10.0, wait_s = 30.0, fill_timeout_s = 30.0;
  std::uint64_t fill_mib = 32;
  bool json = false, strict = false;
};

/// 0: ok (or warnings without --strict), 2: a link fails, 3: warnings with --strict.
int run_check(const CheckArgs& a) {
  cluster::LinkCheckOptions options;
  options.config =
      cluster::load_cluster_config(a.cluster.empty() ? default_config(kDefaultClusterName).string() : a.cluster);
  if (a.port) options.port = static_cast<std::uint16_t>(*a.port);
  options.duration = std::chrono::milliseconds(std::lround(a.seconds * 1000));
  options.ping_interval = std::chrono::microseconds(std::lround(a.ping_interval_ms * 1000));
  options.fill_bytes = a.fill_mib << 20;
  options.wait_for_nodes = std::chrono::milliseconds(std::lround(a.wait_s * 1000));
  options.fill_timeout = std::chrono::milliseconds(std::lround(a.fill_timeout_s * 1000));
  cluster::SharedSecret secret =
      cluster::load_shared_secret(options.config.secret_file, options.config.secret_env.c_str());
  const cluster::LinkCheckReport report = cluster::make_report(options, check_links(options, std::move(secret)));
  const std::string text = a.json ? report.to_json_text() : cluster::format_table(report);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  switch (report.grade()) {
    case cluster::LinkGrade::ok: return 0;
    case cluster::LinkGrade::warn: return a.strict ? 3 : 0;
    case cluster::LinkGrade::fail: return 2;
  }
  return 2;
}

}  // namespace

void register_cluster_check(CLI::App& cluster_command) {
  auto a = std::make_shared<CheckArgs>();
  CLI::App* cmd = cluster_command.add_subcommand(
      "check",
      "Check the network before a show: run on the master's PC (no master running), the nodes' services up; each "
      "node's round trip, loss, throughput and clock, and a verdict (docs/cluster.md, \"Checking the network\")");
  cmd->add_option("--cluster", a->cluster, "Cluster config JSON (default: the built-in local cluster)");
  cmd->add_option("--port", a->port, "Override the config's master port")->check(CLI::Range(1, 65535));
  cmd->add_option("--seconds", a->seconds, "Seconds of pings per node (default 5)")->check(CLI::Range(0.1, 60.0));
  cmd->add_option("--ping-interval-ms", a->ping_interval_ms, "Between pings (default 10: 100 a second)")
      ->check(CLI::Range(1.0, 100.0));
  cmd->add_option("--fill-mib", a->fill_mib, "MiB sent to each node for its throughput (default 32; 0: none)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--wait-s", a->wait_s, "How long to wait for the nodes to connect (default 30)")
      ->check(CLI::Range(1.0, 3600.0));
  cmd->add_option("--fill-timeout-s", a->fill_timeout_s, "How long a node may take over its fill (default 30)")
      ->check(CLI::Range(1.0, 3600.0));
  cmd->add_flag("--json", a->json, "Print the result as JSON (docs/cluster.md names every key)");
  cmd->add_flag("--strict", a->strict, "Exit 3 on warnings (default: only a failing link exits non-zero, with 2)");
  cmd->callback([a] {
    const int code = run_check(*a);
    if (code != 0) std::exit(code);
  });
}

}  // namespace zenith::app
