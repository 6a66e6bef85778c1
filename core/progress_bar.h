#pragma once
// A terminal progress bar on stderr for long operations (precompute, offline
// renders). On a terminal it redraws one line; otherwise (CI logs, pipes) it
// prints a line whenever the stage changes.
#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <string>

#include <fmt/format.h>

namespace zenith::core {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label) : label_(std::move(label)), tty_(::isatty(STDERR_FILENO) != 0) {}
  ~ProgressBar() { finish(); }

  void update(const std::string& stage, double fraction) {
    if (finished_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (tty_) {
      constexpr int kWidth = 30;
      const int filled = int(fraction * kWidth + 0.5);
      fmt::print(stderr, "\r{} [{}{}] {:3.0f}% {:6.1f} s  {:<40}", label_, std::string(std::size_t(filled), '#'),
                 std::string(std::size_t(kWidth - filled), '.'), fraction * 100.0, elapsed, stage);
      std::fflush(stderr);
    } else if (stage != last_stage_) {
      fmt::print(stderr, "{}: {:3.0f}% {:6.1f} s  {}\n", label_, fraction * 100.0, elapsed, stage);
    }
    last_stage_ = stage;
  }

  void finish() {
    if (finished_) return;
    finished_ = true;
    if (tty_ && !last_stage_.empty()) fmt::print(stderr, "\n");
  }

 private:
  std::string label_;
  bool tty_;
  bool finished_ = false;
  std::string last_stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace zenith::core
