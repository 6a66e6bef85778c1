#pragma once
// A zenith cluster on a NetworkRig (tests/rig/network_rig.h): the master on
// host "master", nodes "n0" … on hosts of their own, each rendering one small
// fisheye output, frames paced and scheduled; what each node presented and
// when, read back from its presents.csv (cluster/node/render_worker.h). Shared
// by the rig tests (tests/cluster/network_rig_test.cpp, pass/fail properties)
// and the rig benchmark (bench/cluster_bench.cpp --rig, the figures).
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tests/rig/network_rig.h"

namespace zenith::testing {

struct RigClusterSetup {
  std::filesystem::path zenith;  ///< the zenith binary
  std::filesystem::path work;    ///< configs, logs and node outputs go here (made afresh)
  std::filesystem::path cache;   ///< the master's table cache (shared between runs)
  std::filesystem::path scene;   ///< the scene file
  int nodes = 2;
  double frame_rate_hz = 30.0;
  std::uint64_t frames = 150;  ///< presented frames, the warm-up frame 0 included
  int lookahead_frames = 3;    ///< 0: the barrier
  int output_px = 32;          ///< each node's square fisheye output
  std::string tables = "small";
  bool black_when_link_lost = false;  ///< timing.link_lost: "black" (else "hold")
  /// timing.present_priority ("realtime", "normal"); empty: not written (the default, realtime).
  std::string present_priority;
  bool standby = false;  ///< a standby master on host "standby" (docs/cluster.md, "Standby master")
  /// A delaying relay (tests/rig/delay_relay.cpp) in front of each node, in
  /// its namespace: the node connects to it as to its master (127.0.0.1), and
  /// it forwards to the master and back with these impairments, each way.
  struct Relay {
    std::filesystem::path program;  ///< zenith_delay_relay
    double delay_ms = 0, jitter_ms = 0, duplicate_percent = 0, reorder_percent = 0;
  };
  std::optional<Relay> relay;
  /// The master starts frame 0 when every node is ready, or after this long with those that are.
  int wait_for_nodes_ms = 120000;
  /// Nodes start() leaves out (join() starts them later: a node joining mid-show).
  std::vector<int> late_nodes;
  /// The niceness join() starts a late node with. On a dome a joining node
  /// loads its tables (checksums, decoding, uploads, its first render) on its
  /// own PC; on the rig every host shares this machine's cores, and a nice
  /// joiner leaves them to the nodes already playing, as its own PC would.
  int late_node_niceness = 0;
  /// The default show's sun turns this much a frame (`zenith master --sun-step-deg`; unset: the master's default).
  std::optional<double> sun_step_deg;
  /// More arguments for node k's `zenith node` (a rehearsal of faults, e.g. its clock's).
  std::map<int, std::vector<std::string>> node_args;
};

/// One present of a node, from its presents.csv (ns of CLOCK_MONOTONIC).
struct NodePresent {
  std::uint64_t frame = 0;
  std::int64_t presented_ns = 0, asked_ns = 0;
  bool scheduled = false;
  std::int64_t woke_ns = 0;        ///< when the render thread woke for it (0: not recorded)
  std::int64_t wake_asked_ns = 0;  ///< when it had asked to wake: the moment less its margin (0: none)
};

/// What a node showed over a run, from its presents.
struct NodeTimeline {
  std::vector<NodePresent> presents;   ///< in the order presented
  bool in_order = true;                ///< frame numbers strictly increasing
  std::vector<std::uint64_t> missing;  ///< frames in [first, last expected] never presented
  double longest_interval_ms = 0.0;    ///< between consecutive presents (from `from_ns` on)
  std::uint64_t long_intervals = 0;    ///< longer than `long_ms`
  double latest_ms = 0.0;              ///< the largest present − scheduled moment
};
/// The timeline of `presents` over the frames [first, last], intervals counted
/// from presents of frames ≥ `first` at or after `from_ns` (so not from the
/// warm-up frame 0 to the schedule's first frame, which is `lookahead_frames`
/// periods after it by design); `long_ms`: what counts as long.
NodeTimeline timeline_of(const std::vector<NodePresent>& presents, std::uint64_t first, std::uint64_t last,
                         std::int64_t from_ns, double long_ms);
/// max − min of the nodes' present times (ms), for each frame every node presented, in frame order.
std::vector<double> swap_spreads_ms(const std::vector<std::vector<NodePresent>>& nodes);
/// max − min of the moments the nodes had for each frame every node presented
/// as scheduled (ms): their clock estimates' disagreement. On one machine the
/// truth is 0 (one CLOCK_MONOTONIC), so this is the clock synchronisation's
/// error, apart from how promptly each node then presented.
std::vector<double> moment_spreads_ms(const std::vector<std::vector<NodePresent>>& nodes);

/// The `p` quantile of `values` (0: the smallest, 1: the largest; the nearest rank); 0 for none.
double percentile(std::vector<double> values, double p);

class RigCluster {
 public:
  RigCluster(NetworkRig& rig, RigClusterSetup setup);
  ~RigCluster();

  /// Starts the master and every node but the late ones in their namespaces.
  void start();
  /// Starts a late node (setup().late_nodes).
  void join(int node);
  /// Starts `zenith cluster check --json` (with `args`) on the master's host
  /// instead of the master, and every node: wait_for_master() waits for the
  /// check, whose output (its log lines, then the JSON) is log(`name`).
  void start_check(const std::vector<std::string>& args, const std::string& name);
  /// Waits until the nodes are warmed up (the master presented frame 0, and
  /// the frame rate's schedule started); false on timeout or when the master ended.
  bool wait_until_warmed_up(std::chrono::milliseconds timeout);
  /// Waits for the master's exit; its status, nothing on timeout.
  std::optional<int> wait_for_master(std::chrono::milliseconds timeout);
  /// Waits for every node's exit (after the master's Goodbye).
  bool wait_for_nodes(std::chrono::milliseconds timeout);
  /// The standby master (setup().standby): SIGTERM, then its exit status
  /// within `timeout` (nothing when it did not end).
  std::optional<int> stop_standby(std::chrono::milliseconds timeout);

  /// "n0", "n1", …
  static std::string node_name(int k);
  std::vector<NodePresent> presents(int node) const;
  std::filesystem::path log(const std::string& host) const { return setup_.work / (host + ".log"); }
  const RigClusterSetup& setup() const { return setup_; }
  double period_ms() const { return 1000.0 / setup_.frame_rate_hz; }

 private:
  NetworkRig& rig_;
  RigClusterSetup setup_;
  std::filesystem::path config_;
  std::vector<std::filesystem::path> node_configs_;  ///< each node's: config_, or its relay's address as the master
  void start_nodes();
  pid_t start_node(int k, int niceness = 0);

  pid_t master_ = -1, standby_ = -1;
  std::vector<pid_t> nodes_, relays_;
};

}  // namespace zenith::testing
