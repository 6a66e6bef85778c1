#pragma once
// `zenith cluster check` (docs/cluster.md, "Checking the network"): what a
// planetarium engineer runs from the master's PC before a show. It listens
// on the master's port as the master would; each node that connects (its
// service waits for masters) is authenticated as for a show, then measured
// instead of sent tables:
//
//   LinkCheck ──► the node pings over UDP at a fast rate for the duration
//                 (round trips, losses each way, its clock estimate)
//   LinkFill  ──► fill_bytes over TCP (the throughput toward the node)
//   ◄── LinkReport: what the node measured; the master adds the pings it heard
//
// then Goodbye, as at a show's end. One thread, the io_context's.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "cluster/check/link_verdict.h"
#include "cluster/link/cluster_config.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

struct LinkCheckOptions {
  ClusterConfig config;
  std::optional<std::uint16_t> port;               ///< overrides config.master.port
  std::chrono::milliseconds duration{5000};        ///< of the pings, per node
  std::chrono::microseconds ping_interval{10000};  ///< between pings (100 a second)
  std::uint64_t fill_bytes = std::uint64_t{32} << 20;
  /// How long to wait for the configured nodes to connect.
  std::chrono::milliseconds wait_for_nodes{30000};
  /// How long a node may take over its fill (a slow link reports no throughput past it).
  std::chrono::milliseconds fill_timeout{30000};
  /// Called once the port is bound (tests start their nodes then).
  std::function<void()> on_listening;
};

/// Runs the check; one measurement per configured node, in the config's
/// order. Throws std::runtime_error when the port cannot be bound (a master
/// is running: stop the show first).
std::vector<LinkMeasurement> check_links(const LinkCheckOptions& options, SharedSecret secret);

}  // namespace zenith::cluster
