#pragma once
// Where a frame's time goes, pass by pass (RenderOptions::time_passes): each
// GL command sequence is bracketed by glFinish and timed by the wall clock,
// as is each CPU step; the times are summed per name over the frame's bands
// and groups. (GL_TIME_ELAPSED queries are no use here: Mesa's llvmpipe, which
// runs compute dispatches on the CPU, reports microseconds for passes that
// take milliseconds.) Finishing every pass serialises the frame, so a timed
// frame can be a little slower than an untimed one; the split is what it is for.
#include <chrono>
#include <map>
#include <string>

namespace zenith::render {

class PassTimer {
 public:
  explicit PassTimer(bool enabled) : enabled_(enabled) {}
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  /// Runs `commands` (GL calls) and adds their GPU time to `name` [ms].
  template <class F>
  void gpu(const std::string& name, F&& commands) {
    if (!enabled_) return commands();
    begin_gpu();
    commands();
    ms_[name] += end_gpu_ms();
  }
  /// Runs `work` (CPU, may end with a blocking GL read) and adds its wall time to `name` [ms].
  template <class F>
  void cpu(const std::string& name, F&& work) {
    if (!enabled_) return work();
    const auto start = std::chrono::steady_clock::now();
    work();
    ms_[name] += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  const std::map<std::string, double>& milliseconds() const { return ms_; }

 private:
  void begin_gpu();
  double end_gpu_ms();
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::map<std::string, double> ms_;
};

}  // namespace zenith::render
