#pragma once
// What an acceptor does when accept() fails (docs/operator.md, "Threat
// model"). Out of file descriptors (EMFILE, ENFILE) or memory, the kernel
// keeps the connection queued and every accept fails again at once: an
// acceptor that re-arms at once spins and logs a line per try (a million lines
// in 4 s), one that gives up never accepts again. AcceptRetry re-arms after a
// back-off — 10 ms doubling to 1 s while the failures go on — and logs at most
// one line a second, with the count of those held back.
#include <chrono>
#include <functional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/system/error_code.hpp>

#include "core/log_limiter.h"

namespace zenith::cluster {

/// Invariant: after cancel() the re-arm callback is never called.
class AcceptRetry {
 public:
  static constexpr std::chrono::milliseconds kFirstDelay{10};
  static constexpr std::chrono::milliseconds kMaxDelay{1000};

  /// `what`: the acceptor, for the log ("operator console", "control socket").
  AcceptRetry(boost::asio::io_context& io, std::string what);

  /// accept() failed with `ec`: logs (rate-limited) and calls `rearm` after the current delay.
  void failed(const boost::system::error_code& ec, std::function<void()> rearm);
  /// accept() succeeded: the next failure waits kFirstDelay again.
  void succeeded() { delay_ = kFirstDelay; }
  void cancel();
  /// Failures seen in all (tests).
  std::uint64_t failures() const { return log_.total(); }

 private:
  boost::asio::steady_timer timer_;
  std::string what_;
  std::chrono::milliseconds delay_ = kFirstDelay;
  core::LogLimiter log_;
  bool cancelled_ = false;
};

}  // namespace zenith::cluster
