#include "tests/rig/network_rig.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "core/process.h"

namespace zenith::testing {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

constexpr const char* kPrefix = "zr-";  // every rig namespace: zr-<pid>-<tag>-<host>
constexpr const char* kSubnet = "198.18.0.";
constexpr const char* kHostInterface = "eth0";
constexpr auto kCommandTimeout = 20s;

/// The first of `names` found in the system's program folders; "" when none.
fs::path system_program(const std::string& name) {
  for (const char* dir : {"/usr/sbin", "/sbin", "/usr/bin", "/bin"}) {
    const fs::path p = fs::path(dir) / name;
    if (::access(p.c_str(), X_OK) == 0) return p;
  }
  return {};
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs argv[0] (a system program) with the rest; its exit status and output.
std::pair<int, std::string> run_command(const std::vector<std::string>& argv) {
  const fs::path program = system_program(argv.front());
  if (program.empty()) return {127, argv.front() + ": not found"};
  const fs::path log = fs::temp_directory_path() / ("zenith-rig-" + std::to_string(::getpid()) + ".out");
  const pid_t pid = core::spawn_process(program, std::vector<std::string>(argv.begin() + 1, argv.end()), log);
  const std::optional<int> status =
      core::wait_for_exit(pid, std::chrono::duration_cast<std::chrono::milliseconds>(kCommandTimeout));
  if (!status) {
    ::kill(pid, SIGKILL);
    core::wait_for_exit(pid, 5000ms);
  }
  std::string output = read_file(log);
  fs::remove(log);
  return {status.value_or(124), output};
}

/// zr-<pid>-<tag>-<suffix>: a rig namespace, its owner's pid in its name.
std::string netns_name(const std::string& tag, const std::string& suffix) {
  std::string name = kPrefix;
  name += std::to_string(::getpid());
  name += '-';
  name += tag;
  name += '-';
  name += suffix;
  return name;
}

std::string joined(const std::vector<std::string>& argv) {
  std::string text;
  for (const std::string& a : argv) text += (text.empty() ? "" : " ") + a;
  return text;
}

/// Namespaces of rigs whose process is gone (a run killed before its rig's destructor).
void remove_abandoned_rigs() {
  const auto [status, list] = run_command({"ip", "netns", "list"});
  if (status != 0) return;
  std::size_t at = 0;
  while ((at = list.find(kPrefix, at)) != std::string::npos) {
    const std::size_t end = list.find_first_of(" \n", at);
    const std::string name = list.substr(at, end - at);
    at = end;
    const std::size_t dash = name.find('-', 3);
    if (dash == std::string::npos) continue;
    const pid_t owner = static_cast<pid_t>(std::strtol(name.substr(3, dash - 3).c_str(), nullptr, 10));
    if (owner > 0 && ::kill(owner, 0) != 0 && errno == ESRCH) run_command({"ip", "netns", "delete", name});
  }
}

}  // namespace

std::optional<std::string> NetworkRig::unavailable() {
  if (::geteuid() != 0) return "network namespaces need root (the tests run as root in CI)";
  if (system_program("ip").empty()) return "iproute2's `ip` is not installed (scripts/bootstrap installs it)";
  if (system_program("nft").empty()) return "nftables' `nft` is not installed (scripts/bootstrap installs it)";
  const std::string probe = netns_name("probe", "0");
  const auto [status, output] = run_command({"ip", "netns", "add", probe});
  if (status != 0) return "cannot make a network namespace here: " + output;
  run_command({"ip", "netns", "delete", probe});
  return std::nullopt;
}

NetworkRig::NetworkRig(std::string tag) : tag_(std::move(tag)) {
  if (tag_.empty() || tag_.size() > 12 ||
      !std::all_of(tag_.begin(), tag_.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); }))
    throw std::invalid_argument("NetworkRig: tag '" + tag_ + "': 1 to 12 letters and digits");
  remove_abandoned_rigs();
  switch_netns_ = netns_name(tag_, "switch");
  run({"ip", "netns", "add", switch_netns_});
  run({"ip", "-n", switch_netns_, "link", "add", "br0", "type", "bridge"});
  run({"ip", "-n", switch_netns_, "link", "set", "br0", "up"});
  run({"ip", "-n", switch_netns_, "addr", "add", std::string(kSubnet) + "1/24", "dev", "br0"});
}

NetworkRig::~NetworkRig() {
  for (const pid_t pid : children_)
    if (::kill(pid, 0) == 0) {
      ::kill(pid, SIGKILL);
      core::wait_for_exit(pid, 5000ms);
    }
  // Deleting a namespace deletes its interfaces, and with them both ends of its link.
  for (const Host& h : hosts_) run_command({"ip", "netns", "delete", h.netns});
  run_command({"ip", "netns", "delete", switch_netns_});
}

void NetworkRig::run(const std::vector<std::string>& argv) const {
  const auto [status, output] = run_command(argv);
  if (status != 0)
    throw std::runtime_error("network rig: `" + joined(argv) + "` failed (" + std::to_string(status) + "): " + output);
}

namespace {
/// The switch's side of the k-th host's link: "p<k>".
std::string port_name(std::size_t k) {
  std::string port = "p";
  port += std::to_string(k);
  return port;
}
}  // namespace

