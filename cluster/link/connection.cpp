#include "cluster/link/connection.h"

#include <boost/asio/buffer.hpp>
#include <boost/asio/write.hpp>

namespace zenith::cluster {

namespace asio = boost::asio;

Connection::Connection(asio::ip::tcp::socket socket, std::string peer)
    : socket_(std::move(socket)),
      grace_timer_(socket_.get_executor()),
      peer_(std::move(peer)),
      read_buffer_(kReadChunkBytes),
      last_received_(std::chrono::steady_clock::now()) {
  boost::system::error_code ec;
  socket_.set_option(asio::ip::tcp::no_delay(true), ec);  // small control messages: no Nagle delay
}

Connection::~Connection() {
  boost::system::error_code ec;
  socket_.close(ec);
}

void Connection::start(MessageHandler on_message, CloseHandler on_close) {
  on_message_ = std::move(on_message);
  on_close_ = std::move(on_close);
  open_ = true;
  last_received_ = std::chrono::steady_clock::now();
  read_more();
}

void Connection::read_more() {
  auto self = shared_from_this();
  socket_.async_read_some(asio::buffer(read_buffer_), [self](const boost::system::error_code& ec, std::size_t n) {
    if (!self->open_) return;
    if (self->closing_) {  // lingering (close_after_flush): dropped, until the peer closes
      if (ec)
        self->finish(self->closing_reason_);
      else
        self->read_more();
      return;
    }
    if (ec) {
      std::string reason = ec == asio::error::eof ? std::string("end of stream") : "read error: " + ec.message();
      if (self->decoder_.buffered_bytes() > 0)
        reason +=
            " inside a frame (" + std::to_string(self->decoder_.buffered_bytes()) + " bytes of a truncated frame)";
      self->finish(reason);
      return;
    }
    self->last_received_ = std::chrono::steady_clock::now();
    self->decoder_.feed(std::span<const std::uint8_t>(self->read_buffer_.data(), n));
    try {
      while (self->open_ && !self->closing_) {
        std::optional<Message> message = self->decoder_.next();
        if (!message) break;
        self->on_message_(std::move(*message));
      }
    } catch (const ProtocolError& e) {
      self->finish(std::string("protocol error: ") + e.what());
      return;
    }
    if (self->open_) self->read_more();  // closing: on to the end of stream
  });
}

void Connection::limit_payload(std::uint32_t max_bytes, std::string why) {
  decoder_.limit_payload(max_bytes, std::move(why));
  std::vector<std::uint8_t>(kLimitedReadBytes).swap(read_buffer_);
}

void Connection::lift_payload_limit() {
  decoder_.lift_payload_limit();
  if (read_buffer_.size() < kReadChunkBytes) read_buffer_.resize(kReadChunkBytes);
}

void Connection::send(const Message& message) {
  send_encoded(std::make_shared<const std::vector<std::uint8_t>>(encode(message)));
}

void Connection::send_encoded(std::shared_ptr<const std::vector<std::uint8_t>> frame) {
  if (!open_ || closing_) return;
  queue_.push_back(std::move(frame));
  if (!writing_) write_next();
}

void Connection::write_next() {
  if (queue_.empty()) {
    writing_ = false;
    if (closing_) shut_down_sending();
    return;
  }
  writing_ = true;
  auto self = shared_from_this();
  asio::async_write(socket_, asio::buffer(*queue_.front()), [self](const boost::system::error_code& ec, std::size_t) {
    if (self->finished_) return;
    self->queue_.pop_front();
    if (ec) {
      self->finish(self->closing_ ? self->closing_reason_ : "write error: " + ec.message());
      return;
    }
    self->write_next();
  });
}

void Connection::close_after_flush(const std::string& reason, std::chrono::milliseconds grace) {
  if (!open_ || closing_) return;
  closing_ = true;
  closing_reason_ = reason;
  auto self = shared_from_this();
  grace_timer_.expires_after(grace);
  grace_timer_.async_wait([self](const boost::system::error_code& ec) {
    if (!ec) self->finish(self->closing_reason_);
  });
  if (!writing_) shut_down_sending();
}

void Connection::shut_down_sending() {
  // FIN after the last queued byte; the read loop (still pending) sees the
  // peer's end of stream and finishes.
  boost::system::error_code ec;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_send, ec);
  if (ec) finish(closing_reason_);
}

void Connection::close(const std::string& reason) {
  if (!open_) return;
  finish(reason);
}

void Connection::finish(const std::string& reason) {
  if (finished_) return;
  finished_ = true;
  open_ = false;
  grace_timer_.cancel();
  boost::system::error_code ec;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ec);
  socket_.close(ec);
  queue_.clear();
  if (on_close_) {
    CloseHandler handler = std::move(on_close_);
    on_close_ = nullptr;
    handler(reason);
  }
}

std::optional<boost::asio::ip::tcp::endpoint> Connection::remote_endpoint() const {
  boost::system::error_code ec;
  const boost::asio::ip::tcp::endpoint endpoint = socket_.remote_endpoint(ec);
  if (ec) return std::nullopt;
  return endpoint;
}

}  // namespace zenith::cluster
