#pragma once
// How a link to the master ends, as the exit code of the process that held it
// (`zenith node`, and a standby master while it follows; docs/cluster.md).
#include <boost/asio/signal_set.hpp>
#include <boost/system/error_code.hpp>

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

/// The end of a process that holds a link: its exit code (NodeExit), decided
/// by the first finish().
struct LinkEnd {
  int exit_code = kNodeExitDone;
  bool finished = false;

  /// Records `code` and cancels the wait for SIGINT/SIGTERM on `signals`;
  /// false, changing nothing, when the process has finished already (the
  /// caller then stops nothing more).
  bool finish(int code, boost::asio::signal_set& signals) {
    if (finished) return false;
    finished = true;
    exit_code = code;
    boost::system::error_code ec;
    signals.cancel(ec);
    return true;
  }
};

}  // namespace zenith::cluster
