#include "cluster/node/present_timing.h"

#include <pthread.h>
#include <sched.h>
#include <spdlog/spdlog.h>
#include <time.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace zenith::cluster {

void sleep_until_moment(std::chrono::steady_clock::time_point moment) {
  // libstdc++'s steady_clock is CLOCK_MONOTONIC on Linux.
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(moment.time_since_epoch()).count();
  if (ns <= 0) return;
  timespec at{};
  at.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  at.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &at, nullptr) == EINTR) {
  }
}

PresentPriority::PresentPriority(bool realtime, std::string node_name)
    : wanted_(realtime), node_name_(std::move(node_name)) {}

PresentPriority::Raised PresentPriority::raise() {
  Raised raised;
  if (!realtime_possible()) return raised;
  sched_param old{};
  if (pthread_getschedparam(pthread_self(), &raised.old_policy_, &old) != 0) return raised;
  raised.old_priority_ = old.sched_priority;
  if (raised.old_policy_ == SCHED_FIFO || raised.old_policy_ == SCHED_RR) return raised;  // already real-time
  sched_param fifo{};
  fifo.sched_priority = kPresentFifoPriority;
  if (const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &fifo); error != 0) {
    refused_ = true;
    spdlog::info(
        "node '{}': presents run at normal priority: the kernel refused SCHED_FIFO ({}); give the node "
        "CAP_SYS_NICE or an RLIMIT_RTPRIO of at least {} (docs/cluster.md, \"Presenting on time\"), or set "
        "timing.present_priority to \"normal\"",
        node_name_, std::strerror(error), kPresentFifoPriority);
    return raised;
  }
  raised.raised_ = true;
  return raised;
}

PresentPriority::Raised::Raised(Raised&& other) noexcept
    : raised_(std::exchange(other.raised_, false)),
      old_policy_(other.old_policy_),
      old_priority_(other.old_priority_) {}

PresentPriority::Raised::~Raised() {
  if (!raised_) return;
  sched_param old{};
  old.sched_priority = old_priority_;
  pthread_setschedparam(pthread_self(), old_policy_, &old);  // lowering is always allowed
}

}  // namespace zenith::cluster
