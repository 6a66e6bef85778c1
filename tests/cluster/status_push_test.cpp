// The operator console's status pushes over a real loopback WebSocket
// (cluster/operator/status_push.h, operator_http_server.h; docs/operator.md,
// "Status pushes"): the status on connecting and whenever it changes, the
// Host and Origin rules, the token as a header or as the first message, and
// close().
#include "cluster/operator/status_push.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <thread>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/websocket.hpp>

#include "cluster/operator/operator_http_server.h"
#include "core/process.h"

namespace zenith::cluster {
namespace {

using nlohmann::json;
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace websocket = beast::websocket;
using asio::ip::tcp;

/// An operator console on 127.0.0.1 (any free port) whose status is {"n": counter}, run on its own thread.
class StatusPushTest : public ::testing::Test {
 protected:
  void start(std::optional<SharedSecret> token = std::nullopt) {
    server_.emplace(
        io_, OperatorHttpServer::Options{"127.0.0.1", 0, std::move(token), {}},
        OperatorHttpServer::Handlers{[this] {
                                       return json{{"n", counter_.load()}};
                                     },
                                     [](const OperatorCommand&, const std::string&) { return std::string(); },
                                     {}});
    server_->start();
    thread_ = std::thread([this] { io_.run(); });
  }
  void TearDown() override {
    if (server_) asio::post(io_, [this] { server_->close(); });
    work_.reset();
    if (thread_.joinable()) thread_.join();
  }

  /// A client WebSocket to /api/events (reads time out after 5 s), with `headers` on its upgrade request.
  std::unique_ptr<websocket::stream<tcp::socket>> connect(
      const std::vector<std::pair<beast::http::field, std::string>>& headers = {}, const std::string& host = "") {
    tcp::socket socket(client_io_);
    socket.connect({asio::ip::make_address("127.0.0.1"), server_->port()});
    const timeval timeout{5, 0};
    setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    auto ws = std::make_unique<websocket::stream<tcp::socket>>(std::move(socket));
    ws->set_option(websocket::stream_base::decorator([headers](websocket::request_type& r) {
      for (const auto& [field, value] : headers) r.set(field, value);
    }));
    ws->handshake(host.empty() ? "127.0.0.1:" + std::to_string(server_->port()) : host, "/api/events");
    return ws;
  }
  static json next(websocket::stream<tcp::socket>& ws) {
    beast::flat_buffer buffer;
    ws.read(buffer);
    return json::parse(beast::buffers_to_string(buffer.data()));
  }

