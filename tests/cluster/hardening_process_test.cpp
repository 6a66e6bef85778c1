// The cluster against stray processes and hostile peers on loopback
// (docs/cluster.md and docs/operator.md, "Threat model"): the `zenith` binary
// as master and two nodes, 32² outputs, small tables. Each test is bounded in
// time and asserts counts, not timings: the machine may be loaded.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cluster/protocol/messages.h"
#include "core/files.h"
#include "core/process.h"
#include "core/strings.h"

namespace zenith::cluster {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
using core::count_of;
using core::read_text;

const fs::path kSource = ZENITH_SOURCE_DIR;
const fs::path kBinary = ZENITH_BINARY;
const fs::path kWork = CLUSTER_TEST_WORK_DIR;

using core::wait_until;

using core::process_gone;

/// Frames in a node's presented.log.
std::size_t presented_count(const fs::path& node_dir) {
  return count_of(read_text(node_dir / "presented.log"), "frame ");
}

/// Whether the peer closed `fd` (read returns 0 or an error) within `timeout`.
bool closed_by_peer(int fd, std::chrono::milliseconds timeout) {
  bool closed = false;
  core::read_until_closed(fd, timeout, closed);  // Reject bytes first, then the end
  return closed;
}

class HardeningProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = kWork / (std::string("hardening-") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    cache_ = kWork / "table-cache";  // shared with cluster.ClusterProcess.* (the same small tables)
    port_ = core::free_loopback_port(
        static_cast<int>(21000 + (getpid() * 13 + std::hash<std::string>{}(info->name())) % 28000));
    setenv("ZENITH_CLUSTER_HARDENING_SECRET", "hardening-test-secret-0123456789", 1);
  }
  void TearDown() override {
    for (const pid_t pid : pids_)
      if (!process_gone(pid)) ::kill(pid, SIGKILL);
    for (const pid_t pid : pids_) core::wait_for_exit(pid, 5000ms);
  }

  /// Two nodes (a, b) with one 32² fisheye output each, 10 Hz; `limits` goes into the config as is.
  fs::path write_config(const std::string& limits = "") {
    std::ofstream(dir_ / "views.json") << R"({"zenith_viewports": 1, "name": "v", "outputs": [
      {"name": "left", "size": [32, 32], "projection": {"type": "fisheye", "fov_deg": 180}},
      {"name": "right", "size": [32, 32], "projection": {"type": "fisheye", "fov_deg": 180}}]})";
    std::ofstream(dir_ / "cluster.json")
        << R"({"zenith_cluster": 1, "name": "hardening", "master": {"host": "127.0.0.1", "port": )" << port_
        << R"(}, "scene": ")" << (kSource / "configs/scenes/earth-sunset.json").string()
        << R"(", "viewports": "views.json",
      "timing": {"heartbeat_ms": 200, "barrier_timeout_ms": 20000, "frame_rate_hz": 10},
      "secret": {"env": "ZENITH_CLUSTER_HARDENING_SECRET"}, "tables": {"sizes": "small", "orders": 4}, )"
        << limits << R"(
      "nodes": [{"name": "a", "host": "127.0.0.1", "outputs": ["left"]}, {"name": "b", "host": "127.0.0.1", "outputs": ["right"]}],
      "output": {"directory": "out", "format": "png"}})";
    return dir_ / "cluster.json";
  }
  pid_t spawn(const std::vector<std::string>& args, const std::string& log) {
    const pid_t pid = core::spawn_process(kBinary, args, dir_ / log, core::LogMode::append);
    pids_.push_back(pid);
    return pid;
  }
  pid_t start_master(const fs::path& config) {
    return spawn({"master", "--cluster", config.string(), "--cache", cache_.string(), "--wait-for-nodes-ms", "120000"},
                 "master.log");
  }
  pid_t start_node(const fs::path& config, const std::string& name, const std::string& as) {
    return spawn({"node", "--cluster", config.string(), "--name", name, "--out", (dir_ / ("out-" + as)).string(),
                  "--cache", (dir_ / "node-cache" / as).string(), "--connect-timeout-ms", "300000"},
                 as + ".log");
  }
  /// Master and nodes a and b, every node past `frames` presented frames.
  pid_t start_cluster(const fs::path& config, std::size_t frames = 5) {
    const pid_t master = start_master(config);
    start_node(config, "a", "a");
    start_node(config, "b", "b");
    EXPECT_TRUE(wait_until([&] { return both_presented_more_than(frames); }, 180s)) << logs();
    return master;
  }
  bool both_presented_more_than(std::size_t frames) const {
    return presented_count(dir_ / "out-a/a") > frames && presented_count(dir_ / "out-b/b") > frames;
  }
  std::string logs() const {
    std::string all;
    for (const auto& entry : fs::directory_iterator(dir_))
      if (entry.path().extension() == ".log")
        all += "---- " + entry.path().filename().string() + "\n" + read_text(entry.path());
    return all;
  }
  /// The pids `zenith cluster` logged for its children ("master started (pid N)", "node 'a' started (pid N)").
  std::vector<pid_t> launched_pids(const std::string& log) const {
    std::vector<pid_t> pids;
    const std::string text = read_text(dir_ / log);
    const std::regex started(R"(started \(pid (\d+)\))");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), started); it != std::sregex_iterator(); ++it)
      pids.push_back(static_cast<pid_t>(std::stol((*it)[1])));
    return pids;
  }
  pid_t start_launcher(const fs::path& config, const std::string& log, const std::string& out = "out-launched") {
    return spawn({"cluster", "--cluster", config.string(), "--frames", "100000", "--out", (dir_ / out).string(),
                  "--cache", cache_.string()},
                 log);
  }

  fs::path dir_, cache_;
  int port_ = 0;
  std::vector<pid_t> pids_;
};

