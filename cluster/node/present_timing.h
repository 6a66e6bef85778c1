#pragma once
// How a node's render thread meets a scheduled frame's moment (docs/cluster.md,
// "Presenting on time"). The networking thread hands the present over a little
// before the moment (present_handoff() in present_schedule.h); the render
// thread sleeps until the moment on the kernel's clock and presents — one
// thread's wake-up at the moment instead of two (the networking thread's
// timer, then the render thread's queue).
//
// On a busy machine (several nodes on one PC, the rig's two cores, another
// output's renderer still drawing) a thread that wakes at normal priority
// waits for a core behind whatever runs there: milliseconds between one
// projector's present and another's. For the sleep and the present (a swap
// queued, or the frame files renamed: well under a millisecond of work) the
// thread therefore runs SCHED_FIFO, which the kernel runs the moment its timer
// fires; it renders at its normal priority. SCHED_FIFO needs CAP_SYS_NICE or
// an RLIMIT_RTPRIO of at least kPresentFifoPriority: without either the
// presents run at normal priority, said once in the log.
#include <chrono>
#include <string>

namespace zenith::cluster {

/// Low among real-time priorities (1–99): above every normal thread, below
/// the kernel's own real-time threads and audio servers.
inline constexpr int kPresentFifoPriority = 10;

/// Sleeps until `moment` of the steady clock (CLOCK_MONOTONIC, absolute:
/// no drift from computing a duration first); returns at once if it passed.
void sleep_until_moment(std::chrono::steady_clock::time_point moment);

class PresentPriority {
 public:
  /// `realtime`: the configuration's timing.present_priority is "realtime";
  /// `node_name` names the node in the log line.
  PresentPriority(bool realtime, std::string node_name);

  /// While alive, the thread that made it runs SCHED_FIFO at
  /// kPresentFifoPriority (when wanted and allowed), with
  /// SCHED_RESET_ON_FORK (threads it starts meanwhile run normally); then its
  /// own policy again.
  class Raised {
   public:
    Raised(Raised&& other) noexcept;
    Raised(const Raised&) = delete;
    Raised& operator=(const Raised&) = delete;
    Raised& operator=(Raised&&) = delete;
    ~Raised();
    /// Whether the thread runs SCHED_FIFO now.
    bool realtime() const { return raised_; }

   private:
    friend class PresentPriority;
    Raised() = default;
    bool raised_ = false;
    int old_policy_ = 0;
    int old_priority_ = 0;
  };
  [[nodiscard]] Raised raise();

  /// False once the kernel refused SCHED_FIFO (or when not wanted).
  bool realtime_possible() const { return wanted_ && !refused_; }

 private:
  bool wanted_;
  bool refused_ = false;
  std::string node_name_;
};

}  // namespace zenith::cluster