  asio::io_context io_, client_io_;
  asio::executor_work_guard<asio::io_context::executor_type> work_ = asio::make_work_guard(io_);
  std::optional<OperatorHttpServer> server_;
  std::thread thread_;
  std::atomic<int> counter_{0};
};

TEST_F(StatusPushTest, PushesTheStatusOnConnectingAndWheneverItChanges) {
  start();
  // The page's own origin (a browser sends it): accepted.
  auto ws = connect({{beast::http::field::origin, "http://127.0.0.1:" + std::to_string(server_->port())}});
  EXPECT_EQ(next(*ws), (json{{"n", 0}}));
  counter_ = 1;
  EXPECT_EQ(next(*ws), (json{{"n", 1}}));
  counter_ = 2;
  EXPECT_EQ(next(*ws), (json{{"n", 2}}));
  // A second connection gets the status at once.
  auto other = connect();
  EXPECT_EQ(next(*other), (json{{"n", 2}}));
  // The server closes: the clients see a close frame.
  asio::post(io_, [this] { server_->close(); });
  beast::flat_buffer buffer;
  beast::error_code ec;
  ws->read(buffer, ec);
  EXPECT_EQ(ec, websocket::error::closed);
  EXPECT_EQ(ws->reason().code, websocket::close_code::going_away);
}

TEST_F(StatusPushTest, RefusesOtherOriginsAndHostsLikeTheApi) {
  start();
  EXPECT_THROW(connect({{beast::http::field::origin, "http://evil.example"}}), beast::system_error);
  EXPECT_THROW(connect({}, "attacker.example:80"), beast::system_error);
  // Without the upgrade: a plain GET is told what /api/events is.
  OperatorHttpServer::Request get{beast::http::verb::get, "/api/events", 11};
  get.set(beast::http::field::host, "127.0.0.1:" + std::to_string(server_->port()));
  EXPECT_EQ(server_->respond(get, "x").result(), beast::http::status::upgrade_required);
}

TEST_F(StatusPushTest, WithATokenNothingIsSentBeforeTheToken) {
  const std::string token(20, 'k');
  start(SharedSecret(std::vector<std::uint8_t>(token.begin(), token.end()), "test"));
  // In the upgrade request's header: pushed at once.
  auto header = connect({{beast::http::field::authorization, "Bearer " + token}});
  EXPECT_EQ(next(*header), (json{{"n", 0}}));
  EXPECT_THROW(connect({{beast::http::field::authorization, "Bearer " + std::string(20, 'j')}}), beast::system_error);
  // As the first message (a browser cannot set the header): nothing before it.
  auto browser = connect();
  counter_ = 5;
  EXPECT_EQ(next(*header), (json{{"n", 5}}));
  browser->write(asio::buffer(json{{"token", token}}.dump()));
  EXPECT_EQ(next(*browser), (json{{"n", 5}})) << "the first message after the token is the status";
  // A wrong token closes the connection.
  auto wrong = connect();
  wrong->write(asio::buffer(json{{"token", "nope"}}.dump()));
  beast::flat_buffer buffer;
  beast::error_code ec;
  wrong->read(buffer, ec);
  EXPECT_EQ(ec, websocket::error::closed);
  EXPECT_EQ(wrong->reason().code, websocket::close_code::policy_error);
}

// 16 WebSockets without the token once held every push
// slot, so the operator's page fell back to polling. Connections waiting for
// the token have slots of their own now, the oldest closed for a new one.
TEST_F(StatusPushTest, ConnectionsWithoutTheTokenNeverTakeTheOperatorsSlots) {
  const std::string token(20, 'k');
  start(SharedSecret(std::vector<std::uint8_t>(token.begin(), token.end()), "test"));
  std::vector<std::unique_ptr<websocket::stream<tcp::socket>>> strangers;
  for (std::size_t i = 0; i < StatusPush::kMaxConnections + 4; ++i) strangers.push_back(connect());
  auto operator_page = connect({{beast::http::field::authorization, "Bearer " + token}});
  EXPECT_EQ(next(*operator_page), (json{{"n", 0}}));
  // A page that sends the token as its first message gets in too.
  auto browser = connect();
  browser->write(asio::buffer(json{{"token", token}}.dump()));
  EXPECT_EQ(next(*browser), (json{{"n", 0}}));
  // The oldest strangers were closed to make room: only kMaxWaitingForToken wait.
  beast::flat_buffer buffer;
  beast::error_code ec;
  strangers.front()->read(buffer, ec);
  EXPECT_TRUE(ec) << "the oldest connection without a token was closed";
}

// 32 half-sent requests once filled every connection for
// 30 s. A new connection now closes the oldest one waiting for its request.
TEST_F(StatusPushTest, HalfSentRequestsNeverLockTheOperatorOutOfTheConsole) {
  start();
  const std::string host = "127.0.0.1:" + std::to_string(server_->port());
  std::vector<int> held;
  for (std::size_t i = 0; i < OperatorHttpServer::kMaxConnections + 8; ++i) {
    const int fd = core::connect_loopback(server_->port());
    ASSERT_GE(fd, 0);
    const std::string half = "GET /api/status HTTP/1.1\r\nHost: " + host + "\r\nX-Slow: ";
    ASSERT_EQ(::send(fd, half.data(), half.size(), MSG_NOSIGNAL), static_cast<ssize_t>(half.size()));
    held.push_back(fd);
  }
  const auto started = std::chrono::steady_clock::now();
  const int fd = core::connect_loopback(server_->port());
  ASSERT_GE(fd, 0);
  const timeval timeout{5, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  const std::string whole = "GET /api/status HTTP/1.1\r\nHost: " + host + "\r\nConnection: close\r\n\r\n";
  ASSERT_EQ(::send(fd, whole.data(), whole.size(), MSG_NOSIGNAL), static_cast<ssize_t>(whole.size()));
  std::string reply;
  char buffer[4096];
  for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) reply.append(buffer, static_cast<std::size_t>(n));
  EXPECT_TRUE(reply.starts_with("HTTP/1.1 200 OK")) << reply;
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(4)) << "answered, not timed out";
  ::close(fd);
  for (const int h : held) ::close(h);
}

}  // namespace
}  // namespace zenith::cluster