// One stray `zenith node --name left` once caused 467
// replacements in 8 s. A second process with a connected name is refused;
// both sides say why; the node keeps its place.
TEST_F(HardeningProcess, AStrayNodeWithATakenNameIsRefusedOnBothSidesAndTheShowGoesOn) {
  const fs::path config = write_config();
  const pid_t master = start_cluster(config);
  const std::size_t before = presented_count(dir_ / "out-a/a");
  const pid_t stray = start_node(config, "a", "stray");
  EXPECT_EQ(core::wait_for_exit(stray, 120s), std::optional<int>(2)) << "refused: status 2, never retried\n" << logs();
  EXPECT_NE(read_text(dir_ / "stray.log").find("node 'a' is already connected from 127.0.0.1:"), std::string::npos)
      << logs();
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("refused node 'a'"), std::string::npos) << master_log;
  EXPECT_NE(master_log.find("(another process: instance "), std::string::npos) << master_log;
  EXPECT_EQ(count_of(master_log, "reconnected"), 0u) << "the live node was never replaced\n" << master_log;
  EXPECT_TRUE(wait_until([&] { return presented_count(dir_ / "out-a/a") > before + 10; }, 60s)) << logs();
  ::kill(master, SIGTERM);
  EXPECT_EQ(core::wait_for_exit(master, 30s), std::optional<int>(0)) << logs();
}

// 1 MiB TableChunk headers were once accepted before the
// handshake, from any number of peers (300: 22 → 349 MB, never returned).
TEST_F(HardeningProcess, UnauthenticatedPeersAreBoundedInMessageSizeAndNumber) {
  const fs::path config = write_config(R"("limits": {"max_unauthenticated_connections": 4},)");
  start_cluster(config);
  TableChunk chunk;
  chunk.index = 0;
  chunk.bytes.assign(1024 * 1024, 0x5a);
  const std::vector<std::uint8_t> frame = encode(Message{chunk});
  for (int i = 0; i < 6; ++i) {
    const int fd = core::connect_loopback(port_);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::send(fd, frame.data(), kHeaderBytes, MSG_NOSIGNAL), static_cast<ssize_t>(kHeaderBytes));
    EXPECT_TRUE(closed_by_peer(fd, 10s)) << "a 1 MiB header before the handshake is closed at once\n" << logs();
    ::close(fd);
  }
  // Silent peers: at most 4 stay; each new one closes the oldest.
  std::vector<int> silent;
  for (int i = 0; i < 24; ++i) {
    silent.push_back(core::connect_loopback(port_));
    std::this_thread::sleep_for(20ms);
  }
  std::this_thread::sleep_for(1500ms);
  int closed = 0;
  for (const int fd : silent) closed += closed_by_peer(fd, 0ms) ? 1 : 0;
  EXPECT_GE(closed, 20) << logs();
  for (const int fd : silent) ::close(fd);
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("exceeds the 1026-byte limit before the handshake"), std::string::npos) << master_log;
  EXPECT_NE(master_log.find("limits.max_unauthenticated_connections"), std::string::npos) << master_log;
  // The nodes never noticed.
  const std::size_t before = presented_count(dir_ / "out-b/b");
  EXPECT_TRUE(wait_until([&] { return presented_count(dir_ / "out-b/b") > before + 10; }, 60s)) << logs();
}

