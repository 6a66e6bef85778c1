#include "cluster/master/operator_input.h"

#include <spdlog/spdlog.h>

#include <istream>
#include <stdexcept>

#include <unistd.h>

#include <boost/asio/read_until.hpp>
#include <boost/asio/write.hpp>

#include "core/strings.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::tcp;
using core::cat;

/// One control-socket client: lines in, one reply line out per command.
struct OperatorInput::ControlClient {
  tcp::socket socket;
  asio::streambuf buffer;
  explicit ControlClient(tcp::socket s) : socket(std::move(s)) {}
};

OperatorInput::OperatorInput(asio::io_context& io, CommandHandler on_command)
    : io_(io), on_command_(std::move(on_command)) {}

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
  if (ec) throw std::runtime_error(cat("master: cannot open the control socket on 127.0.0.1:", port, ": ", ec.message()));
  control_acceptor_->listen();
  accept_control();
}

void OperatorInput::accept_control() {
  control_acceptor_->async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
    if (ec || closed_) return;
    serve_control(std::make_shared<ControlClient>(std::move(socket)));
    accept_control();
  });
}

void OperatorInput::serve_control(std::shared_ptr<ControlClient> client) {
  asio::async_read_until(client->socket, client->buffer, '\n',
                         [this, client](const boost::system::error_code& ec, std::size_t bytes) {
                           if (ec) return;
                           if (bytes > 1024) return;  // not an operator command: drop the client
                           std::istream in(&client->buffer);
                           std::string line;
                           std::getline(in, line);
                           auto reply = std::make_shared<std::string>(on_command_(line) + "\n");
                           asio::async_write(client->socket, asio::buffer(*reply),
                                             [this, client, reply](const boost::system::error_code& e, std::size_t) {
                                               if (!e && !closed_) serve_control(client);
                                             });
                         });
}

void OperatorInput::close() {
  closed_ = true;
  boost::system::error_code ec;
  if (control_acceptor_) control_acceptor_->close(ec);
  if (console_in_) console_in_->close(ec);
}

}  // namespace zenith::cluster
