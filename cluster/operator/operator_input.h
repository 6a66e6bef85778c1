#pragma once
// Where the master's operator commands come from (docs/shows.md, "Playback"):
// lines on standard input (`--console`) and on a TCP control socket at
// 127.0.0.1:PORT (`--control-port`, `zenith show control`). This class only
// carries lines: what a command does is the master's (the handler).
//
// The control socket has no token (it is for scripts on the master's machine;
// docs/operator.md, "Threat model"), so it keeps web pages and stray clients
// out by its limits: a first line that looks like HTTP (a browser's request,
// even a no-cors text/plain POST) closes the connection before anything is
// run; lines are at most kMaxLineBytes; a client silent for `idle_timeout`
// is closed; at most kMaxClients at once (the oldest is closed for a new
// one, so a stray client never locks the operator out); accept failures
// (EMFILE) back off and re-arm (AcceptRetry).
#include <chrono>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/streambuf.hpp>

#include "cluster/link/accept_retry.h"
#include "core/log_limiter.h"

namespace zenith::cluster {

/// Reads command lines on the master's io_context and hands each to the
/// handler on that thread. Console replies go to the log; each control-socket
/// client gets one reply line per command line. Invariant: after close() no
/// line is handled and no client is served again.
class OperatorInput {
 public:
  /// Handles one command line (as read, without the newline); returns the
  /// reply line, empty for none.
  using CommandHandler = std::function<std::string(std::string line)>;

  /// The longest command line (the newline not counted); a longer one closes the client.
  static constexpr std::size_t kMaxLineBytes = 1024;
  /// The most control clients at once; a new one closes the oldest.
  static constexpr std::size_t kMaxClients = 8;
  /// A control client that sends no complete line for this long is closed.
  static constexpr std::chrono::seconds kIdleTimeout{60};

  OperatorInput(boost::asio::io_context& io, CommandHandler on_command,
                std::chrono::milliseconds idle_timeout = kIdleTimeout);
  OperatorInput(const OperatorInput&) = delete;
  OperatorInput& operator=(const OperatorInput&) = delete;

  /// Starts reading standard input (a duplicate of its descriptor); at its end
  /// the show goes on without a console.
  void read_console();
  /// Listens on 127.0.0.1:`port` (0: any free port, see control_port()).
  /// Throws std::runtime_error when the port cannot be bound.
  void listen_for_control(std::uint16_t port);
  std::uint16_t control_port() const { return control_port_; }
  /// Stops reading and listening and closes every control client.
  void close();

  /// Whether `line`, the first line of a connection, is an HTTP request line
  /// ("POST / HTTP/1.1"): a web page's request, never a command.
  static bool looks_like_http(std::string_view line);

 private:
  struct ControlClient;
  void read_console_line();
  void accept_control();
  void serve_control(const std::shared_ptr<ControlClient>& client);
  void drop(const std::shared_ptr<ControlClient>& client, const std::string& why);

  boost::asio::io_context& io_;
  CommandHandler on_command_;
  std::chrono::milliseconds idle_timeout_;
  std::optional<boost::asio::posix::stream_descriptor> console_in_;
  boost::asio::streambuf console_buffer_;
  std::optional<boost::asio::ip::tcp::acceptor> control_acceptor_;
  std::uint16_t control_port_ = 0;
  AcceptRetry accept_retry_;
  core::LogLimiter refusals_;
  std::list<std::shared_ptr<ControlClient>> clients_;  ///< oldest first
  bool closed_ = false;
};

}  // namespace zenith::cluster
