#include "tests/rig/rig_cluster.h"

#include <signal.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/process.h"

namespace zenith::testing {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {
constexpr const char* kSecretVar = "ZENITH_RIG_SECRET";
constexpr int kMasterPort = 47100;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

RigCluster::RigCluster(NetworkRig& rig, RigClusterSetup setup) : rig_(rig), setup_(std::move(setup)) {
  fs::remove_all(setup_.work);
  fs::create_directories(setup_.work);
  const NetworkRig::Host master = rig_.add_host("master");  // a copy: more hosts follow
  std::string standby_entry;
  if (setup_.standby)
    standby_entry = std::string(R"("standby": {"host": ")") + rig_.add_host("standby").address + R"(", "port": )" +
                    std::to_string(kMasterPort) + "},";
  for (int k = 0; k < setup_.nodes; ++k) rig_.add_host(node_name(k));

  std::ofstream v(setup_.work / "viewports.json");
  v << R"({"zenith_viewports": 1, "name": "rig", "outputs": [)";
  for (int k = 0; k < setup_.nodes; ++k)
    v << (k ? "," : "") << R"({"name": "o)" << k << R"(", "size": [)" << setup_.output_px << ", " << setup_.output_px
      << R"(], "projection": {"type": "fisheye", "fov_deg": 180, "rotation_deg": )" << (360.0 * k / setup_.nodes)
      << "}}";
  v << "]}";
  v.close();

  std::ostringstream nodes;
  for (int k = 0; k < setup_.nodes; ++k)
    nodes << (k ? "," : "") << R"({"name": ")" << node_name(k) << R"(", "host": ")" << rig_.host(node_name(k)).address
          << R"(", "outputs": ["o)" << k << R"("]})";
  const auto write_config = [&](const fs::path& path, const std::string& master_host) {
    std::ofstream c(path);
    c << R"({"zenith_cluster": 1, "name": "rig-dome", "master": {"host": ")" << master_host << R"(", "port": )"
      << kMasterPort << R"(}, )" << standby_entry << R"("scene": ")" << setup_.scene.string()
      << R"(", "viewports": "viewports.json",
  "timing": {"heartbeat_ms": 200, "barrier_timeout_ms": 20000, "frame_rate_hz": )"
      << setup_.frame_rate_hz << R"(, "lookahead_frames": )" << setup_.lookahead_frames << R"(, "link_lost": ")"
      << (setup_.black_when_link_lost ? "black" : "hold") << '"'
      << (setup_.present_priority.empty() ? "" : R"(, "present_priority": ")" + setup_.present_priority + '"') << R"(},
  "secret": {"env": ")"
      << kSecretVar << R"("}, "tables": {"sizes": ")" << setup_.tables << R"(", "orders": 4},
  "nodes": [)"
      << nodes.str() << R"(], "output": {"directory": ")" << (setup_.work / "out").string()
      << R"(", "format": "png"}})";
  };
  config_ = setup_.work / "cluster.json";
  write_config(config_, master.address);
  for (int k = 0; k < setup_.nodes; ++k) {
    if (!setup_.relay) {
      node_configs_.push_back(config_);
      continue;
    }
    // The node's master is its relay, on loopback in its own namespace.
    std::string file = "cluster-";  // built with +=: GCC 12's -Wrestrict false positive on "…" + std::string
    file += node_name(k);
    file += ".json";
    node_configs_.push_back(setup_.work / file);
    write_config(node_configs_.back(), "127.0.0.1");
  }
  ::setenv(kSecretVar, "rig-secret-0123456789abcdef", 1);
}

RigCluster::~RigCluster() = default;

std::string RigCluster::node_name(int k) {
  std::string name = std::to_string(k);
  name.insert(name.begin(), 'n');  // not "n" + std::to_string(k): GCC 12's -Wrestrict false positive
  return name;
}  // the rig kills what it started

