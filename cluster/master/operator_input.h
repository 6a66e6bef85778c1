#pragma once
// Where the master's operator commands come from (docs/shows.md, "Playback"):
// lines on standard input (`--console`) and on a TCP control socket at
// 127.0.0.1:PORT (`--control-port`, `zenith show control`). This class only
// carries lines: what a command does is the master's (the handler).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/streambuf.hpp>

namespace zenith::cluster {

/// Reads command lines on the master's io_context and hands each to the
/// handler on that thread. Console replies go to the log; each control-socket
/// client gets one reply line per command line, and is dropped for a line of
/// more than 1024 bytes. Invariant: after close() no line is handled and no
/// client is served again.
class OperatorInput {
 public:
  /// Handles one command line (as read, without the newline); returns the
  /// reply line, empty for none.
  using CommandHandler = std::function<std::string(std::string line)>;

  OperatorInput(boost::asio::io_context& io, CommandHandler on_command);
  OperatorInput(const OperatorInput&) = delete;
  OperatorInput& operator=(const OperatorInput&) = delete;

  /// Starts reading standard input (a duplicate of its descriptor); at its end
  /// the show goes on without a console.
  void read_console();
  /// Listens on 127.0.0.1:`port`. Throws std::runtime_error when the port cannot be bound.
  void listen_for_control(std::uint16_t port);
  /// Stops reading and listening (the master is stopping).
  void close();

 private:
  struct ControlClient;
  void read_console_line();
  void accept_control();
  void serve_control(std::shared_ptr<ControlClient> client);

  boost::asio::io_context& io_;
  CommandHandler on_command_;
  std::optional<boost::asio::posix::stream_descriptor> console_in_;
  boost::asio::streambuf console_buffer_;
  std::optional<boost::asio::ip::tcp::acceptor> control_acceptor_;
  bool closed_ = false;
};

}  // namespace zenith::cluster