// A kill -9 or SIGTERM of `zenith cluster` once left the master
// and every node running under PID 1, holding their ports.
TEST_F(HardeningProcess, TheLaunchersChildrenDieWithItAndItsSignalsAreForwarded) {
  const fs::path config = write_config();
  const pid_t killed = start_launcher(config, "cluster-killed.log");
  ASSERT_TRUE(wait_until([&] { return presented_count(dir_ / "out-launched/a") > 3; }, 180s)) << logs();
  const std::vector<pid_t> children = launched_pids("cluster-killed.log");
  ASSERT_EQ(children.size(), 3u) << logs();
  ::kill(killed, SIGKILL);
  EXPECT_TRUE(wait_until([&] { return std::all_of(children.begin(), children.end(), process_gone); }, 30s))
      << "orphans left after kill -9 of the launcher\n"
      << logs();

  const pid_t stopped = start_launcher(config, "cluster-stopped.log", "out-stopped");
  ASSERT_TRUE(wait_until([&] { return presented_count(dir_ / "out-stopped/b") > 3; }, 180s)) << logs();
  const std::vector<pid_t> second = launched_pids("cluster-stopped.log");
  ::kill(stopped, SIGHUP);
  const std::optional<int> status = core::wait_for_exit(stopped, 60s);
  ASSERT_TRUE(status.has_value()) << logs();
  EXPECT_NE(*status, 0) << "stopped by a signal is not a finished show";
  EXPECT_NE(read_text(dir_ / "cluster-stopped.log").find("Hangup received: forwarding SIGTERM to the master"),
            std::string::npos)
      << logs();
  EXPECT_TRUE(wait_until([&] { return std::all_of(second.begin(), second.end(), process_gone); }, 30s)) << logs();
}

// A new master that could not bind once let its nodes join the
// master already on the port (812 replacements between the two sets).
TEST_F(HardeningProcess, ALauncherWhoseMasterCannotBindStartsNoNode) {
  const fs::path config = write_config();
  const int taken = ::socket(AF_INET, SOCK_STREAM, 0);
  const int yes = 1;  // as the master binds: an older connection's TIME_WAIT does not block it
  ::setsockopt(taken, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port_));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(taken, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(taken, 16), 0);
  const pid_t launcher = start_launcher(config, "cluster.log");
  const std::optional<int> status = core::wait_for_exit(launcher, 120s);
  ASSERT_TRUE(status.has_value()) << logs();
  EXPECT_NE(*status, 0);
  const std::string log = read_text(dir_ / "cluster.log");
  EXPECT_NE(log.find("the master could not start"), std::string::npos) << log;
  EXPECT_EQ(count_of(log, "node 'a' started"), 0u) << log;
  ::fcntl(taken, F_SETFL, O_NONBLOCK);
  EXPECT_LT(::accept(taken, nullptr, nullptr), 0) << "no node knocked on the other master's port";
  ::close(taken);
}

// A paced show's frames go out on a schedule whose period the protocol bounds:
// --fps 0.4 once started the master and its nodes, then stopped the master at
// the first frame ("cannot encode: FrameSchedule.period_ns ..."). Now the rate
// is checked with the show, before any node starts, naming the option and the range.
TEST_F(HardeningProcess, ALauncherWhoseShowRateNoScheduleCanHoldStartsNoNode) {
  const fs::path config = write_config();
  const pid_t launcher = spawn({"cluster", "--cluster", config.string(), "--show",
                                (kSource / "configs/shows/earth-lunar-eclipse-2029-buenos-aires.json").string(),
                                "--fps", "0.004", "--out", (dir_ / "out-rate").string(), "--cache", cache_.string()},
                               "cluster-rate.log");
  const std::optional<int> status = core::wait_for_exit(launcher, 120s);
  ASSERT_TRUE(status.has_value()) << logs();
  EXPECT_NE(*status, 0);
  const std::string log = read_text(dir_ / "cluster-rate.log");
  EXPECT_NE(log.find("master: 0.004 frames per second (--fps): a paced show presents 0.01 to 240 frames per second"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("the master could not start"), std::string::npos) << log;
  EXPECT_EQ(count_of(log, "node 'a' started"), 0u) << log;
}

}  // namespace
}  // namespace zenith::cluster
