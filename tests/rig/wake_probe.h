#pragma once
// How promptly this machine wakes a real-time thread at a moment it asked
// for, measured while a rig test runs. A node presents by sleeping until the
// frame's moment at SCHED_FIFO (cluster/node/present_timing.h), so two nodes'
// presents of one frame can be no closer together than the machine wakes
// them: on this project's VM the kernel wakes such a thread 0.04 ms late at
// the 90th percentile, on a shared CI machine with a noisy neighbour it can be
// milliseconds. The probe does what a node's present does — the same policy
// and priority, clock_nanosleep to an absolute moment — every `period`, with
// no work around it, so what it sees is the machine's share of the nodes'
// spread and none of zenith's.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

namespace zenith::testing {

class WakeProbe {
 public:
  /// Starts the probe thread: a sample every `period`, at most `max_samples`.
  explicit WakeProbe(std::chrono::microseconds period = std::chrono::milliseconds(5), std::size_t max_samples = 120000);
  ~WakeProbe();
  WakeProbe(const WakeProbe&) = delete;
  WakeProbe& operator=(const WakeProbe&) = delete;

  /// Stops the probe (idempotent); the samples are then final.
  void stop();
  /// Whether the probe ran SCHED_FIFO at the nodes' present priority (false:
  /// the kernel refused, and its samples say nothing about a node's presents).
  bool realtime() const { return realtime_; }
  /// How late it woke, each sample (ms); after stop().
  const std::vector<double>& lateness_ms() const { return lateness_ms_; }

 private:
  void run(std::chrono::microseconds period, std::size_t max_samples);

  std::atomic<bool> stopping_{false};
  bool realtime_ = false;
  std::vector<double> lateness_ms_;
  std::thread thread_;
};

}  // namespace zenith::testing
