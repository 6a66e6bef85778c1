#include "cluster/link/accept_retry.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include <boost/asio/error.hpp>

namespace zenith::cluster {

AcceptRetry::AcceptRetry(boost::asio::io_context& io, std::string what) : timer_(io), what_(std::move(what)) {}

void AcceptRetry::failed(const boost::system::error_code& ec, std::function<void()> rearm) {
  if (cancelled_ || ec == boost::asio::error::operation_aborted) return;  // the acceptor was closed
  if (const std::optional<std::string> more = log_.admit(core::LogLimiter::Clock::now()))
    spdlog::warn("master: {}: accept failed: {}; accepting again in {} ms{}", what_, ec.message(), delay_.count(),
                 *more);
  timer_.expires_after(delay_);
  delay_ = std::min(delay_ * 2, kMaxDelay);
  timer_.async_wait([this, rearm = std::move(rearm)](const boost::system::error_code& e) {
    if (!e && !cancelled_) rearm();
  });
}

void AcceptRetry::cancel() {
  cancelled_ = true;
  timer_.cancel();
}

}  // namespace zenith::cluster
