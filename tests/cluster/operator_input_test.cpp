// The control socket's limits on real loopback sockets (cluster/operator/operator_input.h;
// docs/operator.md, "Threat model"): no web page's request
// runs a command, no client holds a line, a slot or the acceptor.
#include "cluster/operator/operator_input.h"

#include <gtest/gtest.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/process.h"
#include "core/strings.h"
#include "tests/cluster/captured_log.h"

namespace zenith::cluster {
namespace {

using namespace std::chrono_literals;

class OperatorInputTest : public ::testing::Test {
 protected:
  void SetUp() override { start(OperatorInput::kIdleTimeout); }
  void TearDown() override {
    input_->close();
    run_for(50ms);
    for (const int fd : fds_) ::close(fd);
  }
  void start(std::chrono::milliseconds idle) {
    if (input_) {
      input_->close();
      run_for(50ms);  // its cancelled handlers run before it goes
    }
    input_.emplace(
        io_,
        [this](std::string line) {
          lines_.push_back(line);
          return "ok " + line;
        },
        idle);
    input_->listen_for_control(0);
  }
  /// A new client (closed by TearDown).
  int connect() {
    const int fd = core::connect_loopback(input_->control_port());
    if (fd >= 0) fds_.push_back(fd);
    return fd;
  }
  static void send_text(int fd, const std::string& text) {
    std::size_t sent = 0;
    while (sent < text.size()) {
      const ssize_t n = ::send(fd, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return;  // closed by the master: what some tests expect
      sent += static_cast<std::size_t>(n);
    }
  }
  /// Runs the master's io_context for `d`.
  void run_for(std::chrono::milliseconds d) {
    io_.restart();
    io_.run_for(d);
  }
  /// What the client has received so far; `closed` says whether the master closed it.
  static std::string received(int fd, bool& closed) { return core::read_until_closed(fd, 0ms, closed); }
  bool closed_by_master(int fd) {
    bool closed = false;
    received(fd, closed);
    return closed;
  }
  /// A command from a fresh client is answered.
  void expect_served() {
    const int fd = connect();
    ASSERT_GE(fd, 0);
    send_text(fd, "status\n");
    std::string reply;
    bool closed = false;
    for (int i = 0; i < 50 && reply.find('\n') == std::string::npos && !closed; ++i) {
      run_for(50ms);
      reply += received(fd, closed);
    }
    EXPECT_EQ(reply, "ok status\n");
  }

  boost::asio::io_context io_;
  std::optional<OperatorInput> input_;
  std::vector<std::string> lines_;
  std::vector<int> fds_;
};

TEST_F(OperatorInputTest, AnswersEachCommandLine) {
  const int fd = connect();
  send_text(fd, "pause\r\nseek 3\n");
  run_for(300ms);
  bool closed = false;
  EXPECT_EQ(received(fd, closed), "ok pause\nok seek 3\n");
  EXPECT_FALSE(closed);
  EXPECT_EQ(lines_, (std::vector<std::string>{"pause", "seek 3"}));
}

// A no-cors fetch from any web site sends exactly this: it once stopped the show.
TEST_F(OperatorInputTest, ClosesAnHttpRequestBeforeRunningAnyOfItsLines) {
  tests::CapturedLog log;
  const int fd = connect();
  send_text(fd, "POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: text/plain\r\nContent-Length: 6\r\n\r\n\nquit\n");
  run_for(300ms);
  EXPECT_TRUE(closed_by_master(fd));
  EXPECT_TRUE(lines_.empty()) << lines_.front();
  EXPECT_NE(log.text().find("an HTTP request (\"POST / HTTP/1.1\")"), std::string::npos) << log.text();
  EXPECT_TRUE(OperatorInput::looks_like_http("GET /api/status HTTP/1.0"));
  EXPECT_FALSE(OperatorInput::looks_like_http("seek 3"));
  EXPECT_FALSE(OperatorInput::looks_like_http("{\"command\": \"quit\"} HTTP/"));
  expect_served();
}

TEST_F(OperatorInputTest, ClosesALineLongerThanTheLimitWithoutBufferingIt) {
  const int fd = connect();
  send_text(fd, std::string(64 * 1024, 'a'));  // no newline: it once buffered 200 MiB of this
  run_for(500ms);
  EXPECT_TRUE(closed_by_master(fd));
  EXPECT_TRUE(lines_.empty());
  const int exact = connect();
  send_text(exact, std::string(OperatorInput::kMaxLineBytes, 'b') + "\n");
  run_for(300ms);
  ASSERT_EQ(lines_.size(), 1u) << "a line of exactly the limit is a line";
  expect_served();
}

TEST_F(OperatorInputTest, ClosesAClientThatHoldsAHalfLine) {
  start(400ms);
  const int fd = connect();
  send_text(fd, "pau");
  run_for(100ms);
  EXPECT_FALSE(closed_by_master(fd));
  run_for(1000ms);
  EXPECT_TRUE(closed_by_master(fd));
  EXPECT_TRUE(lines_.empty());
}

TEST_F(OperatorInputTest, AtMostEightClientsTheOldestClosedForANewOne) {
  std::vector<int> held;
  for (int i = 0; i < 12; ++i) {
    held.push_back(connect());
    send_text(held.back(), "half");
    run_for(30ms);
  }
  run_for(200ms);
  int closed = 0;
  for (int i = 0; i < 12; ++i) {
    const bool c = closed_by_master(held[static_cast<std::size_t>(i)]);
    closed += c;
    if (i < 4) {
      EXPECT_TRUE(c) << "client " << i << " is among the oldest";
    }
  }
  EXPECT_EQ(closed, 4);
  expect_served();  // the operator always gets in
}

// At file-descriptor exhaustion the acceptor once stopped for good (the
// control socket) or spun writing a line per try (the console).
TEST_F(OperatorInputTest, BacksOffAtFileDescriptorExhaustionLogsAtMostOnceASecondAndAcceptsAgain) {
  tests::CapturedLog log;
  rlimit original{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &original), 0);
  std::size_t open_now = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) ++open_now;
  rlimit low = original;
  low.rlim_cur = open_now + 8;
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &low), 0);
  std::vector<int> clients;
  for (int i = 0; i < 64; ++i) {
    const int fd = core::connect_loopback(input_->control_port());
    if (fd < 0) break;
    clients.push_back(fd);
  }
  run_for(2500ms);  // the acceptor meets EMFILE again and again
  for (const int fd : clients) ::close(fd);
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &original), 0);
  const std::string text = log.text();
  const std::size_t lines = core::count_of(text, "control socket: accept failed");
  EXPECT_GE(lines, 1u) << text;
  EXPECT_LE(lines, 4u) << "one line a second at most\n" << text;
  run_for(1200ms);  // the back-off (at most 1 s) ends; the queued connections are accepted and closed
  expect_served();
}

}  // namespace
}  // namespace zenith::cluster
