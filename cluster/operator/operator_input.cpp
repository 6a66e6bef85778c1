#include "cluster/operator/operator_input.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <istream>
#include <stdexcept>

#include <unistd.h>

#include <boost/asio/read_until.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>

#include "core/strings.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::tcp;
using core::cat;

/// One control-socket client: lines in, one reply line out per command.
struct OperatorInput::ControlClient {
  tcp::socket socket;
  asio::streambuf buffer{kMaxLineBytes + 1};  ///< a line and its newline at most: read_until fails beyond
  asio::steady_timer idle;
  std::string peer;
  bool first_line = true;
  bool open = true;
  bool writing = false;  ///< a reply is going out: close() lets it finish (quit's reply)
  explicit ControlClient(tcp::socket s) : socket(std::move(s)), idle(socket.get_executor()) {
    boost::system::error_code ec;
    const tcp::endpoint remote = socket.remote_endpoint(ec);
    peer = ec ? std::string("unknown peer") : cat(remote.address().to_string(), ":", remote.port());
  }
};

OperatorInput::OperatorInput(asio::io_context& io, CommandHandler on_command, std::chrono::milliseconds idle_timeout)
    : io_(io), on_command_(std::move(on_command)), idle_timeout_(idle_timeout), accept_retry_(io, "control socket") {}

bool OperatorInput::looks_like_http(std::string_view line) {
  // METHOD SP TARGET SP HTTP/x.y: a method is a token of capitals (RFC 9110); no command is written so.
  const std::size_t space = line.find(' ');
  if (space == 0 || space == std::string_view::npos) return false;
  if (!std::all_of(line.begin(), line.begin() + static_cast<std::ptrdiff_t>(space),
                   [](char c) { return c >= 'A' && c <= 'Z'; }))
    return false;
  return line.find(" HTTP/") != std::string_view::npos;
}

void OperatorInput::read_console() {
  console_in_.emplace(io_, ::dup(STDIN_FILENO));
  read_console_line();
}

void OperatorInput::read_console_line() {
  asio::async_read_until(*console_in_, console_buffer_, '\n', [this](const boost::system::error_code& ec, std::size_t) {
    if (ec || closed_) return;  // end of input: the show goes on without a console
    std::istream in(&console_buffer_);
    std::string line;
    std::getline(in, line);
    const std::string reply = on_command_(line);
    if (!reply.empty()) spdlog::info("master: {}", reply);
    read_console_line();
  });
}

void OperatorInput::listen_for_control(std::uint16_t port) {
  const tcp::endpoint endpoint(asio::ip::make_address("127.0.0.1"), port);
  control_acceptor_.emplace(io_);
  control_acceptor_->open(endpoint.protocol());
  control_acceptor_->set_option(tcp::acceptor::reuse_address(true));
  boost::system::error_code ec;
  control_acceptor_->bind(endpoint, ec);
  if (ec)
    throw std::runtime_error(cat("master: cannot open the control socket on 127.0.0.1:", port, ": ", ec.message()));
  control_acceptor_->listen();
  control_port_ = control_acceptor_->local_endpoint().port();
  accept_control();
}

void OperatorInput::accept_control() {
  control_acceptor_->async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
    if (closed_) return;
    if (ec) {
      accept_retry_.failed(ec, [this] { accept_control(); });  // EMFILE: back off, then accept again
      return;
    }
    accept_retry_.succeeded();
    if (clients_.size() >= kMaxClients) drop(clients_.front(), cat("more than ", kMaxClients, " control clients"));
    auto client = std::make_shared<ControlClient>(std::move(socket));
    clients_.push_back(client);
    serve_control(client);
    accept_control();
  });
}

void OperatorInput::drop(const std::shared_ptr<ControlClient>& client, const std::string& why) {
  if (!client->open) return;
  client->open = false;
  if (const std::optional<std::string> more = refusals_.admit(core::LogLimiter::Clock::now()))
    spdlog::warn("master: control socket: closing {}: {}{}", client->peer, why, *more);
  boost::system::error_code ec;
  client->idle.cancel();
  client->socket.shutdown(tcp::socket::shutdown_both, ec);
  client->socket.close(ec);
  clients_.remove(client);
}

void OperatorInput::serve_control(const std::shared_ptr<ControlClient>& client) {
  client->idle.expires_after(idle_timeout_);
  client->idle.async_wait([this, weak = std::weak_ptr<ControlClient>(client)](const boost::system::error_code& ec) {
    if (const auto c = weak.lock(); !ec && c && !closed_)
      drop(c, cat("no complete line within ", idle_timeout_.count(), " ms"));
  });
  asio::async_read_until(
      client->socket, client->buffer, '\n', [this, client](const boost::system::error_code& ec, std::size_t) {
        if (closed_ || !client->open) return;
        if (ec == asio::error::not_found) {
          drop(client, cat("a line longer than ", kMaxLineBytes, " bytes"));
          return;
        }
        if (ec) {  // the client closed
          client->open = false;
          client->idle.cancel();
          clients_.remove(client);
          return;
        }
        std::istream in(&client->buffer);
        std::string line;
        std::getline(in, line);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (std::exchange(client->first_line, false) && looks_like_http(line)) {
          drop(client, cat("an HTTP request (\"", core::escaped(line, 80),
                           "\"): the control socket takes command lines only; the console's API is --operator-port"));
          return;
        }
        client->idle.cancel();
        client->writing = true;
        auto reply = std::make_shared<std::string>(on_command_(line) + "\n");
        asio::async_write(client->socket, asio::buffer(*reply),
                          [this, client, reply](const boost::system::error_code& e, std::size_t) {
                            client->writing = false;
                            if (!e && !closed_ && client->open) {
                              serve_control(client);
                              return;
                            }
                            boost::system::error_code ignored;
                            client->open = false;
                            client->socket.close(ignored);
                            if (!closed_) clients_.remove(client);
                          });
      });
}

void OperatorInput::close() {
  closed_ = true;
  boost::system::error_code ec;
  accept_retry_.cancel();
  if (control_acceptor_) control_acceptor_->close(ec);
  if (console_in_) console_in_->close(ec);
  for (const std::shared_ptr<ControlClient>& c : std::list(clients_)) {
    c->idle.cancel();
    if (c->writing) continue;  // closed once its reply is out
    c->open = false;
    c->socket.close(ec);
  }
  clients_.clear();
}

}  // namespace zenith::cluster
