#pragma once
// A standby master (docs/cluster.md, "Standby master"; `zenith master
// --standby`). It follows the active master of its cluster config: it
// connects like a node but in the standby role (docs/protocol.md, "Roles"),
// authenticated with the cluster secret, and keeps every table version the
// active master distributes and the last frames it sends (StandbyFollower).
// It listens on nothing meanwhile, so no node reaches it while the active
// master is alive. When the active master is gone — its connection closed, or
// silent past the silence limit, and one more attempt at once fails
// (TakeoverRule) — it becomes the master on its own address (Master, with
// MasterOptions::takeover): nodes that lost the active master try the listed
// masters in order, reach it, declare their cached tables and rejoin, and the
// show continues from the frame after the last one the active master sent.
#include <cstdint>
#include <memory>

#include "cluster/master/master.h"
#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

struct StandbyOptions {
  /// What the master this standby becomes runs with: the active master's
  /// options (show, frames, sun step, switches, console, …); the config must
  /// have a "standby" entry, the address it listens on after a takeover.
  /// `port` overrides the active master's port (where it follows it).
  MasterOptions master;
  /// How long to try to reach the active master at the start (it may be
  /// preparing its tables for minutes).
  std::uint32_t connect_timeout_ms = 900000;
  /// After a loss, the one more attempt that tells a dead master from a lost
  /// connection gets this long to be welcomed. Shorter than the nodes'
  /// attempt limit (3 s, attempt_timeout_ms_for()), so that with a stopped
  /// master the standby listens before the nodes turn to it.
  std::uint32_t check_attempt_ms = 2000;
  /// After a takeover the show goes on once every configured node is ready
  /// again, or after this long with those that are.
  std::uint32_t takeover_wait_ms = 10000;
};

class Standby {
 public:
  Standby(StandbyOptions options, SharedSecret secret);
  ~Standby();
  Standby(const Standby&) = delete;
  Standby& operator=(const Standby&) = delete;

  /// Follows the active master, and takes over when it is gone. Returns a
  /// NodeExit code while following: 0 when the active master ended the show
  /// (its Goodbye) or on SIGINT/SIGTERM, 1 when the active master sent what a
  /// standby cannot use, 2 when it refused the standby (wrong secret, not this
  /// cluster's standby) or failed to prove the secret, 3 when it could not be
  /// reached within the connect timeout; after a takeover, what Master::run
  /// returns. Throws when the config has no standby, and what Master::run throws.
  int run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace zenith::cluster