const NetworkRig::Host& NetworkRig::add_host(const std::string& name) {
  const std::size_t k = hosts_.size();
  if (k >= 200) throw std::length_error("network rig: at most 200 hosts");
  Host h;
  h.name = name;
  h.netns = netns_name(tag_, std::to_string(k));
  h.address = kSubnet;
  h.address += std::to_string(10 + k);
  h.interface = kHostInterface;
  const std::string port = port_name(k);
  run({"ip", "netns", "add", h.netns});
  hosts_.push_back(h);
  impairments_.emplace_back();
  // Both ends made in their namespaces: nothing appears in the machine's own.
  run({"ip", "link", "add", "name", h.interface, "netns", h.netns, "type", "veth", "peer", "name", port, "netns",
       switch_netns_});
  run({"ip", "-n", switch_netns_, "link", "set", port, "master", "br0", "up"});
  run({"ip", "-n", h.netns, "addr", "add", h.address + "/24", "dev", h.interface});
  run({"ip", "-n", h.netns, "link", "set", h.interface, "up"});
  run({"ip", "-n", h.netns, "link", "set", "lo", "up"});
  return hosts_.back();
}

const NetworkRig::Host& NetworkRig::host(const std::string& name) const {
  for (const Host& h : hosts_)
    if (h.name == name) return h;
  throw std::invalid_argument("network rig: no host '" + name + "'");
}
NetworkRig::Host& NetworkRig::find(const std::string& name) {
  for (Host& h : hosts_)
    if (h.name == name) return h;
  throw std::invalid_argument("network rig: no host '" + name + "'");
}

/// The host's nftables ruleset, made afresh: its loss and its cut, both ways.
void NetworkRig::apply_filter(const Host& h) {
  const Impairment& i = impairments_[static_cast<std::size_t>(&h - hosts_.data())];
  const std::vector<std::string> nft = {"ip", "netns", "exec", h.netns, "nft"};
  const auto with = [&](std::vector<std::string> words) {
    std::vector<std::string> argv = nft;
    argv.insert(argv.end(), words.begin(), words.end());
    return argv;
  };
  run(with({"flush", "ruleset"}));
  if (!i.cut && i.loss_percent <= 0.0) return;
  run(with({"add", "table", "inet", "rig"}));
  run(with({"add", "chain", "inet", "rig", "in", "{", "type", "filter", "hook", "input", "priority", "0", ";", "}"}));
  run(with({"add", "chain", "inet", "rig", "out", "{", "type", "filter", "hook", "output", "priority", "0", ";", "}"}));
  if (i.cut) {
    run(with({"add", "rule", "inet", "rig", "in", "iifname", h.interface, "drop"}));
    run(with({"add", "rule", "inet", "rig", "out", "oifname", h.interface, "drop"}));
    return;
  }
  const std::string per_10000 = std::to_string(std::lround(i.loss_percent * 100.0));
  run(with({"add", "rule", "inet", "rig", "in", "iifname", h.interface, "numgen", "random", "mod", "10000", "lt",
            per_10000, "drop"}));
  run(with({"add", "rule", "inet", "rig", "out", "oifname", h.interface, "numgen", "random", "mod", "10000", "lt",
            per_10000, "drop"}));
}

void NetworkRig::set_loss(const std::string& name, double percent) {
  if (!(percent >= 0.0 && percent <= 100.0))
    throw std::invalid_argument("network rig: loss " + std::to_string(percent) + " %: must be in [0, 100]");
  Host& h = find(name);
  impairments_[static_cast<std::size_t>(&h - hosts_.data())].loss_percent = percent;
  apply_filter(h);
}

void NetworkRig::partition(const std::string& name) {
  Host& h = find(name);
  impairments_[static_cast<std::size_t>(&h - hosts_.data())].cut = true;
  apply_filter(h);
}

void NetworkRig::heal(const std::string& name) {
  Host& h = find(name);
  impairments_[static_cast<std::size_t>(&h - hosts_.data())].cut = false;
  apply_filter(h);
}

void NetworkRig::unplug(const std::string& name) {
  const Host& h = find(name);
  run({"ip", "-n", h.netns, "link", "delete", h.interface});  // a veth pair goes with either end
}

std::string NetworkRig::switch_port(const std::string& name) const {
  for (std::size_t k = 0; k < hosts_.size(); ++k)
    if (hosts_[k].name == name) return port_name(k);
  throw std::invalid_argument("network rig: no host '" + name + "'");
}

void NetworkRig::set_rate(const std::string& name, double bits_per_s, Way way) {
  const Host& h = find(name);
  // The egress of one side of the link: the host's (what it sends) or the switch's port (what it receives).
  const std::string netns = way == Way::from_host ? h.netns : switch_netns_;
  const std::string device = way == Way::from_host ? h.interface : switch_port(name);
  if (bits_per_s <= 0.0) {
    run_command({"ip", "netns", "exec", netns, "tc", "qdisc", "del", "dev", device, "root"});
    return;
  }
  // A burst of 10 ms at the rate (at least 32 KiB), a queue of 50 ms.
  const auto burst = std::max<long long>(32768, std::llround(bits_per_s / 8.0 * 0.010));
  run({"ip", "netns", "exec", netns, "tc", "qdisc", "replace", "dev", device, "root", "tbf", "rate",
       std::to_string(std::llround(bits_per_s)) + "bit", "burst", std::to_string(burst), "latency", "50ms"});
}

pid_t NetworkRig::spawn(const std::string& name, const fs::path& program, const std::vector<std::string>& args,
                        const fs::path& log) {
  const Host& h = host(name);
  std::vector<std::string> argv = {"netns", "exec", h.netns, program.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  // `ip netns exec` enters the namespace and execs the program: the pid is the program's.
  const pid_t pid = core::spawn_process(system_program("ip"), argv, log, core::LogMode::append);
  children_.push_back(pid);
  return pid;
}

}  // namespace zenith::testing
