#include "tests/rig/wake_probe.h"

#include "cluster/node/present_timing.h"

namespace zenith::testing {

WakeProbe::WakeProbe(std::chrono::microseconds period, std::size_t max_samples) {
  lateness_ms_.reserve(max_samples);
  thread_ = std::thread([this, period, max_samples] { run(period, max_samples); });
}

WakeProbe::~WakeProbe() { stop(); }

void WakeProbe::stop() {
  stopping_ = true;
  if (thread_.joinable()) thread_.join();
}

void WakeProbe::run(std::chrono::microseconds period, std::size_t max_samples) {
  cluster::PresentPriority priority(/*realtime=*/true, "wake probe");
  const cluster::PresentPriority::Raised raised = priority.raise();
  realtime_ = raised.realtime();
  auto moment = std::chrono::steady_clock::now();
  while (!stopping_ && lateness_ms_.size() < max_samples) {
    moment += period;
    cluster::sleep_until_moment(moment);
    const auto woke = std::chrono::steady_clock::now();
    lateness_ms_.push_back(std::chrono::duration<double, std::milli>(woke - moment).count());
    // Held past the next moment too: one sample for the stall, not one per period it lasted.
    if (woke - moment > period) moment = woke;
  }
}

}  // namespace zenith::testing
