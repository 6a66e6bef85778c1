#include "cluster/operator/status_push.h"

#include <spdlog/spdlog.h>

#include <openssl/crypto.h>

#include <vector>

#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/websocket/stream.hpp>

namespace zenith::cluster {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using Clock = std::chrono::steady_clock;

/// Time limits of a connection: its handshakes (opening and closing), and
/// the silence after which it is closed (a ping goes out halfway).
constexpr std::chrono::seconds kHandshakeTimeout{5};
constexpr std::chrono::seconds kIdleTimeout{30};

}  // namespace

/// One WebSocket connection: reads the client's messages (the token, then
/// nothing), writes status messages one at a time.
struct StatusPush::Connection : std::enable_shared_from_this<StatusPush::Connection> {
  Connection(beast::tcp_stream stream, StatusPush& owner_, bool authenticated_, std::string peer_)
      : ws(std::move(stream)), owner(owner_), peer(std::move(peer_)), authenticated(authenticated_) {}

  /// The WebSocket handshake of `request`, then the first status (when authenticated) and reading.
  void start(const Request& request) {
    beast::get_lowest_layer(ws).expires_never();  // the WebSocket's own timeouts from here on
    websocket::stream_base::timeout timeouts{kHandshakeTimeout, kIdleTimeout, true};
    ws.set_option(timeouts);
    ws.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& r) { r.set(beast::http::field::server, "zenith operator console"); }));
    ws.read_message_max(kMaxClientMessageBytes);
    ws.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->open = true;
      if (self->authenticated) self->send(self->owner.status_text());
      self->read();
    });
  }

  /// Reads the next message: the token, when one is awaited; anything else is ignored.
  void read() {
    ws.async_read(in, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) {
        self->open = false;
        return;
      }
      const std::string text = beast::buffers_to_string(self->in.data());
      self->in.consume(self->in.size());
      if (!self->authenticated) {
        const nlohmann::json message = nlohmann::json::parse(text, nullptr, false);
        const bool has_token = message.is_object() && message.contains("token") && message["token"].is_string();
        if (!has_token || !self->owner.token_matches(message["token"].get<std::string>())) {
          spdlog::info("master: operator console: closing the status push to {}: {}", self->peer,
                       has_token ? "wrong operator token" : "its first message is not {\"token\": \"...\"}");
          self->close(websocket::close_code::policy_error, "the operator token is needed");
          return;
        }
        if (self->owner.authenticated_count() >= kMaxConnections) {
          spdlog::info("master: operator console: closing the status push to {}: {} connections are pushed to already",
                       self->peer, kMaxConnections);
          self->close(websocket::close_code::try_again_later, "too many status connections: poll /api/status");
          return;
        }
        self->authenticated = true;
        self->send(self->owner.status_text());
      }
      self->read();
    });
  }

  /// Sends `text`, or keeps it to send after the message being written.
  void send(std::string text) {
    if (!open) return;
    if (writing) {
      queued = std::move(text);
      return;
    }
    writing = true;
    out = std::move(text);
    ws.text(true);
    ws.async_write(asio::buffer(out), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      self->writing = false;
      if (ec) {
        self->open = false;
        return;
      }
      if (self->queued) {
        std::string next = std::move(*self->queued);
        self->queued.reset();
        self->send(std::move(next));
      }
    });
  }

  /// Closes now: a connection still in its handshake, or one pushed out for a newer one.
  void abort() {
    closing = true;
    open = false;
    beast::get_lowest_layer(ws).close();
  }

  /// Closes with a close frame (at most kHandshakeTimeout for the peer's answer).
  void close(websocket::close_code code, const char* reason) {
    if (!open) return;
    open = false;
    closing = true;
    ws.async_close(websocket::close_reason(code, reason), [self = shared_from_this()](beast::error_code) {});
  }

  websocket::stream<beast::tcp_stream> ws;
  StatusPush& owner;
  std::string peer;
  bool authenticated = false;
  bool open = false;     ///< handshake done and not closed
  bool closing = false;  ///< closed or closing: counts for no limit
  bool writing = false;  ///< a message is being written
  std::optional<std::string> queued;
  std::string out;
  beast::flat_buffer in;
  Clock::time_point connected_at = Clock::now();
};

