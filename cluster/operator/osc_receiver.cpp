#include "cluster/operator/osc_receiver.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "cluster/operator/osc_command.h"
#include "core/strings.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::udp;
using core::cat;

OscReceiver::OscReceiver(asio::io_context& io, Options options, CommandHandler on_command)
    : io_(io), options_(std::move(options)), on_command_(std::move(on_command)) {}

void OscReceiver::start() {
  boost::system::error_code ec;
  const asio::ip::address address = asio::ip::make_address(options_.host, ec);
  if (ec) throw std::runtime_error(cat("OSC: --osc-host ", options_.host, ": not a numeric IP address"));
  loopback_ = address.is_loopback();
  for (const std::string& sender : options_.allowed_senders) {
    const asio::ip::address a = asio::ip::make_address(sender, ec);
    if (ec) throw std::runtime_error(cat("OSC: --osc-allow ", sender, ": not a numeric IP address"));
    allowed_.push_back(a);
  }
  if (!loopback_ && allowed_.empty())
    throw std::runtime_error(
        cat("OSC: listening on ", options_.host,
            " (not a loopback address) needs the desks' "
            "addresses: --osc-allow ADDRESS for each (OSC has no authentication; docs/operator.md)"));
  const udp::endpoint endpoint(address, options_.port);
  socket_.emplace(io_);
  socket_->open(endpoint.protocol());
  socket_->bind(endpoint, ec);
  if (ec)
    throw std::runtime_error(cat("OSC: cannot listen on UDP ", options_.host, ":", options_.port, ": ", ec.message()));
  port_ = socket_->local_endpoint().port();
  receive();
}

void OscReceiver::close() {
  closed_ = true;
  boost::system::error_code ec;
  if (socket_) socket_->close(ec);
}

void OscReceiver::receive() {
  socket_->async_receive_from(asio::buffer(buffer_), sender_,
                              [this](const boost::system::error_code& ec, std::size_t n) {
                                if (closed_) return;
                                if (!ec)
                                  handle(std::span<const std::uint8_t>(buffer_).first(n), sender_.address());
                                else if (ec != asio::error::message_size)
                                  spdlog::warn("master: OSC: receive failed: {}", ec.message());
                                receive();
                              });
}

std::size_t OscReceiver::handle(std::span<const std::uint8_t> datagram, const asio::ip::address& sender) {
  const std::string from = sender.to_string();
  const bool allowed =
      allowed_.empty() ? sender.is_loopback() : std::find(allowed_.begin(), allowed_.end(), sender) != allowed_.end();
  const auto now = core::LogLimiter::Clock::now();
  if (!allowed) {
    if (const std::optional<std::string> more = strangers_.admit(now))
      spdlog::warn("master: OSC: ignoring {} bytes from {}: not an allowed sender (--osc-allow){}", datagram.size(),
                   from, *more);
    return 0;
  }
  std::vector<OscMessage> messages;
  try {
    messages = decode_osc_packet(datagram);
  } catch (const OscError& e) {
    if (const std::optional<std::string> more = malformed_.admit(now))
      spdlog::warn("master: OSC from {}: refused {} bytes: {}{}", from, datagram.size(), core::escaped(e.what()),
                   *more);
    return 0;
  }
  std::size_t applied = 0;
  for (const OscMessage& m : messages) {
    std::string arguments;
    for (const OscArgument& a : m.arguments) arguments += cat(" ", describe(a));
    OperatorCommand command;
    try {
      command = osc_command(m);
    } catch (const std::exception& e) {
      if (const std::optional<std::string> more = unknown_.admit(now))
        spdlog::warn("master: operator (osc {}): {}{} refused: {}{}", from, core::escaped(m.address),
                     core::escaped(arguments), core::escaped(e.what()), *more);
      continue;
    }
    try {
      on_command_(command, cat("osc ", from));  // logs applied or refused
      ++applied;
    } catch (const std::exception&) {
    }
  }
  return applied;
}

}  // namespace zenith::cluster
