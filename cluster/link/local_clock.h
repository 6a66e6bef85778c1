#pragma once
// The node's own clock as its clock synchronisation reads it (docs/cluster.md,
// "Clocks"). In a show it is the steady clock, read as it is. To rehearse a
// PC whose clock misbehaves without ever touching the machine's time
// (`zenith node --debug-clock-drift-ppm`, `--debug-clock-step-ms`), it can
// run fast or slow and jump:
//
//   local(s) = s + drift · (s − origin) + jump(s)        all in ns
//
// where s is the steady clock, drift the rate error (ppm · 10⁻⁶) and jump(s)
// is 0 or step_ns, switching every `step_every` after `origin` (ahead, then
// back, then ahead …: the clock steps without wandering off for good).
// Everything the node says or believes about the master's clock goes through
// local(); the node's timers still run on the steady clock, at steady_at() of
// the local moment they wait for, as a real PC's timers run on its own clock.
#include <chrono>
#include <cstdint>

namespace zenith::cluster {

class LocalClock {
 public:
  using Steady = std::chrono::steady_clock;

  /// How the clock misbehaves; all zero: the steady clock itself.
  struct Faults {
    double drift_ppm = 0.0;  ///< runs this fast (negative: slow)
    std::int64_t step_ns = 0;
    std::chrono::nanoseconds step_every{0};  ///< 0: no steps
    /// Whether the clock jumps at all (a step and an interval).
    bool steps() const { return step_ns != 0 && step_every.count() > 0; }
    bool any() const { return drift_ppm != 0.0 || steps(); }
  };
  /// The limits of the rehearsal (`zenith node --help`): 10 000 ppm is a
  /// clock 36 s an hour off, a hundred times a bad crystal; a step of 10 s.
  static constexpr double kMaxDriftPpm = 10000.0;
  static constexpr std::int64_t kMaxStepNs = 10'000'000'000;

  /// The steady clock as it is.
  LocalClock() = default;
  /// A clock with `faults`, equal to the steady clock at `origin`.
  LocalClock(const Faults& faults, Steady::time_point origin);

  /// What this clock reads (ns) at the steady moment `s`.
  std::int64_t read_ns(Steady::time_point s) const;
  /// The first steady moment at which this clock reads `local_ns` or later
  /// (a clock that jumped ahead over it: the moment of the jump).
  Steady::time_point steady_at(std::int64_t local_ns) const;

 private:
  /// Whether the jump is in force `since_origin_ns` after the origin.
  bool jumped(std::int64_t since_origin_ns) const;

  Faults faults_;
  std::int64_t origin_ns_ = 0;
};

}  // namespace zenith::cluster