StatusPush::StatusPush(asio::io_context& io, std::function<nlohmann::json()> status, std::optional<SharedSecret> token)
    : io_(io), status_(std::move(status)), token_(std::move(token)), timer_(io) {}

std::size_t StatusPush::authenticated_count() const {
  std::size_t n = 0;
  for (const std::weak_ptr<Connection>& weak : connections_)
    if (const auto c = weak.lock(); c && c->authenticated && !c->closing) ++n;
  return n;
}

bool StatusPush::has_room(bool authenticated) {
  connections_.remove_if([](const std::weak_ptr<Connection>& c) { return c.expired(); });
  if (closed_) return false;
  if (authenticated || !token_) return authenticated_count() < kMaxConnections;
  std::vector<std::shared_ptr<Connection>> waiting;
  for (const std::weak_ptr<Connection>& weak : connections_)
    if (const auto c = weak.lock(); c && !c->authenticated && !c->closing) waiting.push_back(c);
  if (waiting.size() >= kMaxWaitingForToken) {  // the oldest waiting makes room
    spdlog::info(
        "master: operator console: closing the status push to {}: no operator token yet, and a newer "
        "connection waits for one ({} at most)",
        waiting.front()->peer, kMaxWaitingForToken);
    waiting.front()->abort();
  }
  return true;
}

void StatusPush::accept(beast::tcp_stream stream, const Request& request, bool authenticated, std::string peer) {
  if (closed_) return;
  auto connection = std::make_shared<Connection>(std::move(stream), *this, authenticated || !token_, std::move(peer));
  connections_.push_back(connection);
  connection->start(request);
  schedule();
}

void StatusPush::close() {
  closed_ = true;
  timer_.cancel();
  for (const std::weak_ptr<Connection>& weak : connections_)
    if (const auto c = weak.lock()) {
      if (c->open)
        c->close(websocket::close_code::going_away, "the master is stopping");
      else
        c->abort();  // still in its handshake
    }
  connections_.clear();
}

bool StatusPush::token_matches(std::string_view given) const {
  if (!token_) return false;
  const auto expected = token_->bytes();
  return given.size() == expected.size() && CRYPTO_memcmp(given.data(), expected.data(), given.size()) == 0;
}

std::string StatusPush::status_text() const {
  return status_().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void StatusPush::schedule() {
  if (timer_running_ || closed_) return;
  timer_running_ = true;
  timer_.expires_after(kPushInterval);
  timer_.async_wait([this](const boost::system::error_code& ec) {
    timer_running_ = false;
    if (!ec) tick();
  });
}

void StatusPush::tick() {
  if (closed_) return;
  connections_.remove_if([](const std::weak_ptr<Connection>& c) { return c.expired(); });
  if (connections_.empty()) return;  // the timer stops until the next connection
  const auto now = Clock::now();
  bool anyone = false;
  for (const std::weak_ptr<Connection>& weak : connections_)
    if (const auto c = weak.lock()) {
      if (!c->authenticated && c->open && now - c->connected_at > kTokenWait) {
        spdlog::info("master: operator console: closing the status push to {}: no operator token within {} s", c->peer,
                     kTokenWait.count());
        c->close(websocket::close_code::policy_error, "the operator token is needed");
      }
      anyone = anyone || (c->authenticated && c->open);
    }
  if (anyone) {
    std::string text = status_text();
    if (text != last_) {
      last_ = text;
      for (const std::weak_ptr<Connection>& weak : connections_)
        if (const auto c = weak.lock(); c && c->authenticated) c->send(text);
    }
  }
  schedule();
}

}  // namespace zenith::cluster
