#pragma once
// What ties a local cluster's processes to its launcher (`zenith cluster`,
// `zenith show render --cluster`; docs/cluster.md, "Commands"):
//
// - children die with it: the launcher puts its pid in ZENITH_LAUNCHER_PID,
//   and a master, standby or node started so asks the kernel for SIGTERM when
//   its parent dies (PR_SET_PDEATHSIG), so a launcher killed with kill -9
//   leaves no master holding the port and no node reconnecting for minutes;
// - SIGINT, SIGTERM and SIGHUP to the launcher are logged and forwarded to
//   the master (whose Goodbye ends the nodes), never ignored;
// - the master tells the launcher through a pipe that it listens, and the
//   nodes are started only then: a master that cannot bind its port (another
//   cluster's master holds it) ends the run before any node could join that
//   other master.
#include <sys/types.h>

#include <chrono>
#include <csignal>
#include <optional>

namespace zenith::app {

/// The environment variable naming the launcher's pid for its children.
inline constexpr const char* kLauncherPidVariable = "ZENITH_LAUNCHER_PID";

/// In the launcher, before it starts children: they will die with it.
void mark_children_as_launched();
/// In a child (`zenith master`, `zenith node`): when ZENITH_LAUNCHER_PID is
/// set, SIGTERM on the launcher's death; exits at once (status 1) when the
/// launcher is already gone (its parent is not that pid any more).
void die_with_launcher();

/// SIGINT, SIGTERM and SIGHUP noted instead of acted upon, while one lives
/// (the previous handlers come back after). One per process at a time.
class ForwardedSignals {
 public:
  ForwardedSignals();
  ~ForwardedSignals();
  ForwardedSignals(const ForwardedSignals&) = delete;
  ForwardedSignals& operator=(const ForwardedSignals&) = delete;
  /// The signal received since the last call, or 0.
  int take();

 private:
  struct sigaction previous_[3]{};
};

/// The pipe through which a child master says it listens (`--ready-fd`).
class ReadyPipe {
 public:
  ReadyPipe();
  ~ReadyPipe();
  ReadyPipe(const ReadyPipe&) = delete;
  ReadyPipe& operator=(const ReadyPipe&) = delete;
  /// The end the master writes to (inherited by the next child started).
  int write_end() const { return write_; }
  /// After the master started: no later child inherits the write end.
  void close_write_end();
  /// Waits until the master listens (true), or it ends or closes the pipe
  /// without saying so (false), or `stop()` says to give up (false).
  template <typename Stop>
  bool wait(Stop stop) {
    for (;;) {
      if (const std::optional<bool> r = poll_once(std::chrono::milliseconds(200))) return *r;
      if (stop()) return false;
    }
  }

 private:
  /// true: it listens; false: the pipe closed; nullopt: nothing within `timeout`.
  std::optional<bool> poll_once(std::chrono::milliseconds timeout);
  int read_ = -1, write_ = -1;
};

/// In the master: writes the byte that ReadyPipe::wait() expects, then closes `fd`.
void signal_ready(int fd);

/// Every local node ended while the master still runs: the nodes exit with 0
/// on the master's Goodbye, which comes just before the master's own exit, so
/// that is the end of the show unless the master lingers past this grace.
inline constexpr std::chrono::milliseconds kMasterExitGrace{10000};
enum class NodesEndedVerdict {
  wait_for_master,  ///< they said goodbye: the master's exit follows
  nodes_failed,     ///< a node failed, or the master did not follow within the grace: stop it, report
};
/// `all_exited_cleanly`: every local node ended with status 0; `since`: how
/// long ago the last one ended.
NodesEndedVerdict after_nodes_ended(bool all_exited_cleanly, std::chrono::milliseconds since);

}  // namespace zenith::app
