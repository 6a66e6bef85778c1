#pragma once
// How a link to the master ends, as the exit code of the process that held it
// (`zenith node`, and a standby master while it follows; docs/cluster.md).
namespace zenith::cluster {

/// Exit codes of Node::run (and of `zenith node`), and of a following standby.
enum NodeExit : int {
  kNodeExitDone = 0,     ///< the master said Goodbye (show over), or SIGINT/SIGTERM
  kNodeExitFailed = 1,   ///< rendering or writing failed
  kNodeExitRefused = 2,  ///< the master refused us (Reject), or failed to prove the secret
  /// The master could not be reached within the connect timeout, or a lost
  /// connection could not be re-established within the reconnect time.
  kNodeExitMasterLost = 3,
};

}  // namespace zenith::cluster
