#pragma once
// Hosts on one machine for the cluster's network tests and benchmarks
// (docs/cluster.md, "The network rig"): each host a network namespace with
// one link to a switch — a bridge in a namespace of its own — so a master,
// a standby and the nodes talk over real IP with real TCP and UDP stacks and
// real queues, and each link can be impaired on its own:
//
//   * random loss of a percentage of the packets, both ways (nftables,
//     `numgen random` in the host's namespace);
//   * a partition: every packet of the link dropped until healed;
//   * a rate limit (tc tbf on the host's side of the link).
//
// The addresses are the project's own choosing, inside these namespaces
// only: 198.18.0.0/24 (RFC 2544's benchmarking range), the switch at .1, the
// hosts from .10 on. Nothing touches the machine's own namespace, routes or
// interfaces: both ends of every link are made inside their namespaces.
// Everything a rig made — namespaces, links, the processes it started — is
// removed when it is destroyed, and a rig left behind by a killed run (its
// process gone) is removed by the next one. Needs root and iproute2 (and
// nftables for loss and partitions); unavailable() says why not.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace zenith::testing {

class NetworkRig {
 public:
  struct Host {
    std::string name;       ///< the test's name for it ("master", "a")
    std::string netns;      ///< its network namespace
    std::string address;    ///< its IPv4 address on the rig
    std::string interface;  ///< its side of its link (in its namespace)
  };

  /// Why no rig can be made on this machine (not root, no `ip`, no `nft`,
  /// namespaces refused), or nothing when one can.
  static std::optional<std::string> unavailable();

  /// A switch and no host yet; `tag` (letters and digits) names its namespaces.
  explicit NetworkRig(std::string tag);
  ~NetworkRig();
  NetworkRig(const NetworkRig&) = delete;
  NetworkRig& operator=(const NetworkRig&) = delete;

  /// A new host on the switch, its link up and unimpaired. The reference
  /// lasts until the next add_host().
  const Host& add_host(const std::string& name);
  const Host& host(const std::string& name) const;

  /// Drops `percent` (0 to 100, in steps of 0.01) of the packets of the
  /// host's link, each way; 0 removes the loss.
  void set_loss(const std::string& host, double percent);
  /// Cuts the host's link (every packet dropped, both ways) / restores it.
  void partition(const std::string& host);
  void heal(const std::string& host);
  /// Pulls the host's cable: its link is deleted (both ends), so its
  /// connections end without a FIN or a reset — half-open on the other side.
  /// There is no way back for that host.
  void unplug(const std::string& host);
  /// Which way of a host's link a rate limits.
  enum class Way { from_host, to_host };
  /// Limits what the host sends (from_host: tc tbf on its side of the link) or
  /// receives (to_host: on the switch's side) to `bits_per_s`; 0 removes the limit.
  void set_rate(const std::string& host, double bits_per_s, Way way = Way::from_host);

  /// Starts `program args...` in the host's namespace, its output in `log`;
  /// the rig kills it (SIGKILL) when it goes, if it still runs.
  pid_t spawn(const std::string& host, const std::filesystem::path& program, const std::vector<std::string>& args,
              const std::filesystem::path& log);

 private:
  /// Runs a command (argv) with a deadline; throws naming it and its output when it fails.
  void run(const std::vector<std::string>& argv) const;
  void apply_filter(const Host& host);
  Host& find(const std::string& name);
  /// The switch's side of the host's link (in the switch's namespace).
  std::string switch_port(const std::string& name) const;

  std::string tag_;
  std::string switch_netns_;
  std::vector<Host> hosts_;
  struct Impairment {
    double loss_percent = 0.0;
    bool cut = false;
  };
  std::vector<Impairment> impairments_;  ///< per host, in hosts_' order
  std::vector<pid_t> children_;
};

}  // namespace zenith::testing
