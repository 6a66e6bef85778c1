#pragma once
// The operator console's status pushes (docs/operator.md, "Status pushes"): a
// WebSocket at /api/events (Boost.Beast, on the master's io_context) over which
// the master sends the status of GET /api/status, as one text message,
// whenever it changes — checked every kPushInterval, so at most ten messages
// a second — and once on connecting. The page uses it and falls back to
// polling /api/status when it cannot connect or the connection drops.
//
// Security: the HTTP server checks Host and Origin before it hands a
// connection over (operator_http_server.h). With an operator token, a
// connection whose upgrade request carried no "Authorization: Bearer TOKEN"
// (a browser cannot set that header on a WebSocket) must send
// {"token": "TOKEN"} as its first message within kTokenWait; until then it
// is sent nothing, and a wrong token closes it.
#include <chrono>
#include <cstddef>
#include <functional>
#include <list>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <nlohmann/json.hpp>

#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

/// Invariants: only authenticated connections are sent anything; each is
/// sent the latest status once (a status that changes while a message is
/// being written replaces the one waiting); after close() nothing is
/// accepted, the timer stops and every connection is closed.
class StatusPush {
 public:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;

  /// How often the status is compared with the last one pushed.
  static constexpr std::chrono::milliseconds kPushInterval{100};
  /// How long a connection may take to send the token.
  static constexpr std::chrono::seconds kTokenWait{10};
  /// The most authenticated WebSocket connections at once; more are refused (HTTP 503).
  static constexpr std::size_t kMaxConnections = 16;
  /// The most connections waiting for their token (with a token only); a new
  /// one closes the oldest, so connections without the token never take the
  /// slots of the operator's pages.
  static constexpr std::size_t kMaxWaitingForToken = 4;
  /// The largest message a client may send (the token message).
  static constexpr std::size_t kMaxClientMessageBytes = 4096;

  /// `status`: the master's status (called on the io_context's thread).
  StatusPush(boost::asio::io_context& io, std::function<nlohmann::json()> status, std::optional<SharedSecret> token);
  StatusPush(const StatusPush&) = delete;
  StatusPush& operator=(const StatusPush&) = delete;

  /// Whether another connection may be accepted: an authenticated one while
  /// fewer than kMaxConnections are; one waiting for its token always (the
  /// oldest waiting is closed past kMaxWaitingForToken).
  bool has_room(bool authenticated);
  /// Completes the WebSocket handshake of `request` (an upgrade to
  /// /api/events the HTTP server checked) on `stream`; `authenticated`: no
  /// token is needed, or the request carried it.
  void accept(boost::beast::tcp_stream stream, const Request& request, bool authenticated, std::string peer);
  /// Stops pushing and closes every connection.
  void close();

  /// Whether `given` is the token (constant time). False without a token.
  bool token_matches(std::string_view given) const;

 private:
  struct Connection;
  /// Starts the timer unless it runs.
  void schedule();
  /// Compares the status with the last pushed and sends it when it changed;
  /// closes connections that did not send the token in time.
  void tick();
  /// Authenticated connections that are open (or opening).
  std::size_t authenticated_count() const;
  /// The status now, as the text a message carries.
  std::string status_text() const;

  boost::asio::io_context& io_;
  std::function<nlohmann::json()> status_;
  std::optional<SharedSecret> token_;
  boost::asio::steady_timer timer_;
  bool timer_running_ = false;
  bool closed_ = false;
  std::string last_;  ///< the status last pushed
  std::list<std::weak_ptr<Connection>> connections_;
};

}  // namespace zenith::cluster