void RigCluster::start() {
  std::vector<std::string> args = {"master",
                                   "--cluster",
                                   config_.string(),
                                   "--frames",
                                   std::to_string(setup_.frames),
                                   "--cache",
                                   setup_.cache.string(),
                                   "--wait-for-nodes-ms",
                                   std::to_string(setup_.wait_for_nodes_ms)};
  if (setup_.sun_step_deg) args.insert(args.end(), {"--sun-step-deg", std::to_string(*setup_.sun_step_deg)});
  master_ = rig_.spawn("master", setup_.zenith, args, log("master"));
  if (setup_.standby)
    standby_ =
        rig_.spawn("standby", setup_.zenith,
                   {"master", "--standby", "--cluster", config_.string(), "--frames", std::to_string(setup_.frames),
                    "--cache", (setup_.work / "standby-cache").string(), "--wait-for-nodes-ms", "120000"},
                   log("standby"));
  start_nodes();
}

void RigCluster::start_check(const std::vector<std::string>& args, const std::string& name) {
  std::vector<std::string> argv = {"cluster", "check", "--cluster", config_.string(), "--json"};
  argv.insert(argv.end(), args.begin(), args.end());
  master_ = rig_.spawn("master", setup_.zenith, argv, log(name));
  start_nodes();
}

void RigCluster::start_nodes() {
  nodes_.clear();
  if (setup_.relay && relays_.empty())
    for (int k = 0; k < setup_.nodes; ++k) {
      const RigClusterSetup::Relay& r = *setup_.relay;
      const std::string port = std::to_string(kMasterPort);
      std::string listen = "127.0.0.1:", to = rig_.host("master").address, relay_log = "relay-";
      listen += port;
      to += ":";
      to += port;
      relay_log += node_name(k);
      relays_.push_back(
          rig_.spawn(node_name(k), r.program,
                     {"--listen", listen, "--to", to, "--delay-ms", std::to_string(r.delay_ms), "--jitter-ms",
                      std::to_string(r.jitter_ms), "--duplicate-percent", std::to_string(r.duplicate_percent),
                      "--reorder-percent", std::to_string(r.reorder_percent), "--seed", std::to_string(k + 1)},
                     log(relay_log)));
    }
  for (int k = 0; k < setup_.nodes; ++k)
    if (std::find(setup_.late_nodes.begin(), setup_.late_nodes.end(), k) == setup_.late_nodes.end())
      nodes_.push_back(start_node(k));
}

void RigCluster::join(int node) { nodes_.push_back(start_node(node, setup_.late_node_niceness)); }

pid_t RigCluster::start_node(int k, int niceness) {
  std::vector<std::string> args = {
      "node",       "--cluster", node_configs_[static_cast<std::size_t>(k)].string(),  "--name",
      node_name(k), "--cache",   (setup_.work / "node-cache" / node_name(k)).string(), "--connect-timeout-ms",
      "300000"};
  if (const auto more = setup_.node_args.find(k); more != setup_.node_args.end())
    args.insert(args.end(), more->second.begin(), more->second.end());
  if (niceness == 0) return rig_.spawn(node_name(k), setup_.zenith, args, log(node_name(k)));
  // nice execs zenith: the pid stays the node's.
  args.insert(args.begin(), {"-n", std::to_string(niceness), setup_.zenith.string()});
  return rig_.spawn(node_name(k), "/usr/bin/nice", args, log(node_name(k)));
}

bool RigCluster::wait_until_warmed_up(std::chrono::milliseconds timeout) {
  const auto warmed_up = [&] {
    return read_text(log("master")).find("warm-up frame 0 presented") != std::string::npos;
  };
  core::wait_until([&] { return core::process_gone(master_) || warmed_up(); }, timeout);
  return warmed_up();
}

std::optional<int> RigCluster::wait_for_master(std::chrono::milliseconds timeout) {
  const std::optional<int> status = core::wait_for_exit(master_, timeout);
  if (status && *status < 0) return std::nullopt;
  return status;
}

