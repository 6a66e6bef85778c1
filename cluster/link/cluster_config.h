#pragma once
// The cluster configuration: who the master is, which nodes render which
// outputs of a viewport config, the scene, the timing of the frame barrier,
// where the shared secret comes from and where frames are written
// (docs/cluster.md, "Configuration").
//
//   {
//     "zenith_cluster": 1,
//     "name": "local-dome",
//     "master": {"host": "127.0.0.1", "port": 47100},
//     "standby": {"host": "127.0.0.1", "port": 47101},      optional: a standby master (docs/cluster.md, "Standby
//     master") "scene": "../scenes/earth-sunset.json",              relative to this file "viewports":
//     "../viewports/dome-quadrants.json",     relative to this file "timing": {"heartbeat_ms": 250,
//     "barrier_timeout_ms": 5000, "frame_rate_hz": 10,
//                "reconnect_s": 300},                       optional: a node's time to reconnect after a loss
//     "secret": {"env": "ZENITH_CLUSTER_SECRET"},          or {"file": "secret.key"}; never the secret itself
//     "tables": {"sizes": "paper", "orders": 6},           optional (default orders: kDefaultScatteringOrders)
//     "swap_group": 1,                                     optional: GLX_NV_swap_group of the nodes' windows (0: none)
//     "nodes": [{"name": "q1", "host": "127.0.0.1", "outputs": ["top-left"]}, ...],
//     "output": {"directory": "out/cluster", "format": "png"}
//   }
//
// Keys are strict; every error is a zenith::ConfigError naming the file, the
// JSON pointer of the key, the value and the allowed range, e.g.
//   local-dome.json: /timing/barrier_timeout_ms = 5: must be in [10, 600000] ms
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "atmosphere/lut/precompute_options.h"

