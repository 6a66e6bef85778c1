#include "bench/soak_attacks.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <thread>

#include "cluster/protocol/messages.h"
#include "core/process.h"

namespace zenith::bench {

namespace {

using namespace std::chrono_literals;

void send_all(int fd, const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

/// The status code of one HTTP request sent whole on a fresh connection (0: none within 5 s).
int http_status(int port, const std::string& request) {
  const int fd = core::connect_loopback(port);
  if (fd < 0) return 0;
  send_all(fd, request);
  bool closed = false;
  const std::string reply = core::read_until_closed(fd, 5000ms, closed);
  ::close(fd);
  return reply.starts_with("HTTP/1.1 ") && reply.size() >= 12 ? std::stoi(reply.substr(9, 3)) : 0;
}

}  // namespace

SoakAttacks::SoakAttacks(std::filesystem::path zenith, std::vector<std::string> stray_args, std::filesystem::path dir,
                         AttackPorts ports)
    : zenith_(std::move(zenith)), dir_(std::move(dir)), stray_args_(std::move(stray_args)), ports_(ports) {}

SoakAttacks::~SoakAttacks() {
  for (const Held& h : held_) ::close(h.fd);
  for (const pid_t pid : strays_) {
    ::kill(pid, SIGKILL);
    core::wait_for_exit(pid, 5000ms);
  }
}

std::string SoakAttacks::launch(std::mt19937& rng) {
  static const char* kNames[] = {"rebinding", "slowloris", "control", "stray", "preauth", "osc"};
  const std::string name = kNames[std::uniform_int_distribution<int>(0, 5)(rng)];
  ++launched_;
  ++counts_[name];
  if (name == "rebinding")
    rebinding();
  else if (name == "slowloris")
    slowloris(rng);
  else if (name == "control")
    control(rng);
  else if (name == "stray")
    stray();
  else if (name == "preauth")
    preauth(rng);
  else
    osc(rng);
  return name;
}

void SoakAttacks::rebinding() {
  const std::string host = fmt::format("127.evil.example:{}", ports_.console);
  const std::string body = R"({"command": "exposure", "exposure": 77})";
  const int status = http_status(
      ports_.console, fmt::format("POST /api/command HTTP/1.1\r\nHost: {}\r\nOrigin: http://{}\r\nContent-Type: "
                                  "application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{}",
                                  host, host, body.size(), body));
  if (status == 403)
    ++passed_["rebinding"];
  else
    failures_.push_back(fmt::format("rebinding: HTTP {} for Host {} (403 expected)", status, host));
}

void SoakAttacks::slowloris(std::mt19937& rng) {
  const auto until = Clock::now() + std::chrono::milliseconds(std::uniform_int_distribution<int>(1000, 4000)(rng));
  for (int i = 0; i < 40; ++i) {
    const int fd = core::connect_loopback(ports_.console);
    if (fd < 0) continue;
    send_all(fd, fmt::format("GET /api/status HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nX-Slow: ", ports_.console));
    hold(fd, until);
  }
  const int status = http_status(
      ports_.console,
      fmt::format("GET /api/status HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\n\r\n", ports_.console));
  if (status == 200)
    ++passed_["slowloris"];
  else
    failures_.push_back(fmt::format("slowloris: the operator's request got HTTP {} (200 expected)", status));
}

void SoakAttacks::control(std::mt19937& rng) {
  const int fd = core::connect_loopback(ports_.control);
  if (fd < 0) {
    failures_.push_back("control: cannot connect to the control socket");
    return;
  }
  if (std::uniform_int_distribution<int>(0, 1)(rng) == 0)
    send_all(fd, "POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: text/plain\r\nContent-Length: 6\r\n\r\n\nquit\n");
  else
    send_all(fd, std::string(256 * 1024, 'x'));
  bool closed = false;
  core::read_until_closed(fd, 5000ms, closed);
  ::close(fd);
  if (closed)
    ++passed_["control"];
  else
    failures_.push_back("control: the control socket kept a web page's request or a 256 KiB line open");
}

void SoakAttacks::stray() {
  std::vector<std::string> args = stray_args_;
  const int k = counts_["stray"];
  args.insert(args.end(), {"--name", "n0", "--out", (dir_ / fmt::format("stray-{}", k)).string(), "--cache",
                           (dir_ / "stray-cache").string()});
  strays_.push_back(core::spawn_process(zenith_, args, dir_ / "strays.log", core::LogMode::append));
}

void SoakAttacks::preauth(std::mt19937& rng) {
  cluster::TableChunk chunk;
  chunk.bytes.assign(cluster::kMaxTableChunkBytes, 0x5a);
  const std::vector<std::uint8_t> frame = cluster::encode(cluster::Message{chunk});
  const std::string header(frame.begin(), frame.begin() + cluster::kHeaderBytes);
  const auto until = Clock::now() + std::chrono::milliseconds(std::uniform_int_distribution<int>(1000, 3000)(rng));
  for (int i = 0; i < 100; ++i) {
    const int fd = core::connect_loopback(ports_.cluster);
    if (fd < 0) continue;
    if (i % 2 == 0) send_all(fd, header);
    hold(fd, until);
  }
  ++passed_["preauth"];  // judged by the show (no frame lost) and the master's memory
}

void SoakAttacks::osc(std::mt19937& rng) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(ports_.osc));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::vector<std::uint8_t> bytes;
  for (int i = 0; i < 2100; ++i) {
    if (i < 2000) {
      bytes.resize(std::uniform_int_distribution<std::size_t>(1, 512)(rng));
      for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
    } else {  // a message whose address forges a log line: "/zenith/x\nmaster: …\x1b[2J", no arguments
      std::string address = "/zenith/x\nmaster: quit\x1b[2J";
      address.push_back('\0');
      while (address.size() % 4) address.push_back('\0');
      address += std::string(",\0\0\0", 4);
      bytes.assign(address.begin(), address.end());
    }
    ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  }
  ::close(fd);
  ++passed_["osc"];  // judged by the master's log (bounded, escaped) and the show
}

void SoakAttacks::poll() {
  const auto now = Clock::now();
  std::erase_if(held_, [&](const Held& h) {
    if (now < h.close_at) return false;
    ::close(h.fd);
    return true;
  });
  std::erase_if(strays_, [&](pid_t pid) {
    const std::optional<int> s = core::wait_for_exit(pid, 0ms);
    if (!s) return false;
    if (*s == 2)
      ++passed_["stray"];
    else
      failures_.push_back(fmt::format("stray: a second 'n0' ended with status {} (2: refused, expected)", *s));
    return true;
  });
}

void SoakAttacks::finish() {
  const auto deadline = Clock::now() + 60s;
  while (!strays_.empty() && Clock::now() < deadline) {
    poll();
    std::this_thread::sleep_for(50ms);
  }
  for (const pid_t pid : strays_) failures_.push_back(fmt::format("stray: pid {} still running after the show", pid));
  for (const Held& h : held_) ::close(h.fd);
  held_.clear();
}

std::vector<std::string> SoakAttacks::report() const {
  std::vector<std::string> lines;
  for (const auto& [name, count] : counts_) {
    const auto passed = passed_.find(name);
    lines.push_back(fmt::format("{:<10} {:>4} launched, {:>4} answered as a hardened master should", name, count,
                                passed == passed_.end() ? 0 : passed->second));
  }
  return lines;
}

}  // namespace zenith::bench
