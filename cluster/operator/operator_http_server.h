#pragma once
// The operator console's HTTP server (docs/operator.md), on the master's own
// io_context (Boost.Beast): the web page compiled into the binary at `/`,
// GET /api/status (the master's state as JSON), POST /api/command (one
// JSON command, cluster/operator/operator_command.h), GET /api/preview (the
// dome preview as PNG, while it is on) and the WebSocket /api/events that
// pushes the status whenever it changes (status_push.h). Commands are handed to the
// master on its networking thread, between frames, like console commands.
//
// Security: it listens on the loopback interface unless told otherwise; on
// any other interface it needs an operator token, which every /api request
// must then carry as "Authorization: Bearer TOKEN" (the page asks for it).
// Without a token it accepts only the Host literals 127.0.0.1, localhost and
// [::1] with its own port (no DNS rebinding: a DNS name never passes), with
// one IP literals and the names configured too, and in every case commands only with Content-Type
// application/json and an Origin, when a browser sends one, of the console
// itself (no cross-site requests).
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <nlohmann/json.hpp>

#include "cluster/link/accept_retry.h"
#include "cluster/operator/operator_command.h"
#include "cluster/operator/status_push.h"
#include "cluster/protocol/handshake.h"
#include "core/log_limiter.h"

namespace zenith::cluster {

/// Invariants: after close() nothing is accepted and every open connection is
/// closed (the master's io_context can then run out of work and return).
class OperatorHttpServer {
 public:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;
  using Response = boost::beast::http::response<boost::beast::http::string_body>;

  struct Options {
    std::string host = "127.0.0.1";     ///< address to listen on; anything but a loopback address needs `token`
    std::uint16_t port = 0;             ///< 0: any free port (see port())
    std::optional<SharedSecret> token;  ///< when set, every /api request must carry it
    /// With a token, the host names (besides the loopback and IP literals) the
    /// console may be reached by (`--operator-name`): no other Host is served.
    std::vector<std::string> names;
  };
  struct Handlers {
    /// The master's status (GET /api/status).
    std::function<nlohmann::json()> status;
    /// Applies a command from `peer` and returns the reply; throws (its
    /// message is the error) when the command is refused.
    std::function<std::string(const OperatorCommand& command, const std::string& peer)> command;
    /// The dome preview as the bytes of a PNG file (GET /api/preview); nullopt
    /// while it is off or before the first thumbnails. May be empty: no preview.
    std::function<std::optional<std::string>()> preview;
  };

  /// The most connections at once, and from one address; a new one closes
  /// the oldest that waits for a request (header timeout 5 s), so a client
  /// that opens connections and sends nothing cannot lock anyone out.
  static constexpr std::size_t kMaxConnections = 32;
  static constexpr std::size_t kMaxConnectionsPerAddress = 8;

  OperatorHttpServer(boost::asio::io_context& io, Options options, Handlers handlers);
  OperatorHttpServer(const OperatorHttpServer&) = delete;
  OperatorHttpServer& operator=(const OperatorHttpServer&) = delete;

  /// Listens. Throws std::runtime_error when the address is not a numeric IP,
  /// the port cannot be bound, or the address is not a loopback one and there
  /// is no token.
  void start();
  /// The port listened on (after start()).
  std::uint16_t port() const { return port_; }
  /// "http://127.0.0.1:8080/".
  std::string url() const;
  /// Stops listening and closes every connection.
  void close();

  /// The reply to one request from `peer` (no socket: the tests call it).
  Response respond(const Request& request, const std::string& peer) const;
  /// Why a WebSocket upgrade request may not become a status push (the
  /// response to send), or nullopt; then `authenticated` says whether it
  /// carried the token (or none is needed) — else its first message must.
  std::optional<Response> refuse_push(const Request& request, bool& authenticated) const;

 private:
  struct Session;
  void accept();
  /// Whether a connection from `peer` may be served: closes the oldest idle
  /// one when the limits are reached; false when none is idle.
  bool make_room_for(const std::string& peer);
  /// Why the request may not be served (the response to send), or nullopt.
  std::optional<Response> refuse(const Request& request) const;
  /// The Host rule: a loopback literal (127.0.0.1, localhost, [::1]) with the
  /// listening port; with a token also an IP literal or a configured name.
  bool host_allowed(std::string_view host) const;
  /// The Host and Origin rules (every request, WebSockets too).
  std::optional<Response> refuse_foreign(const Request& request) const;
  /// The token rule: the 401 for a missing or wrong "Authorization: Bearer", or nullopt.
  std::optional<Response> refuse_without_token(const Request& request) const;

  boost::asio::io_context& io_;
  Options options_;
  Handlers handlers_;
  bool loopback_ = true;
  std::uint16_t port_ = 0;
  std::optional<boost::asio::ip::tcp::acceptor> acceptor_;
  std::list<std::weak_ptr<Session>> sessions_;
  StatusPush push_;
  AcceptRetry accept_retry_;
  core::LogLimiter refusals_;
  bool closed_ = false;
};

}  // namespace zenith::cluster
