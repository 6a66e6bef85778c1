#pragma once
// How a node's render thread meets a scheduled frame's moment (docs/cluster.md,
// "Presenting on time"). The networking thread hands the present over a little
// before the moment (present_handoff() in present_schedule.h); the render
// thread sleeps until just before the moment on the kernel's clock, waits the
// rest awake (WakeMargin) and presents — one thread's wake-up at the moment
// instead of two (the networking thread's timer, then the render thread's
// queue).
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
#include <array>
#include <chrono>
#include <cstddef>
#include <string>

namespace zenith::cluster {

/// Low among real-time priorities (1–99): above every normal thread, below
/// the kernel's own real-time threads and audio servers.
inline constexpr int kPresentFifoPriority = 10;

/// Sleeps until `moment` of the steady clock (CLOCK_MONOTONIC, absolute:
/// no drift from computing a duration first); returns at once if it passed.
void sleep_until_moment(std::chrono::steady_clock::time_point moment);

/// How long before a moment the render thread asks to wake, learnt from how
/// late its wake-ups came. A thread's timer fires late when its core is idle:
/// the core must leave a deep sleep state, or — in a virtual machine — the
/// hypervisor must run the halted virtual CPU again. On the rig's VM the
/// kernel's own timer events showed a sleeping present's timer interrupt
/// 0.5–2 ms late a few times in a hundred frames with the scheduler then
/// prompt (0.14 ms at most): a projector a millisecond or two behind the
/// others. The thread therefore wakes early by the margin and waits the rest
/// awake, on a core already running.
///
/// The margin is the latest of the last kWindow wake-ups plus kHeadroom,
/// within [kSmallest, largest]: on a machine that wakes in tens of
/// microseconds it waits awake a quarter of a millisecond a frame; on one that
/// wakes late up to `largest` (half the handoff: 2 ms a frame below 125 Hz).
/// A long stall — the VM stopped — widens it for kWindow frames only.
class WakeMargin {
 public:
  using Duration = std::chrono::steady_clock::duration;
  static constexpr std::size_t kWindow = 256;
  static constexpr Duration kSmallest = std::chrono::microseconds(250);
  static constexpr Duration kHeadroom = std::chrono::microseconds(100);

  /// `largest`: the most the thread may wait awake before a present. Until the
  /// first wake-up is recorded the margin is `largest`.
  explicit WakeMargin(Duration largest);
  Duration margin() const;
  /// How late a wake-up came after the time asked (negative counts as 0).
  void record(Duration lateness);

 private:
  Duration largest_;
  std::array<Duration, kWindow> lateness_{};
  std::size_t recorded_ = 0;  ///< all time; the window holds the last kWindow
};

/// When the thread asked to wake before a moment, and when it did.
struct MomentWake {
  std::chrono::steady_clock::time_point asked;
  std::chrono::steady_clock::time_point woke;
};
/// Sleeps until `moment` less the margin, records how late that wake-up came
/// in `margin`, then waits awake (yielding) until the moment; returns at once
/// (having slept nothing) if the moment has passed.
MomentWake wait_for_moment(std::chrono::steady_clock::time_point moment, WakeMargin& margin);

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