namespace zenith::cluster {

/// The schema version this reader understands ("zenith_cluster": 1).
inline constexpr int kClusterConfigVersion = 1;
/// timing.reconnect_s when the configuration does not say (5 minutes: a
/// master restarted from its table cache is back in seconds, a rebooted
/// machine in a minute or two).
inline constexpr std::uint32_t kDefaultReconnectMs = 300000;
/// limits.max_unauthenticated_connections when the configuration does not say.
inline constexpr std::uint32_t kDefaultMaxUnauthenticatedConnections = 16;
/// The largest timing.reconnect_s (and `zenith node --reconnect-s`): a day.
inline constexpr double kMaxReconnectS = 86400.0;

/// Where a master listens and nodes connect: the active master or the standby.
struct MasterAddress {
  std::string host;        ///< a host name or address
  std::uint16_t port = 0;  ///< TCP port, in [1, 65535]
  /// "host:port", for logs.
  std::string text() const;
  bool operator==(const MasterAddress&) const = default;
};

/// The name a standby master listening at `standby` gives in its Hello:
/// "standby@HOST:PORT" (at most 64 bytes). '@' and ':' are not allowed in node
/// names, so it never names a node.
std::string standby_name(const MasterAddress& standby);

/// One render node: a process on `host` rendering `outputs` (names of outputs
/// of the viewport config).
struct ClusterNodeConfig {
  std::string name;  ///< unique; letters, digits, '-', '_', '.' (it names the node's folder of frames)
  std::string host;  ///< the machine it runs on ("127.0.0.1", "dome-pc-3"); `zenith cluster` starts the local ones
  std::vector<std::string> outputs;  ///< at least one; each output belongs to at most one node
};

/// The range of timing.frame_rate_hz: up to the fastest projectors (240 Hz).
inline constexpr double kMinFrameRateHz = 0.01;
inline constexpr double kMaxFrameRateHz = 240.0;
/// The range and default of timing.lookahead_frames: 3 frames (50 ms at 60 Hz)
/// cover a lost datagram twice over and a node's render.
inline constexpr int kMaxLookaheadFrames = 30;
inline constexpr int kDefaultLookaheadFrames = 3;
/// The largest swap_group accepted (drivers offer a few; the driver's own limit is checked on the node).
inline constexpr int kMaxSwapGroup = 64;

struct ClusterConfig {
  std::string name;               ///< the cluster's name (checked in the handshake)
  std::string source;             ///< the file it came from (messages)
  std::string master_host;        ///< where nodes connect (the master listens on it)
  std::uint16_t master_port = 0;  ///< TCP port, in [1, 65535]
  /// The standby master ("standby"): it follows the active master and takes
  /// over when that one is gone; nodes try the active master, then it.
  std::optional<MasterAddress> standby;
  std::filesystem::path scene;              ///< resolved against the config's folder
  std::filesystem::path viewports;          ///< resolved against the config's folder
  std::uint32_t heartbeat_ms = 250;         ///< each side sends a Heartbeat at least this often; 3× silent = gone
  std::uint32_t barrier_timeout_ms = 5000;  ///< a node not done with a frame within this is dropped from it
  /// The master starts frames no faster than this: the projectors' refresh
  /// rate on a live dome (60, 120 Hz), [kMinFrameRateHz, kMaxFrameRateHz].
  double frame_rate_hz = 30.0;
  /// Scheduled frames (timing.lookahead_frames, [0, kMaxLookaheadFrames]):
  /// each frame is sent this many periods before its moment and every node
  /// presents it then, waiting for no other node (docs/cluster.md, "The
  /// frame schedule"); the operator's input shows this much later. 0: the
  /// frame barrier (each frame presented once every node has rendered it).
  int lookahead_frames = kDefaultLookaheadFrames;
  /// What a node's projectors show while its link to the master is cut
  /// (timing.link_lost, "hold" or "black"), once its scheduled frames ran out:
  /// the last frame (hold), or black (docs/cluster.md, "The frame schedule").
  bool black_when_link_lost = false;
  /// A node's render thread waits for a scheduled frame's moment and presents
  /// it at real-time priority (timing.present_priority, "realtime" or
  /// "normal"; cluster/node/present_timing.h): on time however busy the PC.
  bool realtime_presents = true;
  /// Every node's windows join this swap group (GLX_NV_swap_group, bound to
  /// swap barrier 1: Quadro Sync); 0: none (render/window/swap_sync.h).
  unsigned swap_group = 0;
  /// A node that lost its connection to the master tries to be welcomed again
  /// for this long, then exits (timing.reconnect_s, [0, 86400] s; 0: it exits at once).
  std::uint32_t reconnect_ms = kDefaultReconnectMs;
  /// The shared secret: a file (resolved against the config's folder) or else
  /// the environment variable `secret_env`.
  std::optional<std::filesystem::path> secret_file;
  std::string secret_env = "ZENITH_CLUSTER_SECRET";
  /// At most this many connections to the master that have not completed
  /// the handshake (limits.max_unauthenticated_connections, [1, 4096]): a new
  /// one beyond closes the oldest (docs/cluster.md, "Threat model").
  std::uint32_t max_unauthenticated_connections = kDefaultMaxUnauthenticatedConnections;
  std::string table_sizes = "paper";  ///< atmosphere::table_size_names(): paper, twilight, small, large
  int table_orders = atmosphere::lut::kDefaultScatteringOrders;  ///< scattering orders of the tables, [1, 50]
  std::vector<ClusterNodeConfig> nodes;
  std::filesystem::path output_directory = "out/cluster";  ///< relative: to the working directory
  std::string output_format = "png";                       ///< "png" or "exr"

  /// The active master's address (master_host, master_port).
  MasterAddress master_address() const { return {master_host, master_port}; }
  /// The node with that name; nullptr when none.
  const ClusterNodeConfig* find_node(const std::string& node_name) const;
};

/// Parses a cluster config held in `config`; `source` names the file in
/// messages and relative scene, viewport and secret paths resolve against
/// `base_dir`. Also loads the viewport config to check that every node's
/// outputs exist there. Throws zenith::ConfigError.
ClusterConfig parse_cluster_config(const nlohmann::json& config, const std::string& source,
                                   const std::filesystem::path& base_dir);
/// Reads and parses a file (ConfigError "cannot open file" when unreadable).
ClusterConfig load_cluster_config(const std::filesystem::path& path);

/// How long a peer may stay silent before it counts as gone (docs/cluster.md,
/// "Join, rejoin and failures"): 3 heartbeats, but at least 10 s. A loaded
/// machine — every core rendering on llvmpipe, table sets being verified and
/// stored — can starve a networking thread for seconds; a peer that crashes is
/// noticed at once anyway, because its socket closes.
inline double silence_limit_ms(std::uint32_t heartbeat_ms) {
  return 3.0 * heartbeat_ms > 10000.0 ? 3.0 * heartbeat_ms : 10000.0;
}

}  // namespace zenith::cluster
