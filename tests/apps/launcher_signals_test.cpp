// When `zenith cluster` counts a show as ended early (cluster/launcher/launcher_signals.h):
// its nodes exit 0 on the master's Goodbye a moment
// before the master itself exits. The launcher once polled the master every
// 200 ms and, finding every node gone in between, reported "the nodes exited
// before the show ended" (1 normal run in 12).
#include "cluster/launcher/launcher_signals.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

namespace zenith::app {
namespace {

using std::chrono::milliseconds;

TEST(LauncherSignals, NodesThatSaidGoodbyeLeaveTheMasterTimeToExit) {
  EXPECT_EQ(after_nodes_ended(true, milliseconds(0)), NodesEndedVerdict::wait_for_master);
  EXPECT_EQ(after_nodes_ended(true, milliseconds(200)), NodesEndedVerdict::wait_for_master)
      << "the old launcher's 200 ms poll: the master's exit is moments away";
  EXPECT_EQ(after_nodes_ended(true, kMasterExitGrace - milliseconds(1)), NodesEndedVerdict::wait_for_master);
  EXPECT_EQ(after_nodes_ended(true, kMasterExitGrace), NodesEndedVerdict::nodes_failed)
      << "a master that lingers is stopped";
  EXPECT_EQ(after_nodes_ended(false, milliseconds(0)), NodesEndedVerdict::nodes_failed)
      << "a node that failed: the show cannot go on here";
}

TEST(LauncherSignals, SignalsAreNotedNotActedUponAndTheOldHandlersComeBack) {
  struct sigaction before {};
  ::sigaction(SIGHUP, nullptr, &before);
  {
    ForwardedSignals signals;
    EXPECT_EQ(signals.take(), 0);
    ::raise(SIGHUP);  // would end this process without the handler
    EXPECT_EQ(signals.take(), SIGHUP);
    EXPECT_EQ(signals.take(), 0) << "taken once";
    ::raise(SIGINT);
    EXPECT_EQ(signals.take(), SIGINT);
  }
  struct sigaction after {};
  ::sigaction(SIGHUP, nullptr, &after);
  EXPECT_EQ(after.sa_handler, before.sa_handler);
}

TEST(LauncherSignals, TheReadyPipeSaysWhetherTheMasterListensOrEndedWithoutIt) {
  {
    ReadyPipe ready;
    const pid_t child = ::fork();
    if (child == 0) {
      signal_ready(ready.write_end());
      ::_exit(0);
    }
    ready.close_write_end();
    EXPECT_TRUE(ready.wait([] { return false; }));
    ::waitpid(child, nullptr, 0);
  }
  {
    ReadyPipe ready;
    const pid_t child = ::fork();
    if (child == 0) ::_exit(1);  // a master that could not bind: it never writes
    ready.close_write_end();
    EXPECT_FALSE(ready.wait([] { return false; }));
    ::waitpid(child, nullptr, 0);
  }
}

}  // namespace
}  // namespace zenith::app
