#include "cluster/launcher/launcher_signals.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

namespace zenith::app {

namespace {

constexpr int kForwarded[3] = {SIGINT, SIGTERM, SIGHUP};
/// The signal a handler noted (a handler may only touch such a variable).
volatile std::sig_atomic_t noted_signal = 0;

extern "C" void note_signal(int signal) { noted_signal = signal; }

}  // namespace

void mark_children_as_launched() { ::setenv(kLauncherPidVariable, std::to_string(::getpid()).c_str(), 1); }

void die_with_launcher() {
  const char* value = std::getenv(kLauncherPidVariable);
  if (value == nullptr || *value == '\0') return;
  const long launcher = std::strtol(value, nullptr, 10);
  ::unsetenv(kLauncherPidVariable);  // not for this process's own children
  if (::prctl(PR_SET_PDEATHSIG, SIGTERM) != 0) spdlog::warn("cannot ask for SIGTERM when the launcher dies");
  // The launcher may have died before the prctl: then no signal would come.
  if (static_cast<long>(::getppid()) != launcher) {
    spdlog::error("the launcher (pid {}) is gone: exiting", launcher);
    std::exit(1);
  }
}

ForwardedSignals::ForwardedSignals() {
  noted_signal = 0;
  struct sigaction action {};
  action.sa_handler = note_signal;
  sigemptyset(&action.sa_mask);
  for (int i = 0; i < 3; ++i) ::sigaction(kForwarded[i], &action, &previous_[i]);
}

ForwardedSignals::~ForwardedSignals() {
  for (int i = 0; i < 3; ++i) ::sigaction(kForwarded[i], &previous_[i], nullptr);
}

int ForwardedSignals::take() {
  const int signal = noted_signal;
  noted_signal = 0;
  return signal;
}

ReadyPipe::ReadyPipe() {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot make the master's readiness pipe");
  read_ = fds[0];
  write_ = fds[1];
  ::fcntl(read_, F_SETFD, FD_CLOEXEC);  // no child holds the read end
}

ReadyPipe::~ReadyPipe() {
  close_write_end();
  if (read_ >= 0) ::close(read_);
}

void ReadyPipe::close_write_end() {
  if (write_ >= 0) ::close(write_);
  write_ = -1;
}

std::optional<bool> ReadyPipe::poll_once(std::chrono::milliseconds timeout) {
  pollfd p{read_, POLLIN, 0};
  const int r = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (r <= 0) return std::nullopt;  // nothing yet (or a signal: the caller checks)
  char byte = 0;
  const ssize_t n = ::read(read_, &byte, 1);
  if (n < 0 && errno == EINTR) return std::nullopt;
  return n == 1;
}

void signal_ready(int fd) {
  const char byte = 'L';
  [[maybe_unused]] const ssize_t n = ::write(fd, &byte, 1);
  ::close(fd);
}

NodesEndedVerdict after_nodes_ended(bool all_exited_cleanly, std::chrono::milliseconds since) {
  return all_exited_cleanly && since < kMasterExitGrace ? NodesEndedVerdict::wait_for_master
                                                        : NodesEndedVerdict::nodes_failed;
}

}  // namespace zenith::app
