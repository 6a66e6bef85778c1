#include "cluster/node/present_timing.h"

#include <sched.h>
#include <spdlog/spdlog.h>
#include <time.h>

#include <algorithm>
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

WakeMargin::WakeMargin(Duration largest) : largest_(std::max(largest, kSmallest)) {}

WakeMargin::Duration WakeMargin::margin() const {
  if (recorded_ == 0) return largest_;
  const std::size_t held = std::min(recorded_, kWindow);
  const Duration latest = *std::max_element(lateness_.begin(), lateness_.begin() + static_cast<std::ptrdiff_t>(held));
  return std::clamp(latest + kHeadroom, kSmallest, largest_);
}

void WakeMargin::record(Duration lateness) {
  lateness_[recorded_ % kWindow] = std::max(lateness, Duration::zero());
  ++recorded_;
}

MomentWake wait_for_moment(std::chrono::steady_clock::time_point moment, WakeMargin& margin) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point asked = moment - margin.margin();
  if (const Clock::time_point now = Clock::now(); now >= moment) return {asked, now};
  sleep_until_moment(asked);
  const Clock::time_point woke = Clock::now();
  margin.record(woke - asked);
  // Yielding, not spinning flat out: a real-time thread yields to another
  // node's present woken on the same core (several nodes on one machine), a
  // normal one to the machine's other threads; each is back within microseconds.
  while (Clock::now() < moment) sched_yield();
  return {asked, woke};
}

PresentPriority::PresentPriority(bool realtime, std::string node_name)
    : wanted_(realtime), node_name_(std::move(node_name)) {}

PresentPriority::Raised PresentPriority::raise() {
  Raised raised;
  if (!realtime_possible()) return raised;
  // pid 0: the calling thread (Linux schedules threads).
  raised.old_policy_ = sched_getscheduler(0);
  sched_param old{};
  if (raised.old_policy_ < 0 || sched_getparam(0, &old) != 0) return raised;
  raised.old_priority_ = old.sched_priority;
  const int policy = raised.old_policy_ & ~SCHED_RESET_ON_FORK;
  if (policy == SCHED_FIFO || policy == SCHED_RR) return raised;  // already real-time
  // SCHED_RESET_ON_FORK: a thread started meanwhile (a driver's worker, a
  // log's) must not inherit the real-time policy and run every frame at it.
  sched_param fifo{};
  fifo.sched_priority = kPresentFifoPriority;
  if (sched_setscheduler(0, SCHED_FIFO | SCHED_RESET_ON_FORK, &fifo) != 0) {
    const int error = errno;
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
  sched_setscheduler(0, old_policy_, &old);  // lowering is always allowed
}

}  // namespace zenith::cluster