bool RigCluster::wait_for_nodes(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (const pid_t pid : nodes_) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (!core::wait_for_exit(pid, std::max(left, 0ms))) return false;
  }
  return true;
}

std::optional<int> RigCluster::stop_standby(std::chrono::milliseconds timeout) {
  if (standby_ < 0) return std::nullopt;
  ::kill(standby_, SIGTERM);
  const std::optional<int> status = core::wait_for_exit(standby_, timeout);
  if (status && *status < 0) return std::nullopt;
  return status;
}

std::vector<NodePresent> RigCluster::presents(int node) const {
  std::vector<NodePresent> out;
  std::ifstream in(setup_.work / "out" / node_name(node) / "presents.csv");
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    NodePresent p;
    char comma = 0;
    int scheduled = 0;
    std::istringstream fields(line);
    if (fields >> p.frame >> comma >> p.presented_ns >> comma >> p.asked_ns >> comma >> scheduled) {
      p.scheduled = scheduled != 0;
      if (!(fields >> comma >> p.woke_ns)) p.woke_ns = 0;
      if (!(fields >> comma >> p.wake_asked_ns)) p.wake_asked_ns = 0;
      out.push_back(p);
    }
  }
  return out;
}

NodeTimeline timeline_of(const std::vector<NodePresent>& presents, std::uint64_t first, std::uint64_t last,
                         std::int64_t from_ns, double long_ms) {
  NodeTimeline t;
  t.presents = presents;
  std::set<std::uint64_t> seen;
  for (std::size_t i = 0; i < presents.size(); ++i) {
    const NodePresent& p = presents[i];
    seen.insert(p.frame);
    if (i > 0 && p.frame <= presents[i - 1].frame) t.in_order = false;
    if (p.scheduled) t.latest_ms = std::max(t.latest_ms, static_cast<double>(p.presented_ns - p.asked_ns) / 1e6);
    if (i > 0 && presents[i - 1].presented_ns >= from_ns && presents[i - 1].frame >= first) {
      const double interval = static_cast<double>(p.presented_ns - presents[i - 1].presented_ns) / 1e6;
      t.longest_interval_ms = std::max(t.longest_interval_ms, interval);
      if (interval > long_ms) ++t.long_intervals;
    }
  }
  for (std::uint64_t f = first; f <= last; ++f)
    if (!seen.count(f)) t.missing.push_back(f);
  return t;
}

namespace {
/// max − min of `time` over the nodes' presents of each frame all of them presented (and `keep`).
template <class Time, class Keep>
std::vector<double> spreads_ms(const std::vector<std::vector<NodePresent>>& nodes, Time time, Keep keep) {
  std::map<std::uint64_t, std::vector<std::int64_t>> by_frame;
  for (const auto& presents : nodes)
    for (const NodePresent& p : presents)
      if (keep(p)) by_frame[p.frame].push_back(time(p));
  std::vector<double> spreads;
  for (const auto& [frame, times] : by_frame) {
    if (times.size() != nodes.size()) continue;
    const auto [lo, hi] = std::minmax_element(times.begin(), times.end());
    spreads.push_back(static_cast<double>(*hi - *lo) / 1e6);
  }
  return spreads;
}
}  // namespace

std::vector<double> swap_spreads_ms(const std::vector<std::vector<NodePresent>>& nodes) {
  return spreads_ms(
      nodes, [](const NodePresent& p) { return p.presented_ns; }, [](const NodePresent&) { return true; });
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  const double rank = std::clamp(p, 0.0, 1.0) * static_cast<double>(values.size() - 1) + 0.5;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(rank);
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

std::vector<double> moment_spreads_ms(const std::vector<std::vector<NodePresent>>& nodes) {
  return spreads_ms(
      nodes, [](const NodePresent& p) { return p.asked_ns; }, [](const NodePresent& p) { return p.scheduled; });
}

}  // namespace zenith::testing
