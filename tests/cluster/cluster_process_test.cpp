// Multi-process tests of the running cluster: the `zenith` binary as master
// and nodes on loopback, headless, with tiny outputs and small tables
// (docs/cluster.md, "Tests"). Each test is bounded in time.
#include <arpa/inet.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

#include "cluster/operator/osc_packet.h"
#include "cluster/protocol/frame_decoder.h"
#include "cluster/protocol/handshake.h"
#include "cluster/protocol/messages.h"
#include "core/files.h"
#include "core/process.h"
#include "core/strings.h"
#include "image/image_io.h"
#include "image/tone_mapping.h"
#include "test_support.h"
#include "tests/cluster/check_output.h"
#include "tests/cluster/http_client.h"
#include "tests/cluster/webdriver.h"

namespace zenith::cluster {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

const fs::path kSource = ZENITH_SOURCE_DIR;
const fs::path kBinary = ZENITH_BINARY;
const fs::path kWork = CLUSTER_TEST_WORK_DIR;
constexpr const char* kSecretVar = "ZENITH_CLUSTER_TEST_SECRET";
constexpr int kQuadrantPx = 64;

/// A child process with its output in a log file.
struct Child {
  pid_t pid = -1;
  fs::path log;
};

Child spawn(const std::vector<std::string>& args, const fs::path& log) {
  return Child{core::spawn_process(kBinary, args, log, core::LogMode::append), log};
}

/// The exit status (128 + signal when killed), or nullopt on timeout.
std::optional<int> wait_exit(const Child& c, std::chrono::milliseconds timeout) {
  const std::optional<int> status = core::wait_for_exit(c.pid, timeout);
  if (status && *status < 0) return std::nullopt;
  return status;
}

void kill_hard(const Child& c) {
  kill(c.pid, SIGKILL);
  wait_exit(c, 5000ms);
}

using core::count_of;
using core::read_text;

/// "frame N state DIGEST tables BODY=HASH,..." lines of a node's presented.log.
struct Presented {
  std::uint64_t frame;
  std::string digest;
  std::string tables;  ///< "Earth=0123456789abcdef"
  double show_time_s = -1.0;
};
std::vector<Presented> presented(const fs::path& node_dir) {
  std::vector<Presented> out;
  std::ifstream in(node_dir / "presented.log");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string word, state, digest, tables_word, tables;
    std::uint64_t frame = 0;
    if (fields >> word >> frame >> state >> digest >> tables_word >> tables) {
      out.push_back({frame, digest, tables});
      std::string time_word;
      fields >> time_word >> out.back().show_time_s;
    }
  }
  return out;
}

using core::wait_until;

std::vector<Presented> expect_in_sync(const fs::path& out, std::uint64_t last);

/// A cluster of 3 nodes on loopback rendering a 128² dome master as four 64²
/// quadrants: node a renders two, b and c one each.
class ClusterProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = kWork / info->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    cache_ = kWork / "table-cache";  // shared by the tests (same small tables)
    port_ = static_cast<int>(20000 + (getpid() * 7 + std::hash<std::string>{}(info->name())) % 30000);
    // Other test runs share this machine: move on while a port of the test's is taken. Its ports:
    // the master's, the control port, the console's HTTP and OSC, the browser's two, the standby's.
    port_ = core::free_loopback_port(port_, 7);
    standby_port_ = port_ + 6;
    setenv(kSecretVar, "cluster-test-secret-0123456789", 1);
  }
  void TearDown() override {
    for (const Child& c : children_)
      if (kill(c.pid, 0) == 0) kill_hard(c);
  }

  /// The cluster config: 3 nodes, small tables; `standby_port` > 0 adds a standby master on 127.0.0.1 there.
  /// The frame barrier (lookahead_frames 0): these tests check that every node presents every frame,
  /// which the barrier guarantees however slowly three llvmpipe nodes render on a loaded 2-core
  /// machine; scheduled frames drop what a node cannot render in time, and are tested on the
  /// network rig (network_rig_test.cpp) and the hardening tests.
  fs::path write_config(int frame_rate_hz, int barrier_timeout_ms = 20000, int heartbeat_ms = 200, int standby_port = 0,
                        const std::string& file = "cluster.json") {
    std::ofstream v(dir_ / "quadrants.json");
    v << R"({"zenith_viewports": 1, "name": "q", "outputs": [)";
    const char* names[4] = {"top-left", "top-right", "bottom-left", "bottom-right"};
    for (int i = 0; i < 4; ++i) {
      const int cx = (i % 2 == 0) ? kQuadrantPx : 0, cy = (i < 2) ? kQuadrantPx : 0;
      v << (i ? "," : "") << R"({"name": ")" << names[i] << R"(", "size": [)" << kQuadrantPx << ", " << kQuadrantPx
        << R"(], "projection": {"type": "fisheye", "fov_deg": 180, "centre_x_px": )" << cx << R"(, "centre_y_px": )"
        << cy << R"(, "radius_px": )" << kQuadrantPx << "}}";
    }
    v << "]}";
    v.close();
    std::ofstream c(dir_ / file);
    c << R"({"zenith_cluster": 1, "name": "test-dome", "master": {"host": "127.0.0.1", "port": )" << port_ << R"(},)"
      << (standby_port > 0 ? R"("standby": {"host": "127.0.0.1", "port": )" + std::to_string(standby_port) + "}," : "")
      << R"(
      "scene": ")"
      << (kSource / "configs/scenes/earth-sunset.json").string() << R"(", "viewports": "quadrants.json",
      "timing": {"heartbeat_ms": )"
      << heartbeat_ms << R"(, "barrier_timeout_ms": )" << barrier_timeout_ms << R"(, "frame_rate_hz": )"
      << frame_rate_hz << R"(, "lookahead_frames": 0},
      "secret": {"env": ")"
      << kSecretVar << R"("}, "tables": {"sizes": "small", "orders": 4},
      "nodes": [{"name": "a", "host": "127.0.0.1", "outputs": ["top-left", "top-right"]},
                {"name": "b", "host": "127.0.0.1", "outputs": ["bottom-left"]},
                {"name": "c", "host": "127.0.0.1", "outputs": ["bottom-right"]}],
      "output": {"directory": "out", "format": "png"}})";
    c.close();
    return dir_ / file;
  }

  /// Frames scheduled `frames` ahead of their moment in `config` (written by write_config).
  static void use_lookahead(const fs::path& config, int frames) {
    std::string text = read_text(config);
    text.replace(text.find(R"("lookahead_frames": 0)"), 21, fmt::format(R"("lookahead_frames": {})", frames));
    std::ofstream(config) << text;
  }
  /// An LTC track at 25 fps from `start` (`zenith timecode write`), `speed` × real time: its path.
  /// Throws where it cannot be written.
  fs::path write_ltc(const std::string& start, int seconds, const std::string& speed = "1") {
    const fs::path wav = dir_ / "ltc.wav";
    const Child writer = spawn({"timecode", "write", wav.string(), "--start", start, "--rate", "25", "--seconds",
                                std::to_string(seconds), "--speed", speed},
                               dir_ / "timecode.log");
    if (wait_exit(writer, 30s) != std::optional<int>(0))  // thrown: the test fails here, not at a silent master
      throw std::runtime_error("zenith timecode write failed: " + read_text(dir_ / "timecode.log"));
    return wav;
  }

  Child start_master(const fs::path& config, std::uint64_t frames, int wait_for_nodes_ms = 120000,
                     const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = {"master",
                                     "--cluster",
                                     config.string(),
                                     "--frames",
                                     std::to_string(frames),
                                     "--cache",
                                     cache_.string(),
                                     "--wait-for-nodes-ms",
                                     std::to_string(wait_for_nodes_ms)};
    args.insert(args.end(), extra.begin(), extra.end());
    children_.push_back(spawn(args, dir_ / "master.log"));
    return children_.back();
  }
  /// `zenith master --standby` with the master's arguments, logging to `log`.
  Child start_standby(const fs::path& config, std::uint64_t frames, const std::string& log = "standby.log") {
    children_.push_back(spawn({"master", "--standby", "--cluster", config.string(), "--frames", std::to_string(frames),
                               "--cache", (dir_ / "standby-cache").string(), "--wait-for-nodes-ms", "120000"},
                              dir_ / log));
    return children_.back();
  }
  Child start_node(const fs::path& config, const std::string& name, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = {"node",
                                     "--cluster",
                                     config.string(),
                                     "--name",
                                     name,
                                     "--out",
                                     (dir_ / "out").string(),
                                     "--cache",
                                     (dir_ / "node-cache" / name).string(),
                                     "--connect-timeout-ms",
                                     "300000"};
    args.insert(args.end(), extra.begin(), extra.end());
    children_.push_back(spawn(args, dir_ / (name + ".log")));
    return children_.back();
  }
  /// The master with the sun standing still and the operator console on `http` (OSC on `osc`),
  /// `extra` arguments after those, and the three nodes.
  Child start_operated_cluster(const fs::path& config, int http, int osc, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = {"--sun-step-deg",     "0",          "--operator-port",
                                     std::to_string(http), "--osc-port", std::to_string(osc)};
    args.insert(args.end(), extra.begin(), extra.end());
    const Child master = start_master(config, 0, 120000, args);
    for (const char* n : {"a", "b", "c"}) start_node(config, n);
    return master;
  }
  /// The sunset fixture (tests/data/shows/offline-sunset.json: 2.5 s, two table versions) played
  /// live at 2 fps, looping, with the operator console on `http` (and OSC on `osc`), and the three
  /// nodes rendering its scene.
  Child start_sunset_show(const fs::path& config, int http, std::optional<int> osc = std::nullopt) {
    std::vector<std::string> args = {"--show",
                                     (kSource / "tests/data/shows/offline-sunset.json").string(),
                                     "--fps",
                                     "2",
                                     "--loop",
                                     "--operator-port",
                                     std::to_string(http)};
    if (osc) args.insert(args.end(), {"--osc-port", std::to_string(*osc)});
    const Child master = start_master(config, 0, 120000, args);
    for (const char* n : {"a", "b", "c"})
      start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
    return master;
  }
  /// Waits until node c presented a frame after `after_frame` (when given), quits the master
  /// through the operator console on `http`, and expects master and nodes to exit with status 0
  /// and every node to have presented the same frames in sync; node a's presented frames.
  std::vector<Presented> quit_in_sync(int http, const Child& master,
                                      std::optional<std::uint64_t> after_frame = std::nullopt) {
    if (after_frame) {
      EXPECT_TRUE(wait_until(
          [&] { return !presented(dir_ / "out/c").empty() && presented(dir_ / "out/c").back().frame > *after_frame; },
          120s))
          << logs();
    }
    const test::HttpReply quit =
        test::http_request(http, boost::beast::http::verb::post, "/api/command", R"({"command": "quit"})");
    EXPECT_EQ(quit.status, 200) << quit.body;
    EXPECT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
    expect_nodes_exit_cleanly(master);
    return expect_in_sync(dir_ / "out", presented(dir_ / "out/a").back().frame);
  }
  /// Expects every child but `master` (the nodes) to exit with status 0 within 20 s.
  void expect_nodes_exit_cleanly(const Child& master) const {
    for (const Child& c : children_) {
      if (c.pid != master.pid) {
        EXPECT_EQ(wait_exit(c, 20s), std::optional<int>(0)) << logs();
      }
    }
  }
  /// Whether every node (a, b, c) presented frame `frame` or a later one.
  bool all_nodes_past(std::uint64_t frame) const {
    for (const char* n : {"a", "b", "c"}) {
      const auto p = presented(dir_ / "out" / n);
      if (p.empty() || p.back().frame < frame) return false;
    }
    return true;
  }
  /// Every one of `texts` is in the master's log (each one missing fails, showing the log).
  void expect_in_master_log(std::initializer_list<std::string> texts) const {
    const std::string master_log = read_text(dir_ / "master.log");
    for (const std::string& text : texts)
      EXPECT_NE(master_log.find(text), std::string::npos) << "'" << text << "' not in the master's log:\n"
                                                          << master_log;
  }
  std::string logs() const {
    std::string all;
    for (const char* n : {"master", "standby", "standby-2", "a", "b", "c", "cluster"})
      if (fs::exists(dir_ / (std::string(n) + ".log")))
        all += "---- " + std::string(n) + ".log\n" + read_text(dir_ / (std::string(n) + ".log"));
    return all;
  }

  fs::path dir_, cache_;
  int port_ = 0, standby_port_ = 0;
  std::vector<Child> children_;
};

/// How many values of `tile` differ from those of quadrant `q` of `whole` (0
/// top-left, 1 top-right, 2 bottom-left, 3 bottom-right; tiles of kQuadrantPx²).
int values_differing_from_quadrant(const image::LinearImage& tile, const image::LinearImage& whole, std::size_t q) {
  const int x0 = (q % 2) * kQuadrantPx, y0 = (q / 2) * kQuadrantPx;
  int differing = 0;
  for (int y = 0; y < kQuadrantPx; ++y)
    for (int x = 0; x < kQuadrantPx * 3; ++x)
      differing += tile.rgb[y * kQuadrantPx * 3 + x] != whole.rgb[(y0 + y) * whole.width * 3 + x0 * 3 + x];
  return differing;
}

/// How many values of `tile` are more than one 8-bit sRGB code from those of
/// quadrant `q` of `whole`: a thumbnail is tone mapped and encoded on the GPU
/// (float exp and pow), the file on the CPU, so a value within a few ulp of a
/// rounding boundary may land on the neighbouring code (render/display/display_encoder.h).
int values_beyond_a_code_from_quadrant(const image::LinearImage& tile, const image::LinearImage& whole, std::size_t q) {
  const int x0 = (q % 2) * kQuadrantPx, y0 = (q / 2) * kQuadrantPx;
  const auto code = [](float linear) { return static_cast<int>(std::lround(255.0f * image::srgb_encode(linear))); };
  int differing = 0;
  for (int y = 0; y < kQuadrantPx; ++y)
    for (int x = 0; x < kQuadrantPx * 3; ++x)
      differing += std::abs(code(tile.rgb[y * kQuadrantPx * 3 + x]) -
                            code(whole.rgb[(y0 + y) * whole.width * 3 + x0 * 3 + x])) > 1;
  return differing;
}

/// Frames 0..n-1 in order, each once.
void expect_contiguous(const std::vector<Presented>& p, std::uint64_t first, std::uint64_t last,
                       const std::string& who) {
  ASSERT_EQ(p.size(), last - first + 1) << who;
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p[i].frame, first + i) << who << " line " << i;
}

TEST_F(ClusterProcess, ThreeNodesPresentEveryFrameAndStitchToASingleRender) {
  const fs::path config = write_config(20);
  const Child cluster = spawn({"cluster", "--cluster", config.string(), "--frames", "5", "--out",
                               (dir_ / "out").string(), "--cache", cache_.string(), "--stitch-frame", "0"},
                              dir_ / "cluster.log");
  children_.push_back(cluster);
  ASSERT_EQ(wait_exit(cluster, 280s), std::optional<int>(0)) << logs();

  // Every node presented frames 0..4 in order with the same state on every node.
  const auto a = presented(dir_ / "out/a"), b = presented(dir_ / "out/b"), c = presented(dir_ / "out/c");
  expect_contiguous(a, 0, 4, "a");
  expect_contiguous(b, 0, 4, "b");
  expect_contiguous(c, 0, 4, "c");
  for (std::size_t i = 0; i < a.size() && i < b.size() && i < c.size(); ++i) {
    EXPECT_EQ(a[i].digest, b[i].digest) << "frame " << i;
    EXPECT_EQ(a[i].digest, c[i].digest) << "frame " << i;
    if (i > 0) {
      EXPECT_NE(a[i].digest, a[i - 1].digest) << "the sun moves between frames";
    }
  }
  const std::vector<std::pair<std::string, std::string>> files = {
      {"a", "top-left"}, {"a", "top-right"}, {"b", "bottom-left"}, {"c", "bottom-right"}};
  for (const auto& [node, output] : files)
    for (int f = 0; f < 5; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "frame-%06d.png", f);
      EXPECT_TRUE(fs::exists(dir_ / "out" / node / output / name)) << node << "/" << output << "/" << name;
    }
  for (const auto& entry : fs::recursive_directory_iterator(dir_ / "out"))
    EXPECT_NE(entry.path().extension(), ".partial") << entry.path();

  // The quadrants of frame 0 equal a single-process render of the whole dome master, bit for bit.
  const fs::path single = dir_ / "single.png";
  const Child render = spawn(
      {"render", "--scene", (kSource / "configs/scenes/earth-sunset.json").string(), "--projection", "fisheye",
       "--size", "128x128", "--tables", "small", "--orders", "4", "--cache", cache_.string(), "--out", single.string()},
      dir_ / "render.log");
  children_.push_back(render);
  ASSERT_EQ(wait_exit(render, 200s), std::optional<int>(0)) << read_text(dir_ / "render.log");
  const image::LinearImage whole = image::read_image(single);
  ASSERT_EQ(whole.width, 2 * kQuadrantPx);
  for (std::size_t q = 0; q < files.size(); ++q) {
    const auto& [node, output] = files[q];
    const image::LinearImage tile = image::read_image(dir_ / "out" / node / output / "frame-000000.png");
    ASSERT_EQ(tile.width, kQuadrantPx);
    const int differing = values_differing_from_quadrant(tile, whole, q);
    EXPECT_EQ(differing, 0) << output << ": values differing from the single-process render";
  }
  // And so does the stitched image `zenith cluster` wrote.
  const image::LinearImage stitched = image::read_image(dir_ / "out/stitched/frame-000000.png");
  EXPECT_EQ(stitched.rgb, whole.rgb);
}

/// Pixels of `image` brighter than 1.5 times the median of their 5×5
/// neighbourhood and by more than 4 codes of 8-bit sRGB in green: the stars and
/// the Moon of a night frame (a splat covers at most 2 × 2 pixels). Not twice:
/// under the evening show's full Moon the sky is lit by it (moonlight from the
/// tables, docs/night-sky.md), and on a 128² dome master's 1.4° pixels no star
/// doubles the moonlit sky's radiance any more; 1.5 times still finds four.
int point_sources(const image::LinearImage& image) {
  int count = 0;
  for (int y = 2; y + 2 < image.height; ++y)
    for (int x = 2; x + 2 < image.width; ++x) {
      std::vector<float> around;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) around.push_back(image.rgb[((y + dy) * image.width + x + dx) * 3 + 1]);
      std::nth_element(around.begin(), around.begin() + 12, around.end());
      const float v = image.rgb[(y * image.width + x) * 3 + 1], median = around[12];
      count += v > 1.5f * median && image::srgb_encode(v) - image::srgb_encode(median) > 4.0f / 255.0f;
    }
  return count;
}

// The evening show (configs/shows/earth-evening-hayden.json:
// dusk at the Hayden Planetarium, the stars coming out, the full Moon rising)
// rendered on the cluster's three nodes shows at each frame the same stars in
// every quadrant, which stitch into the single-process dome master: no seam
// between quadrants, no node a frame behind. The stars' sums are the same bit
// for bit (a constant step of the star accumulator; night_sky_test.cpp,
// TheQuadrantsOfADomeMaster… checks it on the stars alone), but the sky under
// them is not: the quadrants' rays come from other projection parameters,
// last float bits apart, and at an exposure of 10⁵ a few values of the dark
// sky sit within that rounding of a code boundary — so no value more than one
// code away and at most 0.2 % one code away. Two frames 58 s into the show
// (sun 17° down, exposure 1.8e5), 128² dome master, small tables.
TEST_F(ClusterProcess, TheEveningShowShowsTheSameStarsOnEveryNodeWithoutASeam) {
  if (!fs::exists("/usr/share/stellarium/stars/default/stars_0_0v0_8.cat"))
    GTEST_SKIP() << "stellarium-data is not installed: scripts/bootstrap installs it";
  const fs::path config = write_config(30);
  const fs::path show = kSource / "configs/shows/earth-evening-hayden.json";
  const std::vector<std::string> frames = {"--fps", "30", "--from", "1740", "--to", "1741", "--contact-sheet", "none"};
  std::vector<std::string> on_cluster = {
      "show",          "render",  "--show",        show.string(), "--cluster",
      config.string(), "--cache", cache_.string(), "--out",       (dir_ / "cluster").string()};
  on_cluster.insert(on_cluster.end(), frames.begin(), frames.end());
  const Child cluster = spawn(on_cluster, dir_ / "cluster.log");
  children_.push_back(cluster);
  ASSERT_EQ(wait_exit(cluster, 400s), std::optional<int>(0)) << read_text(dir_ / "cluster.log");

  std::vector<std::string> single = {"show",         "render",        "--show",   show.string(),
                                     "--projection", "fisheye",       "--size",   "128x128",
                                     "--tables",     "small",         "--orders", "4",
                                     "--cache",      cache_.string(), "--out",    (dir_ / "single").string()};
  single.insert(single.end(), frames.begin(), frames.end());
  const Child whole_render = spawn(single, dir_ / "single.log");
  children_.push_back(whole_render);
  ASSERT_EQ(wait_exit(whole_render, 300s), std::optional<int>(0)) << read_text(dir_ / "single.log");

  const char* quadrants[4] = {"top-left", "top-right", "bottom-left", "bottom-right"};
  for (int frame : {1740, 1741}) {
    const image::LinearImage whole = image::read_image(dir_ / fmt::format("single/fisheye/fisheye.{:06d}.png", frame));
    ASSERT_EQ(whole.width, 2 * kQuadrantPx);
    const int stars = point_sources(whole);
    std::printf("frame %d: %d point sources\n", frame, stars);
    EXPECT_GE(stars, 3) << "frame " << frame << ": the stars are out";
    for (std::size_t q = 0; q < 4; ++q) {
      const image::LinearImage tile =
          image::read_image(dir_ / fmt::format("cluster/{0}/{0}.{1:06d}.png", quadrants[q], frame));
      EXPECT_EQ(values_beyond_a_code_from_quadrant(tile, whole, q), 0)
          << quadrants[q] << ", frame " << frame << ": values beyond a code from the single-process dome master";
      EXPECT_LE(values_differing_from_quadrant(tile, whole, q), kQuadrantPx * kQuadrantPx * 3 / 500)
          << quadrants[q] << ", frame " << frame;
    }
  }
}

/// Nodes a and c presented every frame up to the same last one; b presented
/// 0..last_before, then — back after a kill or a stall — a contiguous run from
/// a later frame boundary; every frame b presented has a's state.
void expect_b_rejoined(const fs::path& out, std::uint64_t last_before) {
  const auto a = presented(out / "a"), bp = presented(out / "b"), c = presented(out / "c");
  ASSERT_FALSE(a.empty());
  expect_contiguous(a, 0, a.back().frame, "a");
  expect_contiguous(c, 0, c.back().frame, "c");
  EXPECT_EQ(a.back().frame, c.back().frame);
  std::size_t split = 0;
  while (split < bp.size() && bp[split].frame <= last_before) ++split;
  ASSERT_LT(split, bp.size());
  expect_contiguous(std::vector<Presented>(bp.begin(), bp.begin() + split), 0, last_before, "b before");
  EXPECT_GT(bp[split].frame, last_before + 1) << "b rejoined later, at a frame boundary";
  expect_contiguous(std::vector<Presented>(bp.begin() + split, bp.end()), bp[split].frame, bp.back().frame, "b after");
  for (const Presented& p : bp) EXPECT_EQ(p.digest, a[p.frame].digest) << "frame " << p.frame;
}

/// A show chasing the house's LTC (docs/shows.md, "Chasing timecode"), here a WAV played in real time
/// from the master's start, 0.1 % fast, from 20 s before the show's start (the first frame may take
/// 15 s on a loaded 2-core machine: tables, three nodes): the show holds at its start
/// while the timecode is before it, then every scheduled frame carries the timecode's time at its
/// moment (consecutive frames a period × 1.001 apart, to a millisecond, or whole periods where the
/// schedule moved on), and when the audio ends the show freewheels, then holds its frame.
TEST_F(ClusterProcess, AShowChasingLtcFollowsItFrameForFrameThenHoldsWhenItStops) {
  fs::path config = write_config(10);
  use_lookahead(config, 3);  // scheduled frames, so each frame has its moment on the master's clock
  const fs::path wav = write_ltc("00:59:40:00", 26, "1.001");
  const fs::path recording = dir_ / "recorded.json";
  const Child master = start_master(config, 280, 120000,
                                    {"--show", (kSource / "tests/data/shows/chase-sunset.json").string(), "--ltc-file",
                                     wav.string(), "--record", recording.string()});
  for (const char* n : {"a", "b", "c"})
    start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
  ASSERT_EQ(wait_exit(master, 180s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);
  expect_in_master_log({"master: chasing LTC from", "is before the show's start: the show holds at its start",
                        "master: timecode locked", "ppm)", "master: timecode freewheeling",
                        "master: timecode held (no timecode)"});

  const nlohmann::json frames = nlohmann::json::parse(read_text(recording))["recording"]["frames"];
  ASSERT_GE(frames.size(), 150u);
  std::vector<double> t;
  for (const nlohmann::json& f : frames) t.push_back(f["show_time_s"].get<double>());
  EXPECT_EQ(t[1], 0.0) << "the timecode was before the show's start";
  const double held = t.back(), period = 0.1 * 1.001;
  int followed = 0, held_frames = 0;
  for (std::size_t i = 1; i + 1 < t.size(); ++i) {
    EXPECT_GE(t[i + 1], t[i]) << "frame " << i + 1 << ": the show never steps back";
    if (t[i] > 0.0 && t[i + 1] < held) {
      const double step = t[i + 1] - t[i];
      const double periods = std::max(1.0, std::round(step / period));
      EXPECT_NEAR(step, periods * period, 0.001) << "frames " << i << " and " << i + 1;
      ++followed;
    }
    held_frames += t[i] == held;
  }
  EXPECT_GE(followed, 40) << "frames that followed the timecode";
  EXPECT_GE(held_frames, 5) << "frames held after the timecode stopped";
  EXPECT_GT(held, 5.0);
  EXPECT_LT(held, 6.0 * 1.001 + 1.0 + 0.5) << "the audio ends 6 s past the start: a second of freewheel, then held";

  // The recording of the chased show plays back without the timecode, frame for frame: every frame a
  // node presented live has the same state digest in the replay.
  std::map<std::uint64_t, std::string> live;
  for (const Presented& p : presented(dir_ / "out/a")) live[p.frame] = p.digest;
  fs::rename(dir_ / "out", dir_ / "out-live");
  for (const char* n : {"master", "a", "b", "c"})
    fs::rename(dir_ / (std::string(n) + ".log"), dir_ / (std::string(n) + "-live.log"));
  children_.clear();
  const Child replay = start_master(config, 0, 120000, {"--show", recording.string(), "--unpaced"});
  for (const char* n : {"a", "b", "c"})
    start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
  ASSERT_EQ(wait_exit(replay, 180s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(replay);
  int compared = 0;
  for (const Presented& p : presented(dir_ / "out/a"))
    if (const auto it = live.find(p.frame); it != live.end()) {
      EXPECT_EQ(p.digest, it->second) << "frame " << p.frame;
      ++compared;
    }
  EXPECT_GE(compared, 150) << "frames presented in both runs";
}

TEST_F(ClusterProcess, KilledNodeRestartsAndRejoinsWhileTheOthersSkipNoFrame) {
  const fs::path config = write_config(10);
  const Child master = start_master(config, 0);
  start_node(config, "a");
  Child b = start_node(config, "b");
  start_node(config, "c");
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").size() >= 5; }, 240s)) << logs();
  kill(b.pid, SIGKILL);
  ASSERT_EQ(wait_exit(b, 5s), std::optional<int>(128 + SIGKILL));
  const std::uint64_t last_before = presented(dir_ / "out/b").back().frame;
  const std::size_t a_at_kill = presented(dir_ / "out/a").size();
  // The others go on without b.
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= a_at_kill + 5; }, 60s)) << logs();
  b = start_node(config, "b");
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").size() >= 5 + 3; }, 240s)) << logs();
  kill(master.pid, SIGTERM);
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  for (const Child& c : children_)
    if (c.pid != master.pid && kill(c.pid, 0) == 0) {
      EXPECT_EQ(wait_exit(c, 20s), std::optional<int>(0)) << logs();
    }

  expect_b_rejoined(dir_ / "out", last_before);
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("node 'b'"), std::string::npos);
  EXPECT_NE(master_log.find("disconnected"), std::string::npos) << master_log;
}

using zenith::testing::check_json;

TEST_F(ClusterProcess, ClusterCheckMeasuresEveryNodesLinkThenLetsItGo) {
  const fs::path config = write_config(10);
  // No node: each is reported as never connected, and the check fails (exit 2) once the wait is over.
  const Child empty =
      spawn({"cluster", "check", "--cluster", config.string(), "--json", "--wait-s", "1"}, dir_ / "check-empty.log");
  children_.push_back(empty);
  ASSERT_EQ(wait_exit(empty, 30s), 2) << read_text(empty.log);
  const nlohmann::json none = check_json(read_text(empty.log));
  ASSERT_TRUE(none.is_object()) << read_text(empty.log);
  EXPECT_EQ(none["verdict"], "fail");
  ASSERT_EQ(none["nodes"].size(), 3u);
  EXPECT_EQ(none["nodes"][2]["connected"], false);
  EXPECT_NE(none["nodes"][2]["problem"].get<std::string>().find("nothing connected as 'c' within 1 s"),
            std::string::npos);

  const Child check = spawn({"cluster", "check", "--cluster", config.string(), "--json", "--seconds", "1", "--fill-mib",
                             "8", "--wait-s", "150"},
                            dir_ / "check.log");
  children_.push_back(check);
  std::vector<Child> nodes;
  for (const char* n : {"a", "b", "c"}) nodes.push_back(start_node(config, n));
  ASSERT_EQ(wait_exit(check, 200s), 0) << read_text(check.log) << logs();
  const nlohmann::json j = check_json(read_text(check.log));
  ASSERT_TRUE(j.is_object()) << read_text(check.log);
  EXPECT_EQ(j["verdict"], "ok") << j.dump(2);
  EXPECT_EQ(j["cluster"], "test-dome");
  ASSERT_EQ(j["nodes"].size(), 3u);
  for (const nlohmann::json& n : j["nodes"]) {
    SCOPED_TRACE(n.dump(2));
    EXPECT_EQ(n["verdict"], "ok");
    EXPECT_EQ(n["reported"], true);
    // A ping every 10 ms for 1 s (timers of a loaded machine run late, never early).
    const auto pings = n["datagrams"]["pings_sent"].get<int>();
    EXPECT_GE(pings, 40);
    EXPECT_LE(pings, 101);
    EXPECT_EQ(n["datagrams"]["pongs"].get<int>(), pings) << "loopback loses nothing";
    EXPECT_EQ(n["datagrams"]["loss_to_node"].get<double>(), 0.0);
    EXPECT_EQ(n["fill"]["bytes"].get<std::uint64_t>(), 8u << 20);
    EXPECT_GT(n["throughput_mbit_s"].get<double>(), 100.0);
    const nlohmann::json& rt = n["round_trip_ms"];
    EXPECT_LE(rt["min"].get<double>(), rt["p50"].get<double>());
    EXPECT_LE(rt["p99"].get<double>(), rt["max"].get<double>());
    // One machine, one CLOCK_MONOTONIC and one wall clock: both offsets are the estimate's error.
    EXPECT_LT(std::abs(n["clock"]["steady_offset_ms"].get<double>()), 1.0);
    EXPECT_LT(std::abs(n["clock"]["wall_offset_ms"].get<double>()), 5.0);
    EXPECT_LT(n["clock"]["uncertainty_ms"].get<double>(), 0.5);
  }
  // The nodes leave as at a show's end (their services start them again for the next master).
  for (const Child& n : nodes) EXPECT_EQ(wait_exit(n, 30s), 0) << read_text(n.log);
  EXPECT_NE(read_text(dir_ / "a.log").find("link check done"), std::string::npos);
}

TEST_F(ClusterProcess, NodesExitWithAClearMessageWhenTheMasterStaysGonePastTheReconnectTime) {
  const fs::path config = write_config(10, 20000, 200);
  const Child master = start_master(config, 0, 1000);
  const Child a = start_node(config, "a", {"--reconnect-s", "3"});
  const Child b = start_node(config, "b", {"--reconnect-s", "3"});
  ASSERT_TRUE(
      wait_until([&] { return presented(dir_ / "out/b").size() >= 2 && presented(dir_ / "out/a").size() >= 2; }, 240s))
      << logs();
  kill(master.pid, SIGKILL);
  const auto killed = Clock::now();
  EXPECT_EQ(wait_exit(a, 30s), std::optional<int>(3)) << logs();
  const double exit_s = std::chrono::duration<double>(Clock::now() - killed).count();
  EXPECT_EQ(wait_exit(b, 30s), std::optional<int>(3)) << logs();
  std::printf("[ measured ] node exits %.1f s after the master was killed (reconnect time 3 s)\n", exit_s);
  EXPECT_GE(exit_s, 2.5) << "it kept trying for the reconnect time";
  for (const char* n : {"a", "b"}) {
    const std::string log = read_text(dir_ / (std::string(n) + ".log"));
    EXPECT_NE(log.find("keeping the last frame, reconnecting for up to 3 s"), std::string::npos) << log;
    EXPECT_NE(log.find("could not reconnect to the master at 127.0.0.1:" + std::to_string(port_) + " within 3 s"),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("the master is gone; exiting"), std::string::npos) << log;
  }
  // The last presented frame stays on the outputs: no partial file left, nothing removed.
  for (const auto& entry : fs::recursive_directory_iterator(dir_ / "out"))
    EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  char last[32];
  std::snprintf(last, sizeof last, "frame-%06d.png", static_cast<int>(presented(dir_ / "out/a").back().frame));
  EXPECT_TRUE(fs::exists(dir_ / "out/a/top-left" / last));
}

TEST_F(ClusterProcess, StalledNodeReconnectsAndRejoinsWhileTheOthersSkipNoFrame) {
  // SIGSTOP past the master's silence limit (max(3 × 200 ms, 10 s)): the
  // master drops b; on SIGCONT b finds its connection gone, keeps its last
  // frame, reconnects (a full handshake), declares its cached tables and
  // rejoins at a frame boundary. A short barrier timeout lets a and c go on
  // while b is stopped.
  const fs::path config = write_config(10, 3000, 200);
  const Child master = start_master(config, 0);
  start_node(config, "a");
  const Child b = start_node(config, "b");
  start_node(config, "c");
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").size() >= 3; }, 240s)) << logs();
  ASSERT_EQ(kill(b.pid, SIGSTOP), 0);
  const std::uint64_t last_before = presented(dir_ / "out/b").back().frame;
  ASSERT_TRUE(wait_until(
      [&] {
        return read_text(dir_ / "master.log").find("node 'b'") != std::string::npos &&
               count_of(read_text(dir_ / "master.log"), "disconnected") >= 1;
      },
      60s))
      << logs();
  ASSERT_EQ(kill(b.pid, SIGCONT), 0);
  const auto resumed = Clock::now();
  const std::uint64_t a_at_resume = presented(dir_ / "out/a").back().frame;
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").back().frame > last_before; }, 60s)) << logs();
  const double rejoin_s = std::chrono::duration<double>(Clock::now() - resumed).count();
  const std::uint64_t b_back_at = [&] {
    for (const Presented& p : presented(dir_ / "out/b"))
      if (p.frame > last_before) return p.frame;
    return std::uint64_t{0};
  }();
  std::printf("[ measured ] b presented again %.2f s after SIGCONT, at frame %llu (a was at frame %llu)\n", rejoin_s,
              static_cast<unsigned long long>(b_back_at), static_cast<unsigned long long>(a_at_resume));
  EXPECT_LT(rejoin_s, 15.0);
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").size() >= 3 + 5; }, 60s)) << logs();
  kill(master.pid, SIGTERM);
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);

  expect_b_rejoined(dir_ / "out", last_before);

  const std::string b_log = read_text(dir_ / "b.log");
  EXPECT_NE(b_log.find("lost the connection to the master"), std::string::npos) << b_log;
  EXPECT_NE(b_log.find("keeping the last frame"), std::string::npos) << b_log;
  EXPECT_NE(b_log.find("welcomed again by the master"), std::string::npos) << b_log;
  EXPECT_EQ(b_log.find("exiting"), std::string::npos) << b_log;
  EXPECT_EQ(count_of(b_log, "received ("), 1u) << "the tables travelled once: " << b_log;
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("node 'b' holds 1 of its 1 table set in its cache: sent 0 table chunks"), std::string::npos)
      << master_log;
}

TEST_F(ClusterProcess, MasterRestartedOnTheSamePortGetsItsNodesBackWithTheirCachedTables) {
  const fs::path config = write_config(10, 20000, 200);
  const Child master = start_master(config, 0);
  for (const char* n : {"a", "b", "c"}) start_node(config, n);
  ASSERT_TRUE(wait_until(
      [&] {
        return presented(dir_ / "out/a").size() >= 2 && presented(dir_ / "out/b").size() >= 2 &&
               presented(dir_ / "out/c").size() >= 2;
      },
      240s))
      << logs();
  kill(master.pid, SIGKILL);
  ASSERT_EQ(wait_exit(master, 5s), std::optional<int>(128 + SIGKILL));
  std::this_thread::sleep_for(2s);  // the nodes knock on a closed port meanwhile
  const std::size_t before[3] = {presented(dir_ / "out/a").size(), presented(dir_ / "out/b").size(),
                                 presented(dir_ / "out/c").size()};
  fs::rename(dir_ / "master.log", dir_ / "master-1.log");
  const auto restarted = Clock::now();
  const Child again = start_master(config, 0);
  ASSERT_TRUE(wait_until(
      [&] {
        return presented(dir_ / "out/a").size() > before[0] && presented(dir_ / "out/b").size() > before[1] &&
               presented(dir_ / "out/c").size() > before[2];
      },
      120s))
      << logs();
  std::printf("[ measured ] every node presented again %.2f s after the master restarted\n",
              std::chrono::duration<double>(Clock::now() - restarted).count());
  kill(again.pid, SIGTERM);
  ASSERT_EQ(wait_exit(again, 30s), std::optional<int>(0)) << logs();
  for (const Child& c : children_)
    if (c.pid != master.pid && c.pid != again.pid) {
      EXPECT_EQ(wait_exit(c, 20s), std::optional<int>(0)) << logs();
    }
  const std::string master_log = read_text(dir_ / "master.log");
  for (const char* n : {"a", "b", "c"}) {
    EXPECT_NE(master_log.find(fmt::format("node '{}' holds 1 of its 1 table set in its cache: sent 0 table chunks", n)),
              std::string::npos)
        << master_log;
    const std::string log = read_text(dir_ / (std::string(n) + ".log"));
    EXPECT_EQ(count_of(log, "received ("), 1u) << "no chunk after the restart: " << log;
    EXPECT_NE(log.find("welcomed again by the master"), std::string::npos) << log;
    // The new master counts from frame 0: the frames after the restart are contiguous, the same on every node.
    const auto p = presented(dir_ / "out" / n);
    const std::size_t first_new = before[std::string("abc").find(n[0])];
    ASSERT_LT(first_new, p.size());
    expect_contiguous(std::vector<Presented>(p.begin() + first_new, p.end()), p[first_new].frame, p.back().frame, n);
  }
}

// ---- the standby master (docs/cluster.md, "Standby master") ------------------

/// Node `who` presented frames 0..last in order, none twice, with show time
/// frame / fps throughout (no jump), missing at most `max_lost` frames (the
/// frame in flight at a takeover). Returns the frames it did not present.
std::vector<std::uint64_t> expect_show_goes_on(const std::vector<Presented>& p, std::uint64_t last, double fps,
                                               std::size_t max_lost, const std::string& who) {
  std::vector<std::uint64_t> lost;
  std::uint64_t expected = 0;
  for (const Presented& x : p) {
    EXPECT_GE(x.frame, expected) << who << ": frame " << x.frame << " presented again, or out of order";
    for (; expected < x.frame; ++expected) lost.push_back(expected);
    expected = x.frame + 1;
    EXPECT_EQ(x.show_time_s, static_cast<double>(x.frame) / fps) << who << " frame " << x.frame;
  }
  EXPECT_FALSE(p.empty()) << who;
  if (!p.empty()) {
    EXPECT_EQ(p.back().frame, last) << who;
  }
  EXPECT_LE(lost.size(), max_lost) << who << " did not present frames " << fmt::format("{}", fmt::join(lost, ", "));
  return lost;
}

/// Frames presented by two nodes have the same state.
void expect_same_states(const std::vector<Presented>& a, const std::vector<Presented>& b, const std::string& who) {
  std::map<std::uint64_t, std::string> by_frame;
  for (const Presented& x : a) by_frame[x.frame] = x.digest;
  for (const Presented& x : b)
    if (by_frame.count(x.frame)) {
      EXPECT_EQ(x.digest, by_frame[x.frame]) << who << " frame " << x.frame;
    }
}

/// The pid `zenith cluster` logged for its master ("cluster: master started (pid N)"), or -1.
pid_t launcher_master_pid(const std::string& log) {
  const std::string started = "cluster: master started (pid ";
  const auto at = log.find(started);
  return at == std::string::npos ? -1 : std::stoi(log.substr(at + started.size()));
}

TEST_F(ClusterProcess, StandbyTakesOverWhenTheMasterIsKilledAndEveryNodePresentsEveryLaterFrame) {
  // `zenith cluster` with a standby in the config starts it too. kill -9 of
  // the master mid-show: the standby takes over on its own port, the nodes
  // (which keep their last frame) try the master, then the standby, rejoin
  // with their cached tables, and the show goes on from the frame after the
  // last one the master sent: every node presents every later frame, the
  // frame numbers and the show time go on, at most the frame in flight is
  // never presented.
  const fs::path config = write_config(10, 20000, 200, standby_port_);
  const Child cluster = spawn({"cluster", "--cluster", config.string(), "--frames", "100", "--out",
                               (dir_ / "out").string(), "--cache", cache_.string()},
                              dir_ / "cluster.log");
  children_.push_back(cluster);
  const auto all_presented = [&](std::size_t n) {
    return presented(dir_ / "out/a").size() >= n && presented(dir_ / "out/b").size() >= n &&
           presented(dir_ / "out/c").size() >= n;
  };
  ASSERT_TRUE(wait_until(
      [&] {
        return all_presented(15) && read_text(dir_ / "cluster.log").find("standby: the show runs") != std::string::npos;
      },
      300s))
      << logs();
  const pid_t master = launcher_master_pid(read_text(dir_ / "cluster.log"));
  ASSERT_GT(master, 0) << logs();
  ASSERT_EQ(kill(master, SIGKILL), 0);
  const auto killed = Clock::now();
  std::uint64_t at_kill[3];
  for (int i = 0; i < 3; ++i) at_kill[i] = presented(dir_ / "out" / std::string(1, "abc"[i])).back().frame;
  ASSERT_TRUE(wait_until(
      [&] {
        for (int i = 0; i < 3; ++i)
          if (presented(dir_ / "out" / std::string(1, "abc"[i])).back().frame <= at_kill[i] + 1) return false;
        return true;
      },
      60s))
      << logs();
  const double takeover_s = std::chrono::duration<double>(Clock::now() - killed).count();
  ASSERT_EQ(wait_exit(cluster, 300s), std::optional<int>(0)) << logs();

  const auto a = presented(dir_ / "out/a"), b = presented(dir_ / "out/b"), c = presented(dir_ / "out/c");
  const auto lost_a = expect_show_goes_on(a, 99, 10.0, 1, "a");
  const auto lost_b = expect_show_goes_on(b, 99, 10.0, 1, "b");
  const auto lost_c = expect_show_goes_on(c, 99, 10.0, 1, "c");
  expect_same_states(a, b, "b");
  expect_same_states(a, c, "c");
  std::printf(
      "[ measured ] every node presented again %.2f s after kill -9 of the master (frames lost: a %zu, b %zu, "
      "c %zu; none repeated)\n",
      takeover_s, lost_a.size(), lost_b.size(), lost_c.size());
  EXPECT_LT(takeover_s, 15.0);

  const std::string log = read_text(dir_ / "cluster.log");
  EXPECT_NE(log.find("cluster: standby master started (pid"), std::string::npos) << log;
  EXPECT_NE(log.find("cluster: the master died (killed by signal 9 (Killed)): the standby master"), std::string::npos)
      << log;
  EXPECT_NE(log.find("standby: the active master is gone"), std::string::npos) << log;
  const auto took_over = log.find("master: taking over the show at frame ");
  ASSERT_NE(took_over, std::string::npos) << log;
  const std::string after = log.substr(took_over);
  EXPECT_NE(after.find(fmt::format("listening on 127.0.0.1:{}", standby_port_)), std::string::npos) << after;
  for (const char* n : {"a", "b", "c"})
    EXPECT_NE(after.find(fmt::format("node '{}' holds 1 of its 1 table set in its cache: sent 0 table chunks", n)),
              std::string::npos)
        << "the nodes rejoin the standby with their cached tables: " << after;
  EXPECT_NE(after.find(fmt::format("welcomed again by the master at 127.0.0.1:{}", standby_port_)), std::string::npos)
      << after;
}

/// A show chasing the house's LTC with a standby (docs/shows.md, "Chasing timecode"): both masters chase
/// one rehearsal file from the same instant (`--ltc-file-epoch`), the standby from while it follows. kill -9
/// of the master mid-show: the standby takes over with its chase already locked, so the first frames it
/// sends carry the timecode's time at their moment — not the last frame's, not the show's start — and the
/// show goes on frame for frame with the timecode.
TEST_F(ClusterProcess, AStandbyTakesOverAChasedShowInStepWithTheTimecode) {
  fs::path config = write_config(10, 20000, 200, standby_port_);
  use_lookahead(config, 3);  // scheduled frames, so each frame has its moment on the master's clock
  const fs::path wav = write_ltc("00:59:58:00", 40, "1.001");
  // The file's first sample sounds at `epoch`: the show's start (01:00:00:00) 2 s / 1.001 later.
  const double epoch_s =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count() + 1.0;
  const auto expected_show_time = [&](double wall_s) { return (wall_s - epoch_s) * 1.001 - 2.0; };
  const Child cluster =
      spawn({"cluster", "--cluster", config.string(), "--frames", "150", "--out", (dir_ / "out").string(), "--cache",
             cache_.string(), "--show", (kSource / "tests/data/shows/chase-sunset.json").string(), "--ltc-file",
             wav.string(), "--ltc-file-epoch", fmt::format("{:.3f}", epoch_s)},
            dir_ / "cluster.log");
  children_.push_back(cluster);

  // Every frame node a presents, with the wall time it was first seen in its log (polled every 10 ms).
  std::map<std::uint64_t, std::pair<double, double>> seen;  // frame → (show time, wall time seen)
  const auto watch = [&] {
    const double now_s = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    for (const Presented& p : presented(dir_ / "out/a")) seen.try_emplace(p.frame, p.show_time_s, now_s);
  };
  const auto watching_until = [&](const std::function<bool()>& done, std::chrono::seconds limit) {
    for (const auto deadline = Clock::now() + limit; Clock::now() < deadline; std::this_thread::sleep_for(10ms)) {
      watch();
      if (done()) return true;
    }
    return false;
  };
  ASSERT_TRUE(watching_until(
      [&] {
        return seen.size() >= 30 &&
               read_text(dir_ / "cluster.log").find("standby: timecode locked while following") != std::string::npos;
      },
      300s))
      << logs();
  const pid_t master = launcher_master_pid(read_text(dir_ / "cluster.log"));
  ASSERT_GT(master, 0) << logs();
  ASSERT_EQ(kill(master, SIGKILL), 0);
  const std::uint64_t last_before = seen.rbegin()->first;
  ASSERT_TRUE(watching_until([&] { return seen.rbegin()->first >= last_before + 20; }, 60s)) << logs();
  ASSERT_EQ(wait_exit(cluster, 300s), std::optional<int>(0)) << logs();

  // The first frame the standby sent, from its log.
  const std::string log = read_text(dir_ / "cluster.log");
  const std::string taking_over = "master: taking over the show at frame ";
  const auto took_over = log.find(taking_over);
  ASSERT_NE(took_over, std::string::npos) << log;
  const std::uint64_t first_new = std::stoull(log.substr(took_over + taking_over.size()));

  // The frames in order: never a step back, and every one at the timecode's time of its moment (it is seen
  // in the log after it is presented: up to the poll and the write later, and never before). The
  // standby's first two frames, presented at once, may hold the active master's last frame, which was
  // sent up to the lookahead (0.3 s) ahead of its moment.
  double previous = -1.0, worst_before = 0.0, worst_after = 0.0;
  for (const auto& [frame, times] : seen) {
    const auto [show_time_s, seen_s] = times;
    EXPECT_GE(show_time_s, previous) << "frame " << frame << ": the show never steps back";
    previous = show_time_s;
    if (show_time_s <= 0.0) continue;  // before the show's start: held at 0
    const double lag = expected_show_time(seen_s) - show_time_s;
    const bool may_hold = frame == first_new || frame == first_new + 1;
    EXPECT_GT(lag, may_hold ? -0.35 : -0.05) << "frame " << frame << " presented before its moment";
    double& worst = frame < first_new ? worst_before : worst_after;
    worst = std::max(worst, lag);
  }
  std::printf(
      "[ measured ] frames seen after their timecode's moment by at most %.3f s before the takeover (frame "
      "%llu), %.3f s after it\n",
      worst_before, static_cast<unsigned long long>(first_new), worst_after);
  EXPECT_LT(worst_after, 0.2) << "the frames after the takeover carry the timecode's time of their moment";
  EXPECT_GE(seen.rbegin()->first, first_new + 15);

  EXPECT_NE(log.find("standby: chasing LTC from"), std::string::npos) << log;
  EXPECT_NE(log.find("master: chasing LTC from"), std::string::npos) << log;
  const auto gone = log.find("standby: the active master is gone");
  ASSERT_NE(gone, std::string::npos) << log;
  EXPECT_NE(log.find("(the standby's input, chased while it followed)", gone), std::string::npos) << log;
  EXPECT_NE(log.find("master: taking over the show at frame ", gone), std::string::npos) << log;
}

/// A standby whose timecode input cannot be opened while it follows (a sound device the master holds
/// on the same machine; here one that is not there) says so and follows all the same: it opens the
/// input when it takes over.
TEST_F(ClusterProcess, AStandbyThatCannotOpenItsTimecodeInputYetFollowsAllTheSame) {
  const fs::path config = write_config(10, 20000, 200, standby_port_);
  const fs::path wav = write_ltc("00:59:58:00", 60);
  const std::string show = (kSource / "tests/data/shows/chase-sunset.json").string();
  const Child master = start_master(config, 0, 120000, {"--show", show, "--ltc-file", wav.string()});
  const Child standby = spawn({"master", "--standby", "--cluster", config.string(), "--frames", "0", "--cache",
                               (dir_ / "standby-cache").string(), "--show", show, "--ltc-device", "hw:97,0"},
                              dir_ / "standby.log");
  children_.push_back(standby);
  for (const char* n : {"a", "b", "c"})
    start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
  ASSERT_TRUE(wait_until(
      [&] { return read_text(dir_ / "standby.log").find("standby: the show runs") != std::string::npos; }, 300s))
      << logs();
  const std::string log = read_text(dir_ / "standby.log");
  EXPECT_NE(log.find("standby: cannot open the timecode input while following (ALSA capture device 'hw:97,0': "),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("it opens it when it takes over"), std::string::npos) << log;
  kill(master.pid, SIGTERM);
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);
}

TEST_F(ClusterProcess, StandbyKilledAndRestartedFollowsAgainWhileTheShowGoesOnThenTakesOver) {
  // kill -9 of the standby while the master runs: the show is undisturbed
  // (the master never waits for a standby); a new standby follows again, and
  // it is the one that takes over when the master is killed afterwards. The
  // nodes take 250 ms per frame, so that a frame is in flight most of the
  // time: the kill of the master loses it (the stated bound), no more.
  const fs::path config = write_config(10, 20000, 200, standby_port_);
  const Child master = start_master(config, 0);
  Child standby = start_standby(config, 0);
  for (const char* n : {"a", "b", "c"}) start_node(config, n, {"--debug-render-delay-ms", "250"});
  ASSERT_TRUE(wait_until(
      [&] {
        return presented(dir_ / "out/c").size() >= 5 &&
               read_text(dir_ / "standby.log").find("standby: the show runs") != std::string::npos;
      },
      300s))
      << logs();
  kill(standby.pid, SIGKILL);
  ASSERT_EQ(wait_exit(standby, 5s), std::optional<int>(128 + SIGKILL));
  const std::uint64_t standby_killed_at = presented(dir_ / "out/a").back().frame;
  ASSERT_TRUE(wait_until(
      [&] {
        return read_text(dir_ / "master.log").find("the standby (") != std::string::npos &&
               read_text(dir_ / "master.log").find("disconnected") != std::string::npos;
      },
      30s))
      << logs();
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").back().frame >= standby_killed_at + 10; }, 60s))
      << logs();
  standby = start_standby(config, 0, "standby-2.log");
  ASSERT_TRUE(wait_until(
      [&] { return read_text(dir_ / "standby-2.log").find("standby: the show runs") != std::string::npos; }, 60s))
      << logs();
  const std::uint64_t restarted_at = presented(dir_ / "out/a").back().frame;
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").back().frame >= restarted_at + 5; }, 60s)) << logs();
  // Undisturbed so far: every node presented every frame.
  for (const char* n : {"a", "b", "c"}) {
    const auto p = presented(dir_ / "out" / n);
    expect_contiguous(p, 0, p.back().frame, n);
  }

  kill(master.pid, SIGKILL);
  ASSERT_EQ(wait_exit(master, 5s), std::optional<int>(128 + SIGKILL));
  const std::uint64_t master_killed_at = presented(dir_ / "out/a").back().frame;
  ASSERT_TRUE(wait_until([&] { return all_nodes_past(master_killed_at + 10); }, 60s)) << logs();
  kill(standby.pid, SIGTERM);
  ASSERT_EQ(wait_exit(standby, 30s), std::optional<int>(0)) << logs();
  for (const Child& c : children_)
    if (c.pid != master.pid && c.pid != standby.pid && c.pid != children_[1].pid) {
      EXPECT_EQ(wait_exit(c, 20s), std::optional<int>(0)) << logs();
    }
  const auto a = presented(dir_ / "out/a");
  for (const char* n : {"a", "b", "c"}) {
    const auto p = presented(dir_ / "out" / n);
    const auto lost = expect_show_goes_on(p, p.back().frame, 10.0, 1, n);
    expect_same_states(a, p, n);
    std::printf("[ measured ] node %s: frames not presented at the takeover: %s\n", n,
                lost.empty() ? "none" : fmt::format("{}", fmt::join(lost, ", ")).c_str());
  }
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_EQ(count_of(master_log,
                     "the standby master 'standby@127.0.0.1:" + std::to_string(standby_port_) + "' authenticated"),
            2u)
      << master_log;
  const std::string second = read_text(dir_ / "standby-2.log");
  EXPECT_NE(second.find("master: taking over the show at frame"), std::string::npos) << second;
  EXPECT_EQ(read_text(dir_ / "standby.log").find("master: taking over"), std::string::npos)
      << "the killed one never did";
}

TEST_F(ClusterProcess, StandbyTakesOverFromAStoppedMasterAfterTheSilenceLimit) {
  // SIGSTOP of the master closes no socket: the standby and the nodes find it
  // silent past the silence limit (max(3 × 200 ms, 10 s)). The stopped
  // master's kernel still accepts connections, so the standby's one more
  // attempt ends at its 2 s limit, and the nodes' attempts on the master at
  // their 3 s limit, without a Welcome: the standby takes over, the nodes
  // then reach it.
  const fs::path config = write_config(10, 20000, 200, standby_port_);
  const Child master = start_master(config, 0);
  const Child standby = start_standby(config, 0);
  for (const char* n : {"a", "b", "c"}) start_node(config, n);
  ASSERT_TRUE(wait_until(
      [&] {
        return all_nodes_past(5) && read_text(dir_ / "standby.log").find("standby: the show runs") != std::string::npos;
      },
      300s))
      << logs();
  ASSERT_EQ(kill(master.pid, SIGSTOP), 0);
  const auto stopped = Clock::now();
  const std::uint64_t stopped_at = presented(dir_ / "out/a").back().frame;
  ASSERT_TRUE(wait_until([&] { return all_nodes_past(stopped_at + 2); }, 90s)) << logs();
  const double takeover_s = std::chrono::duration<double>(Clock::now() - stopped).count();
  ASSERT_TRUE(wait_until([&] { return all_nodes_past(stopped_at + 10); }, 60s)) << logs();
  kill(master.pid, SIGKILL);  // a stopped process dies too
  ASSERT_EQ(wait_exit(master, 5s), std::optional<int>(128 + SIGKILL));
  kill(standby.pid, SIGTERM);
  ASSERT_EQ(wait_exit(standby, 30s), std::optional<int>(0)) << logs();
  for (const Child& c : children_)
    if (c.pid != master.pid && c.pid != standby.pid) {
      EXPECT_EQ(wait_exit(c, 20s), std::optional<int>(0)) << logs();
    }
  const auto a = presented(dir_ / "out/a");
  for (const char* n : {"a", "b", "c"}) {
    const auto p = presented(dir_ / "out" / n);
    expect_show_goes_on(p, p.back().frame, 10.0, 1, n);
    expect_same_states(a, p, n);
  }
  std::printf(
      "[ measured ] every node presented again %.1f s after SIGSTOP of the master (silence limit 10 s, "
      "attempt limits 2 s (standby) and 3 s (nodes))\n",
      takeover_s);
  EXPECT_GT(takeover_s, 10.0) << "not before the silence limit";
  EXPECT_LT(takeover_s, 30.0);
  const std::string log = read_text(dir_ / "standby.log");
  EXPECT_NE(log.find("past its silence limit of 10 s"), std::string::npos) << log;
  EXPECT_NE(log.find("the active master is gone"), std::string::npos) << log;
  EXPECT_NE(log.find("no Welcome within 2.0 s"), std::string::npos) << log;
}

TEST_F(ClusterProcess, StandbyTakingOverAShowContinuesItsShowTime) {
  // A show file (2.5 s at 5 fps, looping: 14 frames a loop, 0, 0.2, …, 2.4,
  // 2.5) on master and standby: after the kill the standby's clock goes on
  // where the master's was, at its step, through the loop's wrap.
  const fs::path config = write_config(10, 20000, 200, standby_port_);
  const fs::path show = kSource / "tests/data/shows/offline-sunset.json";
  const std::vector<std::string> playback = {"--show", show.string(), "--fps", "5", "--loop"};
  const Child master = start_master(config, 0, 120000, playback);
  std::vector<std::string> standby_args = {"master",        "--standby", "--cluster",
                                           config.string(), "--cache",   (dir_ / "standby-cache").string()};
  standby_args.insert(standby_args.end(), playback.begin(), playback.end());
  children_.push_back(spawn(standby_args, dir_ / "standby.log"));
  const Child standby = children_.back();
  for (const char* n : {"a", "b", "c"})
    start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/c").size() >= 17; }, 300s)) << logs();
  kill(master.pid, SIGKILL);
  ASSERT_EQ(wait_exit(master, 5s), std::optional<int>(128 + SIGKILL));
  const std::uint64_t killed_at = presented(dir_ / "out/a").back().frame;
  ASSERT_TRUE(wait_until([&] { return all_nodes_past(killed_at + 16); }, 60s)) << logs();
  kill(standby.pid, SIGTERM);
  ASSERT_EQ(wait_exit(standby, 30s), std::optional<int>(0)) << logs();
  const auto a = presented(dir_ / "out/a");
  ASSERT_GE(a.size(), 14u);
  for (const char* n : {"a", "b", "c"}) {
    const auto p = presented(dir_ / "out" / n);
    std::uint64_t expected = 0;
    std::size_t lost = 0;
    for (const Presented& x : p) {
      EXPECT_GE(x.frame, expected) << n << ": frame " << x.frame << " presented again";
      lost += x.frame - std::min(x.frame, expected);
      expected = x.frame + 1;
      // Every loop shows the first loop's times, frame for frame, on the master and after the takeover alike.
      EXPECT_NEAR(x.show_time_s, a[x.frame % 14].show_time_s, 1e-9) << n << " frame " << x.frame;
    }
    EXPECT_LE(lost, 1u) << n;
    expect_same_states(a, p, n);
  }
  EXPECT_NE(read_text(dir_ / "standby.log").find("master: taking over the show at frame"), std::string::npos) << logs();
}

TEST_F(ClusterProcess, StandbyWithTheWrongSecretOrAnotherStandbyAddressIsRefused) {
  const fs::path config = write_config(10, 20000, 200, standby_port_);
  const Child master = start_master(config, 0, 600000);
  setenv(kSecretVar, "not-the-cluster-secret-at-all-0123", 1);
  const Child wrong_secret = start_standby(config, 0);
  setenv(kSecretVar, "cluster-test-secret-0123456789", 1);
  EXPECT_EQ(wait_exit(wrong_secret, 200s), std::optional<int>(2)) << logs();
  const std::string standby_log = read_text(dir_ / "standby.log");
  EXPECT_NE(
      standby_log.find("standby: the master at 127.0.0.1:" + std::to_string(port_) + " refused the connection (3)"),
      std::string::npos)
      << standby_log;
  EXPECT_NE(standby_log.find("failed authentication (wrong shared secret)"), std::string::npos) << standby_log;
  EXPECT_EQ(standby_log.find("master: taking over"), std::string::npos) << standby_log;

  // A standby whose config names another standby address is not this cluster's standby.
  const fs::path other = write_config(10, 20000, 200, standby_port_ + 1, "other-standby.json");
  const Child stranger = start_standby(other, 0, "standby-2.log");
  EXPECT_EQ(wait_exit(stranger, 60s), std::optional<int>(2)) << logs();
  const std::string stranger_log = read_text(dir_ / "standby-2.log");
  EXPECT_NE(stranger_log.find("refused the connection (7)"), std::string::npos) << stranger_log;
  EXPECT_NE(stranger_log.find("is not this cluster's standby"), std::string::npos) << stranger_log;

  kill(master.pid, SIGTERM);
  EXPECT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("refused the standby (127.0.0.1:"), std::string::npos) << master_log;
  EXPECT_NE(master_log.find(": handshake: standby 'standby@127.0.0.1:" + std::to_string(standby_port_) +
                            "' failed authentication (wrong shared secret)"),
            std::string::npos)
      << master_log;
  EXPECT_NE(master_log.find("is not this cluster's standby ('standby@127.0.0.1:" + std::to_string(standby_port_)),
            std::string::npos)
      << master_log;
}

/// The pids `zenith cluster` logged for node `name`: "node 'b' started (pid N)", then one per "restarted it (pid N".
std::vector<pid_t> launcher_pids(const std::string& log, const std::string& name) {
  std::vector<pid_t> pids;
  const std::string started = "cluster: node '" + name + "' started (pid ";
  if (const auto at = log.find(started); at != std::string::npos)
    pids.push_back(std::stoi(log.substr(at + started.size())));
  const std::string restarted = "cluster: node '" + name + "' died (";
  for (auto at = log.find(restarted); at != std::string::npos; at = log.find(restarted, at + 1)) {
    const auto pid_at = log.find("restarted it (pid ", at);
    const auto line_end = log.find('\n', at);
    if (pid_at != std::string::npos && pid_at < line_end) pids.push_back(std::stoi(log.substr(pid_at + 18)));
  }
  return pids;
}

TEST_F(ClusterProcess, LauncherRestartsAKilledNodeWhichRejoins) {
  const fs::path config = write_config(10, 5000, 200);
  const Child cluster = spawn({"cluster", "--cluster", config.string(), "--frames", "250", "--out",
                               (dir_ / "out").string(), "--cache", cache_.string(), "--restart-nodes"},
                              dir_ / "cluster.log");
  children_.push_back(cluster);
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").size() >= 3; }, 240s)) << logs();
  const std::vector<pid_t> pids = launcher_pids(read_text(dir_ / "cluster.log"), "b");
  ASSERT_EQ(pids.size(), 1u) << logs();
  ASSERT_EQ(kill(pids[0], SIGKILL), 0);
  const auto killed = Clock::now();
  const std::uint64_t last_before = presented(dir_ / "out/b").back().frame;
  ASSERT_TRUE(wait_until([&] { return launcher_pids(read_text(dir_ / "cluster.log"), "b").size() == 2; }, 30s))
      << logs();
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").back().frame > last_before; }, 120s)) << logs();
  std::printf("[ measured ] the relaunched node b presented again %.2f s after kill -9\n",
              std::chrono::duration<double>(Clock::now() - killed).count());
  ASSERT_EQ(wait_exit(cluster, 400s), std::optional<int>(0)) << logs();
  const std::string log = read_text(dir_ / "cluster.log");
  EXPECT_NE(log.find("cluster: node 'b' died (killed by signal 9"), std::string::npos) << log;
  EXPECT_NE(log.find("restart 1, 1 of at most 5 within 60 s"), std::string::npos) << log;
  const auto a = presented(dir_ / "out/a"), c = presented(dir_ / "out/c");
  expect_contiguous(a, 0, 249, "a");
  expect_contiguous(c, 0, 249, "c");
  const auto bp = presented(dir_ / "out/b");
  for (const Presented& p : bp) EXPECT_EQ(p.digest, a[p.frame].digest) << "frame " << p.frame;
  EXPECT_EQ(bp.back().frame, 249u) << "b rejoined and stayed to the end";
}

TEST_F(ClusterProcess, LauncherStopsRestartingACrashLoopAtTheLimit) {
  const fs::path config = write_config(10, 5000, 200);
  const Child cluster =
      spawn({"cluster", "--cluster", config.string(), "--frames", "120", "--out", (dir_ / "out").string(), "--cache",
             cache_.string(), "--restart-nodes", "--max-restarts", "2", "--restart-window-s", "60"},
            dir_ / "cluster.log");
  children_.push_back(cluster);
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/b").size() >= 1; }, 240s)) << logs();
  // b dies three times in a row, as fast as it is restarted: the third death is one too many.
  for (std::size_t death = 1; death <= 3; ++death) {
    std::vector<pid_t> pids;
    ASSERT_TRUE(
        wait_until([&] { return (pids = launcher_pids(read_text(dir_ / "cluster.log"), "b")).size() == death; }, 30s))
        << logs();
    ASSERT_EQ(kill(pids.back(), SIGKILL), 0);
  }
  ASSERT_TRUE(
      wait_until([&] { return read_text(dir_ / "cluster.log").find("giving up on it") != std::string::npos; }, 30s))
      << logs();
  // The show goes on with a and c; the launcher reports the failed node at the end.
  EXPECT_EQ(wait_exit(cluster, 400s), std::optional<int>(1)) << logs();
  const std::string log = read_text(dir_ / "cluster.log");
  EXPECT_EQ(launcher_pids(log, "b").size(), 3u) << "started once, restarted twice: " << log;
  EXPECT_NE(log.find("cluster: node 'b' died (killed by signal 9 (Killed)) after 2 restarts within 60 s: giving up on "
                     "it, it stays down"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("1 node failed"), std::string::npos) << log;
  expect_contiguous(presented(dir_ / "out/a"), 0, 119, "a");
  expect_contiguous(presented(dir_ / "out/c"), 0, 119, "c");
}

/// The quadrants of `frame` equal a single-process 128² render of `scene`, bit for bit.
void expect_frame_equals_single_render(const fs::path& dir, const fs::path& cache, const fs::path& scene,
                                       std::uint64_t frame, std::vector<Child>& children) {
  const fs::path single = dir / "single.png";
  const Child render =
      spawn({"render", "--scene", scene.string(), "--projection", "fisheye", "--size", "128x128", "--tables", "small",
             "--orders", "4", "--cache", cache.string(), "--out", single.string()},
            dir / "render.log");
  children.push_back(render);
  ASSERT_EQ(wait_exit(render, 200s), std::optional<int>(0)) << read_text(dir / "render.log");
  const image::LinearImage whole = image::read_image(single);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"a", "top-left"}, {"a", "top-right"}, {"b", "bottom-left"}, {"c", "bottom-right"}};
  char name[32];
  std::snprintf(name, sizeof name, "frame-%06d.png", static_cast<int>(frame));
  for (std::size_t q = 0; q < files.size(); ++q) {
    const image::LinearImage tile = image::read_image(dir / "out" / files[q].first / files[q].second / name);
    ASSERT_EQ(tile.width, kQuadrantPx);
    const int differing = values_differing_from_quadrant(tile, whole, q);
    EXPECT_EQ(differing, 0) << files[q].second << " of " << name << ": values differing from the single render";
  }
}

TEST_F(ClusterProcess, AtmosphereSwitchTakesEffectAtTheSameFrameOnEveryNode) {
  const fs::path config = write_config(10);
  // Earth goes from earth-advanced (the scene's) to earth-standard: asked for at frame 3, prepared in the background.
  const Child master =
      start_master(config, 0, 120000, {"--sun-step-deg", "0", "--switch-atmosphere", "3:Earth:earth-standard"});
  for (const char* n : {"a", "b", "c"}) start_node(config, n);
  const auto switched_frames = [&](const char* node) {
    const auto p = presented(dir_ / "out" / node);
    return std::count_if(p.begin(), p.end(), [&](const Presented& x) { return x.tables != p.front().tables; });
  };
  ASSERT_TRUE(wait_until(
      [&] { return switched_frames("a") >= 3 && switched_frames("b") >= 3 && switched_frames("c") >= 3; }, 400s))
      << logs();
  kill(master.pid, SIGTERM);
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);

  const auto a = presented(dir_ / "out/a");
  ASSERT_FALSE(a.empty());
  const std::string old_tables = a.front().tables;
  std::optional<std::uint64_t> first_new;
  std::string new_tables;
  for (const Presented& p : a)
    if (p.tables != old_tables) {
      first_new = p.frame;
      new_tables = p.tables;
      break;
    }
  ASSERT_TRUE(first_new.has_value());
  EXPECT_GE(*first_new, 3u) << "not before the switch was asked for";
  for (const char* node : {"a", "b", "c"}) {
    const auto p = presented(dir_ / "out" / node);
    expect_contiguous(p, 0, p.back().frame, node);
    for (const Presented& x : p)
      EXPECT_EQ(x.tables, x.frame < *first_new ? old_tables : new_tables) << node << " frame " << x.frame;
  }
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("takes effect at frame " + std::to_string(*first_new)), std::string::npos) << master_log;

  // A frame after the switch equals a single-process render with the new atmosphere.
  std::ifstream in(kSource / "configs/scenes/earth-sunset.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const auto at = scene.find("\"earth-advanced\"");
  ASSERT_NE(at, std::string::npos);
  scene.replace(at, 16, "\"earth-standard\"");
  std::ofstream(dir_ / "earth-standard-sunset.json") << scene;
  expect_frame_equals_single_render(dir_, cache_, dir_ / "earth-standard-sunset.json", *first_new + 1, children_);
}

/// Every node presented frames 0..last with one state per frame, the same on
/// every node; returns node a's log.
std::vector<Presented> expect_in_sync(const fs::path& out, std::uint64_t last) {
  const auto a = presented(out / "a"), b = presented(out / "b"), c = presented(out / "c");
  expect_contiguous(a, 0, last, "a");
  expect_contiguous(b, 0, last, "b");
  expect_contiguous(c, 0, last, "c");
  for (std::size_t i = 0; i < a.size() && i < b.size() && i < c.size(); ++i) {
    EXPECT_EQ(a[i].digest, b[i].digest) << "frame " << i;
    EXPECT_EQ(a[i].digest, c[i].digest) << "frame " << i;
    EXPECT_EQ(a[i].tables, b[i].tables) << "frame " << i;
    EXPECT_EQ(a[i].tables, c[i].tables) << "frame " << i;
  }
  return a;
}

TEST_F(ClusterProcess, ShowPlaysInSyncAndItsRecordingPlaysBackIdentically) {
  const fs::path config = write_config(10);
  // 2.5 s at 2 fps = 6 frames; the turbidity track steps from 2 to 3: two table
  // versions the nodes know only from the master's AtmosphereDefinitions.
  const fs::path show = kSource / "tests/data/shows/offline-sunset.json";
  const fs::path scene = kSource / "configs/scenes/earth-sunset.json";
  const fs::path recording = dir_ / "recording.json";
  const Child master = start_master(
      config, 0, 120000, {"--show", show.string(), "--fps", "2", "--unpaced", "--record", recording.string()});
  for (const char* n : {"a", "b", "c"}) start_node(config, n, {"--scene", scene.string()});
  ASSERT_EQ(wait_exit(master, 400s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);
  const auto played = expect_in_sync(dir_ / "out", 5);
  ASSERT_EQ(played.size(), 6u);
  EXPECT_NE(played.front().tables, played.back().tables) << "the turbidity track switches table versions";
  for (std::size_t i = 1; i < played.size(); ++i) EXPECT_NE(played[i].digest, played[i - 1].digest) << "frame " << i;
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("needs 2 table sets"), std::string::npos) << master_log;
  EXPECT_NE(master_log.find("6 frames recorded"), std::string::npos) << master_log;
  ASSERT_TRUE(fs::exists(recording));

  // Play the recording on fresh nodes (new output folder): the same states, frame by frame.
  fs::rename(dir_ / "out", dir_ / "out-live");
  for (const char* n : {"master", "a", "b", "c"})
    fs::rename(dir_ / (std::string(n) + ".log"), dir_ / (std::string(n) + "-live.log"));
  children_.clear();
  const Child replay = start_master(config, 0, 120000, {"--show", recording.string(), "--unpaced"});
  for (const char* n : {"a", "b", "c"}) start_node(config, n, {"--scene", scene.string()});
  ASSERT_EQ(wait_exit(replay, 400s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(replay);
  const auto replayed = expect_in_sync(dir_ / "out", 5);
  ASSERT_EQ(replayed.size(), played.size());
  for (std::size_t i = 0; i < played.size(); ++i) {
    EXPECT_EQ(replayed[i].digest, played[i].digest) << "frame " << i;
    EXPECT_EQ(replayed[i].tables, played[i].tables) << "frame " << i;
  }
  // And the pixels: every file of the replay equals the live run's, byte for byte.
  for (const auto& entry : fs::recursive_directory_iterator(dir_ / "out")) {
    if (entry.path().extension() != ".png") continue;
    const fs::path live = dir_ / "out-live" / fs::relative(entry.path(), dir_ / "out");
    EXPECT_EQ(read_text(entry.path()), read_text(live)) << entry.path();
  }
}

TEST_F(ClusterProcess, ShowStartsBeforeItsLaterTablesAreReadyAndTheirFrameWaitsForThem) {
  // The sunset fixture's second table set (turbidity 3) is first used part of
  // the way through its 6 frames. It takes 12 s more to prepare here
  // (--debug-table-delay-ms): the frames before are presented meanwhile, the
  // first frame that uses it waits for it, and every node still presents
  // every frame with one state. The delay runs from the end of the first set,
  // while the nodes still warm up (4–5 s on 2 quiet cores, 7–12 s under
  // load: 4 s was not enough), so it must outlast their warm-up.
  const fs::path config = write_config(10);
  const fs::path show = kSource / "tests/data/shows/offline-sunset.json";
  const Child master = start_master(
      config, 0, 120000, {"--show", show.string(), "--fps", "2", "--unpaced", "--debug-table-delay-ms", "12000"});
  for (const char* n : {"a", "b", "c"})
    start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
  ASSERT_EQ(wait_exit(master, 400s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);
  const auto played = expect_in_sync(dir_ / "out", 5);
  ASSERT_EQ(played.size(), 6u);
  std::size_t first_of_second = 1;
  while (first_of_second < played.size() && played[first_of_second].tables == played[0].tables) ++first_of_second;
  ASSERT_LT(first_of_second, played.size()) << "the turbidity track switches table versions";
  const std::string master_log = read_text(dir_ / "master.log");
  const auto at = [&](const std::string& text) {
    const std::size_t position = master_log.find(text);
    EXPECT_NE(position, std::string::npos) << "'" << text << "' not in the master's log:\n" << master_log;
    return position;
  };
  const std::size_t started = at("starting the show");
  const std::size_t before = at(fmt::format("present frame {} ", first_of_second - 1));
  const std::size_t waits = at(fmt::format("frame {} waits for table set", first_of_second));
  const std::size_t second_set = at("table set 2 of 2");
  const std::size_t goes_on = at(fmt::format("frame {} goes on after waiting", first_of_second));
  EXPECT_LT(started, second_set) << "frame 0 does not wait for the last set";
  EXPECT_LT(before, second_set) << "the frames before it are presented while the second set is prepared";
  EXPECT_LT(waits, second_set);
  EXPECT_LT(second_set, goes_on);
}

TEST_F(ClusterProcess, OperatorPausesSeeksAndQuitsThroughTheControlSocket) {
  const fs::path config = write_config(5);
  const fs::path show = kSource / "tests/data/shows/offline-sunset.json";
  const int control_port = port_ + 1;
  const Child master =
      start_master(config, 0, 120000,
                   {"--show", show.string(), "--fps", "2", "--loop", "--control-port", std::to_string(control_port)});
  for (const char* n : {"a", "b", "c"})
    start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
  const auto control = [&](const std::string& command) {
    const fs::path log = dir_ / "control.log";
    fs::remove(log);
    std::vector<std::string> args = {"show", "control", "--port", std::to_string(control_port)};
    std::istringstream words(command);
    for (std::string w; words >> w;) args.push_back(w);
    const Child c = spawn(args, log);
    const auto status = wait_exit(c, 30s);
    return std::make_pair(status, read_text(log));
  };
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= 3; }, 400s)) << logs();

  auto [status, reply] = control("pause");
  ASSERT_EQ(status, std::optional<int>(0)) << reply << logs();
  EXPECT_NE(reply.find("paused"), std::string::npos) << reply;
  // Frames go on while paused, all with one show time: the same state but for the frame number.
  const std::size_t paused_at = presented(dir_ / "out/a").size();
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= paused_at + 4; }, 120s)) << logs();
  const std::size_t before_seek = presented(dir_ / "out/a").size();
  std::tie(status, reply) = control("seek 0.5");
  EXPECT_EQ(status, std::optional<int>(0)) << reply;
  EXPECT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= before_seek + 2; }, 120s)) << logs();
  std::tie(status, reply) = control("warp 9");
  EXPECT_EQ(status, std::optional<int>(1)) << "an unknown command is refused: " << reply;
  EXPECT_NE(reply.find("error"), std::string::npos) << reply;
  std::tie(status, reply) = control("quit");
  EXPECT_EQ(status, std::optional<int>(0)) << reply;
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);

  const auto a = expect_in_sync(dir_ / "out", presented(dir_ / "out/a").back().frame);
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("operator: pause"), std::string::npos) << master_log;
  EXPECT_NE(master_log.find("operator: seek 0.5"), std::string::npos) << master_log;
  // Playing: show time advances by 1/2 s per frame (looping at 2.5 s). Paused: it holds for at
  // least the 4 frames waited for. Sought: 0.5 s comes back after the pause.
  std::size_t longest_hold = 1, hold = 1;
  std::optional<std::size_t> first_hold_end;
  for (std::size_t i = 1; i < a.size(); ++i) {
    ASSERT_GE(a[i].show_time_s, 0.0) << "presented.log carries the show time";
    hold = a[i].show_time_s == a[i - 1].show_time_s ? hold + 1 : 1;
    if (hold >= 4 && !first_hold_end) first_hold_end = i;
    longest_hold = std::max(longest_hold, hold);
  }
  EXPECT_GE(longest_hold, 4u) << "the show time holds while paused";
  ASSERT_TRUE(first_hold_end.has_value());
  bool sought = false;
  for (std::size_t i = *first_hold_end; i < a.size(); ++i) sought = sought || a[i].show_time_s == 0.5;
  EXPECT_TRUE(sought) << "after seek 0.5 a frame shows t = 0.5 s";
}

TEST_F(ClusterProcess, ShowRendersOfflineOnTheNodesResumesAndMatchesASingleProcessRender) {
  const fs::path config = write_config(10);
  const fs::path show = kSource / "tests/data/shows/offline-sunset.json";
  const auto render = [&](const fs::path& out, const std::vector<std::string>& where, const std::string& log) {
    std::vector<std::string> args = {"show",  "render",     "--show",  show.string(),
                                     "--out", out.string(), "--cache", cache_.string()};
    args.insert(args.end(), where.begin(), where.end());
    const Child c = spawn(args, dir_ / log);
    children_.push_back(c);
    const auto status = wait_exit(c, 400s);
    return std::make_pair(status, read_text(dir_ / log));
  };
  const fs::path out = dir_ / "offline";
  auto [status, text] = render(out, {"--cluster", config.string()}, "render-1.log");
  ASSERT_EQ(status, std::optional<int>(0)) << text;
  EXPECT_NE(text.find("rendered 6, skipped 0 of 6 frames"), std::string::npos) << text;
  const char* outputs[4] = {"top-left", "top-right", "bottom-left", "bottom-right"};
  for (const char* o : outputs)
    for (int f = 0; f < 6; ++f) {
      char name[64];
      std::snprintf(name, sizeof name, "%s/%s.%06d.png", o, o, f);
      EXPECT_TRUE(fs::exists(out / name)) << name;
    }
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
  EXPECT_TRUE(fs::exists(out / "contact-sheet.png"));
  // Every node presented the 6 frames with one state each.
  for (const char* node : {"a", "b", "c"}) expect_contiguous(presented(out / "nodes" / node), 0, 5, node);

  // Resume: nothing to do, then exactly the frame whose file is gone.
  std::tie(status, text) = render(out, {"--cluster", config.string()}, "render-2.log");
  ASSERT_EQ(status, std::optional<int>(0)) << text;
  EXPECT_NE(text.find("rendered 0, skipped 6 of 6 frames"), std::string::npos) << text;
  const std::string before = read_text(out / "bottom-left/bottom-left.000003.png");
  fs::remove(out / "bottom-left/bottom-left.000003.png");
  std::tie(status, text) = render(out, {"--cluster", config.string()}, "render-3.log");
  ASSERT_EQ(status, std::optional<int>(0)) << text;
  EXPECT_NE(text.find("rendered 1, skipped 5 of 6 frames"), std::string::npos) << text;
  EXPECT_EQ(read_text(out / "bottom-left/bottom-left.000003.png"), before) << "re-rendered bit for bit";

  // The quadrants of frame 5 (after the turbidity step) equal one process rendering the whole dome master,
  // within one code: the single process encodes its PNGs on the GPU (the display pass of the offline
  // pipeline), the nodes on the CPU (render/display/display_encoder.h: ±1 code).
  const fs::path single = dir_ / "single";
  std::tie(status, text) = render(single,
                                  {"--projection", "fisheye", "--size", "128x128", "--tables", "small", "--orders", "4",
                                   "--from", "5", "--to", "5"},
                                  "render-single.log");
  ASSERT_EQ(status, std::optional<int>(0)) << text;
  const image::LinearImage whole = image::read_image(single / "fisheye/fisheye.000005.png");
  ASSERT_EQ(whole.width, 2 * kQuadrantPx);
  for (int q = 0; q < 4; ++q) {
    const image::LinearImage tile = image::read_image(out / outputs[q] / (std::string(outputs[q]) + ".000005.png"));
    const int differing = values_beyond_a_code_from_quadrant(tile, whole, q);
    EXPECT_EQ(differing, 0) << outputs[q];
  }
}

TEST_F(ClusterProcess, SlowNodeMissesTheBarrierWhileTheOthersSkipNoFrame) {
  const fs::path config = write_config(10, 300);
  const Child master = start_master(config, 0);
  start_node(config, "a");
  start_node(config, "b");
  start_node(config, "c", {"--debug-render-delay-ms", "1500"});
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= 8; }, 300s)) << logs();
  kill(master.pid, SIGTERM);
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  const auto a = presented(dir_ / "out/a"), b = presented(dir_ / "out/b");
  expect_contiguous(a, 0, a.back().frame, "a");
  expect_contiguous(b, 0, b.back().frame, "b");
  EXPECT_EQ(a.back().frame, b.back().frame);
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("node 'c' missed the barrier of frame"), std::string::npos) << master_log;
  EXPECT_EQ(master_log.find("node 'a' missed"), std::string::npos) << master_log;
  EXPECT_EQ(master_log.find("node 'b' missed"), std::string::npos) << master_log;
}

TEST_F(ClusterProcess, ReconnectingNodeWithCachedTablesReceivesNoChunks) {
  const fs::path config = write_config(10);
  const Child master = start_master(config, 0, 1000);
  Child a = start_node(config, "a");
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= 2; }, 240s)) << logs();
  kill(a.pid, SIGKILL);
  ASSERT_EQ(wait_exit(a, 5s), std::optional<int>(128 + SIGKILL));
  const std::size_t before = presented(dir_ / "out/a").size();
  a = start_node(config, "a");  // same cache folder
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= before + 3; }, 240s)) << logs();
  kill(master.pid, SIGTERM);
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  const std::string master_log = read_text(dir_ / "master.log");
  // First connection: an empty cache, the whole set; second: announced only.
  EXPECT_EQ(count_of(master_log, "node 'a' holds 0 of its 1 table set in its cache: sent "), 1u) << master_log;
  EXPECT_EQ(count_of(master_log, "node 'a' holds 1 of its 1 table set in its cache: sent 0 table chunks"), 1u)
      << master_log;
  const std::string node_log = read_text(dir_ / "a.log");
  EXPECT_EQ(count_of(node_log, "received ("), 1u) << node_log;
  EXPECT_NE(node_log.find("1 table set already in the cache"), std::string::npos) << node_log;
}

// ---- hostile clients --------------------------------------------------------

void send_all(int fd, const std::vector<std::uint8_t>& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

/// Reads until the peer closes (true) or `timeout` passes (false); decoded messages go to `messages`.
bool read_until_closed(int fd, std::chrono::milliseconds timeout, std::vector<Message>* messages = nullptr) {
  FrameDecoder decoder;
  const auto deadline = Clock::now() + timeout;
  std::uint8_t buffer[4096];
  while (Clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;
    const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) return true;
    decoder.feed(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(n)));
    try {
      while (auto m = decoder.next())
        if (messages) messages->push_back(*m);
    } catch (const ProtocolError&) {
    }
  }
  return false;
}

TEST_F(ClusterProcess, HostileClientsAreClosedAndTheMasterKeepsServing) {
  const fs::path config = write_config(10);
  const Child master = start_master(config, 0, 1000);
  const Child a = start_node(config, "a");
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= 2; }, 240s)) << logs();

  {  // garbage bytes
    const int fd = zenith::core::connect_loopback(port_);
    ASSERT_GE(fd, 0);
    const std::string junk = "GET / HTTP/1.1\r\nHost: zenith\r\n\r\n";
    send_all(fd, std::vector<std::uint8_t>(junk.begin(), junk.end()));
    EXPECT_TRUE(read_until_closed(fd, 5s)) << "garbage: the master must close";
    close(fd);
  }
  {  // an oversized length in an otherwise valid header
    const int fd = zenith::core::connect_loopback(port_);
    std::vector<std::uint8_t> frame = test::raw_frame(static_cast<std::uint16_t>(MessageType::hello), {});
    test::put_be32(frame, 8, 0x7FFFFFFF);
    test::fix_header_crc(frame);
    send_all(fd, frame);
    EXPECT_TRUE(read_until_closed(fd, 5s)) << "oversized: the master must close";
    close(fd);
  }
  {  // another protocol version
    const int fd = zenith::core::connect_loopback(port_);
    std::vector<std::uint8_t> frame =
        test::raw_frame(static_cast<std::uint16_t>(MessageType::heartbeat), std::vector<std::uint8_t>(8, 0));
    test::put_be16(frame, 4, kProtocolVersion + 1);
    test::fix_header_crc(frame);
    send_all(fd, frame);
    EXPECT_TRUE(read_until_closed(fd, 5s)) << "wrong version: the master must close";
    close(fd);
  }
  {  // a message before the handshake
    const int fd = zenith::core::connect_loopback(port_);
    send_all(fd, encode(RenderDone{0, 1.0}));
    std::vector<Message> got;
    EXPECT_TRUE(read_until_closed(fd, 5s, &got));
    ASSERT_FALSE(got.empty());
    EXPECT_TRUE(std::holds_alternative<Reject>(got.back()));
    close(fd);
  }
  {  // the wrong secret: Reject(authentication_failed), then closed
    const int fd = zenith::core::connect_loopback(port_);
    const std::string wrong = "not-the-cluster-secret-at-all";
    NodeHandshake hs(SharedSecret(std::vector<std::uint8_t>(wrong.begin(), wrong.end()), "test"), "test-dome", "b");
    send_all(fd, encode(hs.start()));
    FrameDecoder decoder;
    std::optional<Challenge> challenge;
    std::uint8_t buffer[512];
    const auto deadline = Clock::now() + 5s;
    while (!challenge && Clock::now() < deadline) {
      pollfd p{fd, POLLIN, 0};
      if (poll(&p, 1, 50) <= 0) continue;
      const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
      ASSERT_GT(n, 0);
      decoder.feed(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(n)));
      if (auto m = decoder.next()) challenge = std::get<Challenge>(*m);
    }
    ASSERT_TRUE(challenge.has_value());
    send_all(fd, encode(hs.on_challenge(*challenge)));
    std::vector<Message> got;
    EXPECT_TRUE(read_until_closed(fd, 5s, &got));
    ASSERT_EQ(got.size(), 1u);
    ASSERT_TRUE(std::holds_alternative<Reject>(got[0]));
    EXPECT_EQ(std::get<Reject>(got[0]).reason, RejectReason::authentication_failed);
    close(fd);
  }
  {  // a truncated frame, then the client goes away
    const int fd = zenith::core::connect_loopback(port_);
    std::vector<std::uint8_t> frame = encode(Hello{kProtocolVersion, "test-dome", "c", Nonce{}});
    frame.resize(frame.size() / 2);
    send_all(fd, frame);
    close(fd);
  }
  // The master keeps serving node a.
  const std::size_t before = presented(dir_ / "out/a").size();
  EXPECT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= before + 3; }, 60s)) << logs();
  kill(master.pid, SIGTERM);
  EXPECT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  EXPECT_EQ(wait_exit(a, 20s), std::optional<int>(0)) << logs();
  const std::string log = read_text(dir_ / "master.log");
  EXPECT_NE(log.find("protocol error: bad_magic"), std::string::npos) << log;
  EXPECT_NE(log.find("protocol error: oversized"), std::string::npos) << log;
  EXPECT_NE(log.find("protocol error: unsupported_version"), std::string::npos) << log;
  EXPECT_NE(log.find("refused"), std::string::npos) << log;
  EXPECT_NE(log.find("wrong shared secret"), std::string::npos) << log;
  EXPECT_NE(log.find("truncated frame"), std::string::npos) << log;
}

// ---- a hostile master -------------------------------------------------------

TEST_F(ClusterProcess, NodeRefusesAMasterThatProvesTheWrongSecret) {
  const fs::path config = write_config(10);
  // A fake master: it answers the handshake but cannot compute the master MAC.
  const int listener = socket(AF_INET, SOCK_STREAM, 0);
  const int yes = 1;
  setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port_));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(listen(listener, 4), 0);
  const Child node = start_node(config, "a");
  pollfd p{listener, POLLIN, 0};
  ASSERT_EQ(poll(&p, 1, 60000), 1) << logs();
  const int fd = accept(listener, nullptr, nullptr);
  ASSERT_GE(fd, 0);
  FrameDecoder decoder;
  std::uint8_t buffer[512];
  const auto next_message = [&]() -> std::optional<Message> {
    const auto deadline = Clock::now() + 10s;
    while (Clock::now() < deadline) {
      if (auto m = decoder.next()) return m;
      pollfd q{fd, POLLIN, 0};
      if (poll(&q, 1, 50) <= 0) continue;
      const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
      if (n <= 0) return std::nullopt;
      decoder.feed(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(n)));
    }
    return std::nullopt;
  };
  const auto hello = next_message();
  ASSERT_TRUE(hello && std::holds_alternative<Hello>(*hello)) << logs();
  send_all(fd, encode(Challenge{random_nonce()}));
  const auto auth = next_message();
  ASSERT_TRUE(auth && std::holds_alternative<Authenticate>(*auth)) << logs();
  Welcome welcome;
  welcome.node_id = 1;
  welcome.master_mac.fill(0x42);  // not HMAC(secret, ...)
  welcome.heartbeat_interval_ms = 200;
  welcome.barrier_timeout_ms = 20000;
  send_all(fd, encode(welcome));
  EXPECT_EQ(wait_exit(node, 20s), std::optional<int>(2)) << logs();
  read_until_closed(fd, 2s);
  close(fd);
  close(listener);
  const std::string log = read_text(dir_ / "a.log");
  EXPECT_NE(log.find("failed to authenticate"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "out/a/presented.log"));
}

// ---- the operator console (docs/operator.md) ----------------------------------

/// The console's status, or an empty object when it cannot be had.
nlohmann::json console_status(int port) {
  const test::HttpReply r = test::http_request(port, boost::beast::http::verb::get, "/api/status");
  nlohmann::json status = r.status == 200 ? r.json() : nlohmann::json();
  return status.is_object() ? status : nlohmann::json::object();
}

/// POSTs one JSON command to the console on 127.0.0.1:`port`.
test::HttpReply console_command(int port, const std::string& command) {
  return test::http_request(port, boost::beast::http::verb::post, "/api/command", command);
}

/// One OSC datagram to 127.0.0.1:`port`.
void send_osc(int port, const std::vector<std::uint8_t>& packet) {
  boost::asio::io_context io;
  boost::asio::ip::udp::socket socket(io, boost::asio::ip::udp::v4());
  socket.send_to(boost::asio::buffer(packet),
                 {boost::asio::ip::make_address("127.0.0.1"), static_cast<std::uint16_t>(port)});
}

/// Paused: frames go on while the show time holds (expected). The held show
/// time, or nullopt when the frames did not go on.
std::optional<double> held_show_time(int port) {
  const auto frames = [&] { return console_status(port).value("frames_presented", -1); };
  int at = frames();
  if (!wait_until([&] { return frames() >= at + 2; }, 60s)) return std::nullopt;
  const double held = console_status(port).value("show_time_s", -1.0);
  at = frames();
  if (!wait_until([&] { return frames() >= at + 3; }, 60s)) return std::nullopt;
  EXPECT_EQ(console_status(port).value("show_time_s", -2.0), held) << "paused: the show time stops";
  return held;
}

/// Whether the status lists the three nodes, all in `state`.
bool all_nodes(const nlohmann::json& status, const std::string& state) {
  // Before the console answers the status is {}: a const json's [] on a missing key is undefined.
  if (!status.contains("nodes") || status.at("nodes").size() != 3) return false;
  for (const auto& n : status.at("nodes"))
    if (n.value("state", "") != state) return false;
  return true;
}

TEST_F(ClusterProcess, OperatorConsoleSwitchesAnAtmosphereOnEveryNodeAtOneFrameAndRefusesBadCommands) {
  const fs::path config = write_config(10);
  const int http = port_ + 2, osc = port_ + 3;
  const Child master = start_operated_cluster(config, http, osc, {"--debug-table-delay-ms", "3000"});
  ASSERT_TRUE(wait_until([&] { return all_nodes(console_status(http), "ready"); }, 400s)) << logs();
  const nlohmann::json first = console_status(http);
  EXPECT_EQ(first["state"], "playing");
  EXPECT_EQ(first["show"], nullptr);
  EXPECT_TRUE(first["live_atmospheres"]);
  ASSERT_EQ(first["atmospheres"].size(), 1u);
  EXPECT_EQ(first["atmospheres"][0]["body"], "Earth");
  EXPECT_EQ(first["atmospheres"][0]["parameters"]["aerosol"]["scattering"]["turbidity"], 2.0);
  const std::string old_version = first["atmospheres"][0]["version"];
  for (const auto& node : first["nodes"]) EXPECT_EQ(node["tables_held"], nlohmann::json::array({old_version})) << node;

  // The page, from the binary.
  const test::HttpReply page = test::http_request(http, boost::beast::http::verb::get, "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("operator console"), std::string::npos);

  // Refused, each with its reason; nothing applied.
  test::HttpReply r = console_command(
      http, R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scattering/turbidity", "value": 100})");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(r.json()["error"], "set Earth: /aerosol/scattering/turbidity = 100: must be in [1, 64]") << r.body;
  r = console_command(http, R"({"command": "pause"})");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("no show is playing"), std::string::npos) << r.body;
  r = test::http_request(http, boost::beast::http::verb::post, "/api/command", R"({"command": "quit"})", "text/plain");
  EXPECT_EQ(r.status, 415) << r.body;

  // OSC: an exposure applied, a turbidity out of range and a malformed packet refused.
  send_osc(osc, encode_osc_message({"/zenith/exposure", {40.0f}}));
  send_osc(osc, encode_osc_message({"/zenith/atmosphere/Earth/aerosol/scattering/turbidity", {200.0f}}));
  send_osc(osc, {'/', 'z', 'e', 'n'});
  ASSERT_TRUE(wait_until([&] { return console_status(http)["exposure"] == 40.0; }, 60s)) << logs();
  EXPECT_EQ(console_status(http)["exposure_override"], 40.0);
  EXPECT_EQ(console_status(http)["atmospheres"][0]["version"], old_version);

  // Live changes: each a new table version, on every node from one frame on.
  struct Version {
    std::string hex;
    std::uint64_t from_frame = 0;
  };
  std::vector<Version> versions{{old_version, 0}};
  nlohmann::json now;
  const auto atmosphere = [&] { return now["atmospheres"][0]; };
  /// Waits until the version after versions.back() is in effect, and records it (a waiting change may
  /// then be pending already).
  const auto next_version = [&] {
    const bool switched = wait_until(
        [&] {
          now = console_status(http);
          return now.contains("atmospheres") && atmosphere()["version"] != versions.back().hex;
        },
        400s);
    if (switched) versions.push_back({atmosphere()["version"], atmosphere()["effective_from_frame"]});
    return switched;
  };
  r = console_command(http,
                      R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scattering/turbidity", "value": 3})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.json()["reply"].get<std::string>().find("table version"), std::string::npos) << r.body;
  ASSERT_TRUE(next_version()) << logs();
  EXPECT_EQ(atmosphere()["parameters"]["aerosol"]["scattering"]["turbidity"], 3);
  EXPECT_TRUE(atmosphere()["pending"].is_null());
  for (const auto& node : now["nodes"]) {
    const auto& held = node["tables_held"];
    EXPECT_NE(std::find(held.begin(), held.end(), versions.back().hex), held.end()) << node;
    EXPECT_GT(node["frames_rendered"].get<std::uint64_t>(), 0u) << node;
    EXPECT_TRUE(node["last_render_ms"].is_number()) << node;
  }
  // The next version takes 3 s more to prepare (--debug-table-delay-ms): its progress shows, and a
  // change made meanwhile waits for it, then becomes the version after it.
  r = console_command(
      http, R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scattering/turbidity", "value": 2.5})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_TRUE(wait_until(
      [&] {
        now = console_status(http);
        return now.contains("atmospheres") && atmosphere()["pending"].is_object() &&
               atmosphere()["pending"]["stage"] == "preparing";
      },
      10s))
      << now.dump();
  EXPECT_EQ(atmosphere()["pending"]["change"], "/aerosol/scattering/turbidity = 2.5") << now.dump();
  r = console_command(http,
                      R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scale_height_m", "value": 1500})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.body.find("waits for the version before it"), std::string::npos) << r.body;
  EXPECT_EQ(console_status(http)["atmospheres"][0]["waiting"], "/aerosol/scale_height_m = 1500");
  ASSERT_TRUE(next_version()) << logs();
  EXPECT_EQ(atmosphere()["parameters"]["aerosol"]["scattering"]["turbidity"], 2.5);
  EXPECT_EQ(atmosphere()["parameters"]["aerosol"]["scale_height_m"], 1200) << "not yet: it waits";
  ASSERT_TRUE(next_version()) << logs();
  EXPECT_EQ(atmosphere()["parameters"]["aerosol"]["scattering"]["turbidity"], 2.5);
  EXPECT_EQ(atmosphere()["parameters"]["aerosol"]["scale_height_m"], 1500);
  EXPECT_TRUE(atmosphere()["waiting"].is_null());
  EXPECT_TRUE(atmosphere()["pending"].is_null());
  // Clear: the scene's own atmosphere again, a version every node still holds.
  r = console_command(http, R"({"command": "clear", "what": "atmosphere", "body": "Earth"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.body.find("the scene's own atmosphere, table version"), std::string::npos) << r.body;
  ASSERT_TRUE(next_version()) << logs();
  EXPECT_EQ(versions.back().hex, old_version);
  EXPECT_EQ(atmosphere()["parameters"]["aerosol"]["scattering"]["turbidity"], 2.0);
  const std::uint64_t last_switch = versions.back().from_frame;
  quit_in_sync(http, master, last_switch + 2);

  // Every node rendered each version from the same frame on, never before.
  ASSERT_EQ(versions.size(), 5u);
  for (const char* node : {"a", "b", "c"})
    for (const Presented& p : presented(dir_ / "out" / node)) {
      std::size_t v = 0;
      while (v + 1 < versions.size() && versions[v + 1].from_frame <= p.frame) ++v;
      EXPECT_EQ(p.tables, "Earth=" + versions[v].hex) << node << " frame " << p.frame;
    }
  expect_in_master_log({"operator console at http://127.0.0.1:" + std::to_string(http) + "/",
                        "operator (http 127.0.0.1): set Earth /aerosol/scattering/turbidity = 100 refused: set Earth: "
                        "/aerosol/scattering/turbidity = 100: must be in [1, 64]",
                        "operator (osc 127.0.0.1): exposure 40.0 → exposure 40 from the next frame on",
                        "operator (osc 127.0.0.1): set Earth /aerosol/scattering/turbidity = 200.0 refused",
                        "OSC from 127.0.0.1: refused 4 bytes",
                        "operator (http 127.0.0.1): set Earth /aerosol/scattering/turbidity = 3 → 'Earth'",
                        "takes effect at frame " + std::to_string(last_switch)});
}

TEST_F(ClusterProcess, OperatorConsolePausesSeeksAndPlaysAShowOverHttpAndOsc) {
  const fs::path config = write_config(5);
  const int http = port_ + 2, osc = port_ + 3;
  const Child master = start_sunset_show(config, http, osc);
  ASSERT_TRUE(wait_until([&] { return console_status(http).value("frames_presented", -1) >= 3; }, 400s)) << logs();
  nlohmann::json s = console_status(http);
  EXPECT_EQ(s["state"], "playing");
  EXPECT_EQ(s["show"]["duration_s"], 2.5);
  EXPECT_TRUE(s["live_atmospheres"]) << "set works during a show too";

  test::HttpReply r = console_command(http, R"({"command": "pause"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.body.find("paused"), std::string::npos) << r.body;
  ASSERT_TRUE(held_show_time(http)) << logs();
  EXPECT_EQ(console_status(http)["state"], "paused");

  r = console_command(http, R"({"command": "seek", "seconds": 99})");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(r.json()["error"], "command: /seconds = 99: must be in [0, 2.5] s (the show's duration)") << r.body;
  r = console_command(
      http, R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scattering/turbidity", "value": 100})");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(r.json()["error"], "set Earth: /aerosol/scattering/turbidity = 100: must be in [1, 64]") << r.body;
  r = console_command(http, R"({"command": "seek", "seconds": 0.5})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_TRUE(wait_until([&] { return console_status(http)["show_time_s"] == 0.5; }, 60s)) << logs();

  // OSC: rate and play.
  send_osc(osc, encode_osc_message({"/zenith/rate", {std::int32_t{2}}}));
  send_osc(osc, encode_osc_message({"/zenith/play", {1.0f}}));
  EXPECT_TRUE(wait_until(
      [&] {
        const nlohmann::json now = console_status(http);
        return now["state"] == "playing" && now["show"]["rate"] == 2.0 && now["show_time_s"] != 0.5;
      },
      60s))
      << logs();

  quit_in_sync(http, master);
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_NE(master_log.find("operator (http 127.0.0.1): pause → paused"), std::string::npos) << master_log;
  EXPECT_NE(master_log.find("operator (osc 127.0.0.1): play → playing"), std::string::npos) << master_log;
}

/// The latest frame's sun in the status: {elevation_deg, azimuth_deg}, or nullopt.
std::optional<std::pair<double, double>> status_sun(const nlohmann::json& status) {
  if (!status.contains("sun") || !status["sun"].is_object()) return std::nullopt;
  return std::pair{status["sun"]["elevation_deg"].get<double>(), status["sun"]["azimuth_deg"].get<double>()};
}

/// Whether the latest frame's sun is within 1e-6° of (elevation, azimuth).
bool sun_is(int port, double elevation_deg, double azimuth_deg) {
  const auto sun = status_sun(console_status(port));
  return sun && std::abs(sun->first - elevation_deg) < 1e-6 && std::abs(sun->second - azimuth_deg) < 1e-6;
}

TEST_F(ClusterProcess, OperatorConsoleSetsTheSunOfTheDefaultShowOverHttpAndOscUntilCleared) {
  const fs::path config = write_config(10);
  const int http = port_ + 2, osc = port_ + 3;
  const Child master = start_operated_cluster(config, http, osc);
  ASSERT_TRUE(
      wait_until([&] { return all_nodes(console_status(http), "ready") && status_sun(console_status(http)); }, 400s))
      << logs();
  // The scene's sun: 1° above the horizon at azimuth 272°.
  EXPECT_TRUE(sun_is(http, 1.0, 272.0)) << console_status(http).dump();
  EXPECT_TRUE(console_status(http)["sun_override"].is_null());

  test::HttpReply r = console_command(http, R"({"command": "sun", "elevation_deg": 91})");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(r.json()["error"], "command: /elevation_deg = 91: must be in [-90, 90] deg") << r.body;
  r = console_command(http, R"({"command": "sun", "elevation_deg": -4, "azimuth_deg": 250})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.json()["reply"], "sun at elevation -4°, azimuth 250° from the next frame on, until cleared");
  ASSERT_TRUE(wait_until([&] { return sun_is(http, -4.0, 250.0); }, 60s)) << console_status(http).dump();
  EXPECT_EQ(console_status(http)["sun_override"], (nlohmann::json{{"elevation_deg", -4.0}, {"azimuth_deg", 250.0}}));
  const auto frame_now = [&] { return console_status(http)["frame"].get<std::uint64_t>(); };
  const std::uint64_t set_by_http = frame_now();

  // OSC: the azimuth alone (the elevation stays the operator's), then the scene's sun again.
  send_osc(osc, encode_osc_message({"/zenith/sun/azimuth", {200.0f}}));
  ASSERT_TRUE(wait_until([&] { return sun_is(http, -4.0, 200.0); }, 60s)) << console_status(http).dump();
  const std::uint64_t set_by_osc = frame_now();
  send_osc(osc, encode_osc_message({"/zenith/clear/sun", {1.0f}}));
  ASSERT_TRUE(wait_until([&] { return sun_is(http, 1.0, 272.0); }, 60s)) << console_status(http).dump();
  EXPECT_TRUE(console_status(http)["sun_override"].is_null());
  const std::uint64_t cleared = frame_now();
  // Every node rendered one state per frame, the same on all of them; the pixels show each sun
  // (a frame under the scene's sun again equals frame 0 byte for byte).
  const auto played = quit_in_sync(http, master, cleared + 1);
  ASSERT_GT(played.size(), cleared + 1);
  const auto picture = [&](std::uint64_t frame) {
    return read_text(dir_ / "out/b/bottom-left" / fmt::format("frame-{:06d}.png", frame));
  };
  EXPECT_NE(picture(set_by_http), picture(0));
  EXPECT_NE(picture(set_by_osc), picture(set_by_http));
  EXPECT_EQ(picture(cleared), picture(0));
  expect_in_master_log(
      {"operator (http 127.0.0.1): sun elevation -4.0° azimuth 250.0° → sun at elevation -4°, azimuth 250°",
       "operator (osc 127.0.0.1): sun azimuth 200.0° → sun at elevation -4°, azimuth 200°",
       "operator (osc 127.0.0.1): clear sun → the default show's sun from the next frame on"});
}

TEST_F(ClusterProcess, OperatorConsoleOverridesTheSunTrackOfAShowUntilCleared) {
  const fs::path config = write_config(5);
  const int http = port_ + 2;
  const Child master = start_sunset_show(config, http);
  ASSERT_TRUE(wait_until([&] { return console_status(http).value("frames_presented", -1) >= 2; }, 400s)) << logs();
  // Paused, the sun track holds still: the override and the track's sun are both steady.
  ASSERT_EQ(console_command(http, R"({"command": "pause"})").status, 200);
  ASSERT_TRUE(held_show_time(http)) << logs();
  const auto track = status_sun(console_status(http));
  ASSERT_TRUE(track);
  EXPECT_NEAR(track->second, 272.0, 1e-6) << "the track's azimuth";
  EXPECT_LE(track->first, 4.0) << "the track's elevation, sinking from 4° to 0.5°";

  ASSERT_EQ(console_command(http, R"({"command": "sun", "elevation_deg": 20})").status, 200);
  ASSERT_TRUE(wait_until([&] { return sun_is(http, 20.0, 272.0); }, 60s)) << console_status(http).dump();
  // The override holds while the show plays on, until cleared.
  ASSERT_EQ(console_command(http, R"({"command": "play"})").status, 200);
  const auto frames = [&] { return console_status(http).value("frames_presented", -1); };
  const int at = frames();
  ASSERT_TRUE(wait_until([&] { return frames() >= at + 3; }, 60s)) << logs();
  EXPECT_TRUE(sun_is(http, 20.0, 272.0)) << console_status(http).dump();
  const test::HttpReply r = console_command(http, R"({"command": "clear", "what": "sun"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.json()["reply"], "the show's sun track from the next frame on");
  ASSERT_TRUE(wait_until(
      [&] {
        const auto sun = status_sun(console_status(http));
        return sun && sun->first <= 4.0 + 1e-9 && console_status(http)["sun_override"].is_null();
      },
      60s))
      << console_status(http).dump();

  quit_in_sync(http, master);
}

TEST_F(ClusterProcess, OperatorConsoleSetsAnAtmosphereDuringAShowWhichFollowsTheTrackUntilCleared) {
  // The sunset fixture loops through two table versions (turbidity 2, then 3). The operator's
  // scale height goes on top of either: a version of its own on every node from one frame on, a
  // new one when the track moves on, and clear gives the show's versions back.
  const fs::path config = write_config(5);
  const int http = port_ + 2, osc = port_ + 3;
  const Child master = start_sunset_show(config, http, osc);
  // A whole loop (6 frames): both of the show's versions seen.
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/a").size() >= 7; }, 400s)) << logs();
  std::set<std::string> show_versions;
  for (const Presented& p : presented(dir_ / "out/a")) show_versions.insert(p.tables.substr(6));  // "Earth=…"
  ASSERT_EQ(show_versions.size(), 2u);

  test::HttpReply r = console_command(
      http, R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scale_height_m", "value": 1500})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.body.find("it replaces the show's track of the body until cleared"), std::string::npos) << r.body;
  nlohmann::json now;
  const auto earth = [&] { return now["atmospheres"][0]; };
  const auto in_show = [&](const nlohmann::json& version) {
    return show_versions.count(version.get<std::string>()) > 0;
  };
  // The operator's version of the show's version of the moment, then the one of the other.
  std::set<std::string> operator_versions;
  ASSERT_TRUE(wait_until(
      [&] {
        now = console_status(http);
        if (!now.contains("atmospheres") || in_show(earth()["version"])) return false;
        operator_versions.insert(earth()["version"].get<std::string>());
        return operator_versions.size() == 2;
      },
      400s))
      << logs();
  EXPECT_EQ(earth()["operator_changes"], "/aerosol/scale_height_m = 1500");
  EXPECT_EQ(earth()["parameters"]["aerosol"]["scale_height_m"], 1500);
  EXPECT_TRUE(in_show(earth()["show_version"])) << now.dump();
  for (const auto& node : now["nodes"]) {
    const auto& held = node["tables_held"];
    EXPECT_NE(std::find(held.begin(), held.end(), earth()["version"]), held.end()) << node;
  }
  // Refused: out of range; over OSC, the show's own again.
  r = console_command(http,
                      R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scale_height_m", "value": -5})");
  EXPECT_EQ(r.status, 400) << r.body;
  send_osc(osc, encode_osc_message({"/zenith/clear/atmosphere/Earth", {}}));
  ASSERT_TRUE(wait_until(
      [&] {
        now = console_status(http);
        return now.contains("atmospheres") && in_show(earth()["version"]) && earth()["operator_changes"].is_null();
      },
      60s))
      << now.dump();
  EXPECT_EQ(earth()["version"], earth()["show_version"]);
  const std::uint64_t cleared = now["frame"];
  // On every node, the same tables at every frame: the show's, then one block of the operator's
  // (each of its versions from one frame on), then the show's again.
  const auto played = quit_in_sync(http, master, cleared + 3);
  std::string phases;
  for (const Presented& p : played) {
    const char phase = show_versions.count(p.tables.substr(6))       ? 's'
                       : operator_versions.count(p.tables.substr(6)) ? 'o'
                                                                     : '?';
    if (phases.empty() || phases.back() != phase) phases += phase;
  }
  EXPECT_EQ(phases, "sos");
  expect_in_master_log(
      {"operator (http 127.0.0.1): set Earth /aerosol/scale_height_m = 1500 → 'Earth'",
       "the show's track of 'Earth' moved on to version",
       "operator (osc 127.0.0.1): clear atmosphere of Earth → 'Earth' follows the show's track again"});
}

TEST_F(ClusterProcess, OperatorConsoleShowsTheDomeFromTheNodesThumbnailsOnlyWhileThePreviewIsOn) {
  const fs::path config = write_config(10);
  const int http = port_ + 2, osc = port_ + 3;
  const Child master = start_operated_cluster(config, http, osc);
  ASSERT_TRUE(wait_until([&] { return console_status(http).value("frames_presented", -1) >= 3; }, 400s)) << logs();
  // Off by default: no thumbnails, no preview.
  nlohmann::json preview = console_status(http)["preview"];
  EXPECT_EQ(preview["on"], false);
  EXPECT_EQ(preview["layout"], "dome");
  EXPECT_EQ(preview["width_px"], 128);
  EXPECT_EQ(preview["outputs"], 4);
  EXPECT_EQ(preview["tiles"], 0);
  EXPECT_TRUE(preview["frame"].is_null());
  EXPECT_EQ(test::http_request(http, boost::beast::http::verb::get, "/api/preview").status, 404);

  const test::HttpReply r = console_command(http, R"({"command": "preview", "preview": true})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.json()["reply"],
            "dome preview on: every node sends a thumbnail of each output every 5 frames (placed in the dome master, "
            "128x128 px at /api/preview)");
  // Every node's tiles arrive (the oldest tile is of a frame after the preview went on).
  const std::uint64_t on_at = console_status(http)["frame"];
  ASSERT_TRUE(wait_until(
      [&] {
        preview = console_status(http)["preview"];
        return preview["tiles"] == 4 && preview["oldest_frame"].get<std::uint64_t>() > on_at &&
               preview["frame"] == preview["oldest_frame"];
      },
      60s))
      << preview.dump();
  const test::HttpReply png = test::http_request(http, boost::beast::http::verb::get, "/api/preview");
  ASSERT_EQ(png.status, 200);
  const fs::path preview_file = dir_ / "preview.png";
  std::ofstream(preview_file, std::ios::binary) << png.body;
  const image::LinearImage picture = image::read_image(preview_file);
  ASSERT_EQ(picture.width, 2 * kQuadrantPx);
  ASSERT_EQ(picture.height, 2 * kQuadrantPx);
  // 64² quadrants give 64² thumbnails: the preview is the dome master the nodes wrote, pixel for
  // pixel within a code (a still scene: every frame is the same).
  const std::uint64_t frame = preview["frame"];
  ASSERT_TRUE(wait_until([&] { return presented(dir_ / "out/c").size() > frame; }, 60s));
  const std::pair<const char*, const char*> tiles[4] = {
      {"a", "top-left"}, {"a", "top-right"}, {"b", "bottom-left"}, {"c", "bottom-right"}};
  for (std::size_t q = 0; q < 4; ++q) {
    const image::LinearImage tile =
        image::read_image(dir_ / "out" / tiles[q].first / tiles[q].second / fmt::format("frame-{:06d}.png", frame));
    EXPECT_EQ(values_beyond_a_code_from_quadrant(tile, picture, q), 0) << tiles[q].second;
  }

  // Over OSC, off again: the thumbnails are dropped and no more come.
  send_osc(osc, encode_osc_message({"/zenith/preview", {false}}));
  ASSERT_TRUE(wait_until([&] { return console_status(http)["preview"]["on"] == false; }, 60s));
  const int at = console_status(http).value("frames_presented", -1);
  ASSERT_TRUE(wait_until([&] { return console_status(http).value("frames_presented", -1) >= at + 12; }, 60s));
  EXPECT_TRUE(console_status(http)["preview"]["frame"].is_null());
  EXPECT_EQ(console_status(http)["preview"]["tiles"], 0);
  EXPECT_EQ(test::http_request(http, boost::beast::http::verb::get, "/api/preview").status, 404);

  quit_in_sync(http, master);
  const std::string master_log = read_text(dir_ / "master.log");
  EXPECT_EQ(master_log.find("protocol"), std::string::npos) << master_log;
  EXPECT_NE(master_log.find("operator (osc 127.0.0.1): preview off → dome preview off"), std::string::npos)
      << master_log;
}

TEST_F(ClusterProcess, OperatorConsolePushesTheStatusOverAWebSocketUntilTheMasterStops) {
  namespace websocket = boost::beast::websocket;
  const fs::path config = write_config(10);
  const int http = port_ + 2;
  const Child master =
      start_master(config, 0, 120000, {"--sun-step-deg", "0", "--operator-port", std::to_string(http)});
  for (const char* n : {"a", "b", "c"}) start_node(config, n);
  ASSERT_TRUE(wait_until([&] { return console_status(http).value("frames_presented", -1) >= 2; }, 400s)) << logs();

  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  socket.connect({boost::asio::ip::make_address("127.0.0.1"), static_cast<std::uint16_t>(http)});
  const timeval timeout{10, 0};
  setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  websocket::stream<boost::asio::ip::tcp::socket> ws(std::move(socket));
  ws.handshake("127.0.0.1:" + std::to_string(http), "/api/events");
  const auto next = [&] {
    boost::beast::flat_buffer buffer;
    ws.read(buffer);
    return nlohmann::json::parse(boost::beast::buffers_to_string(buffer.data()));
  };
  // The status at once, then a new one as frames are presented: the same document as /api/status.
  nlohmann::json first = next();
  EXPECT_EQ(first["state"], "playing");
  EXPECT_EQ(first["nodes"].size(), 3u);
  const int start = first["frames_presented"];
  nlohmann::json previous = first;
  for (int i = 0; i < 5; ++i) {
    const nlohmann::json pushed = next();
    EXPECT_NE(pushed, previous) << "only changes are pushed";
    EXPECT_GE(pushed["frames_presented"].get<int>(), previous["frames_presented"].get<int>()) << pushed.dump();
    previous = pushed;
  }
  EXPECT_GT(previous["frames_presented"].get<int>(), start);
  // A command's effect arrives by push too.
  ASSERT_EQ(console_command(http, R"({"command": "exposure", "exposure": 33})").status, 200);
  ASSERT_TRUE(wait_until([&] { return next()["exposure_override"] == 33.0; }, 30s));

  // quit: the master closes the WebSocket (going away) and exits.
  EXPECT_EQ(console_command(http, R"({"command": "quit"})").status, 200);
  boost::beast::error_code ec;
  for (int i = 0; i < 100 && !ec; ++i) {
    boost::beast::flat_buffer buffer;
    ws.read(buffer, ec);
  }
  EXPECT_EQ(ec, websocket::error::closed) << ec.message();
  EXPECT_EQ(ws.reason().code, websocket::close_code::going_away);
  ASSERT_EQ(wait_exit(master, 30s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(master);
}

// ---- the operator console in a real browser (chromium headless) ----------------

/// Waits until the JavaScript expression `condition` is true in the page.
bool wait_in_page(test::WebDriver& browser, const std::string& condition, std::chrono::milliseconds timeout) {
  return wait_until(
      [&] {
        try {
          return browser.script("return " + condition + ";") == true;
        } catch (const std::exception&) {
          return false;
        }
      },
      timeout);
}

TEST_F(ClusterProcess, OperatorConsoleInABrowserPausesAShowAndTheShowTimeStops) {
  if (!test::browser_available()) GTEST_SKIP() << "chromium and chromium-driver are not installed (scripts/bootstrap)";
  const fs::path config = write_config(5);
  const int http = port_ + 2;
  const Child master = start_sunset_show(config, http);
  ASSERT_TRUE(wait_until([&] { return console_status(http).value("frames_presented", -1) >= 2; }, 400s)) << logs();

  test::WebDriver browser(port_ + 5, dir_ / "chromedriver.log");
  browser.open("http://127.0.0.1:" + std::to_string(http) + "/");
  ASSERT_TRUE(wait_in_page(browser, "document.getElementById('state').textContent === 'playing'", 60s));
  EXPECT_EQ(browser.script("return document.getElementById('show-name').textContent;"), "offline-sunset");
  // The status comes by push over the WebSocket; without it the page polls, and connects again.
  ASSERT_TRUE(wait_in_page(browser, "document.getElementById('transport').textContent === 'push'", 30s));
  browser.script("pushSocket.close(); return true;");
  ASSERT_TRUE(wait_in_page(browser, "document.getElementById('transport').textContent === 'polling'", 10s));
  const std::string frame_in_page = browser.script("return document.getElementById('frame').textContent;");
  EXPECT_TRUE(wait_in_page(browser,
                           "document.getElementById('frame').textContent !== '" + frame_in_page +
                               "' && document.getElementById('transport').textContent === 'polling'",
                           4s))
      << "polled while the push is away";
  EXPECT_TRUE(wait_in_page(browser, "document.getElementById('transport').textContent === 'push'", 30s));
  EXPECT_TRUE(wait_in_page(browser, "document.querySelectorAll('#nodes tbody tr').length === 3", 30s));
  browser.click(browser.element("#pause"));
  ASSERT_TRUE(wait_in_page(browser, "document.getElementById('state').textContent === 'paused'", 30s)) << logs();
  // Frames go on; the show time stops, in the API and on the page.
  const std::optional<double> held = held_show_time(http);
  ASSERT_TRUE(held) << logs();
  EXPECT_TRUE(wait_in_page(
      browser, "document.getElementById('show-time').textContent === '" + fmt::format("{:.3f}", *held) + " s'", 10s));
  // The sun: an elevation typed into its box replaces the track's (WebDriver keys: \ue009 Control
  // held until \ue000, \ue004 Tab), the button gives the track back.
  const std::string elevation = browser.element("#sun-elevation");
  browser.click(elevation);
  browser.type(elevation, "\ue009a\ue00020\ue004");
  ASSERT_TRUE(wait_in_page(browser, "document.getElementById('sun-source').textContent === '(operator)'", 30s))
      << logs();
  EXPECT_TRUE(wait_until([&] { return sun_is(http, 20.0, 272.0); }, 30s)) << console_status(http).dump();
  EXPECT_TRUE(wait_in_page(browser, "document.getElementById('sun-elevation-now').textContent === '20.00'", 30s));
  browser.screenshot(dir_ / "operator-console-show.png");
  browser.click(browser.element("#sun-reset"));
  EXPECT_TRUE(wait_in_page(browser, "document.getElementById('sun-source').textContent === \"(the show's)\"", 30s));
  EXPECT_TRUE(console_status(http)["sun_override"].is_null());
  browser.click(browser.element("#play"));
  EXPECT_TRUE(wait_in_page(browser, "document.getElementById('state').textContent === 'playing'", 30s));

  quit_in_sync(http, master);
}

/// A show chasing the house's timecode takes its start on the timecode from every desk: the API's JSON
/// command, OSC, and the web console's box (where a browser is installed), which shows the chase's
/// controls in place of the clock's; a label the show's rate does not have is refused by name.
TEST_F(ClusterProcess, OperatorConsoleMovesAChasedShowsStartOverTheApiOscAndTheBrowser) {
  const fs::path config = write_config(5);
  const int http = port_ + 2, osc = port_ + 3;
  const fs::path wav = write_ltc("01:00:00:00", 120);
  const Child master =
      start_master(config, 0, 120000,
                   {"--show", (kSource / "tests/data/shows/chase-sunset.json").string(), "--ltc-file", wav.string(),
                    "--operator-port", std::to_string(http), "--osc-port", std::to_string(osc)});
  for (const char* n : {"a", "b", "c"})
    start_node(config, n, {"--scene", (kSource / "configs/scenes/earth-sunset.json").string()});
  const auto chase = [&] { return console_status(http).value("timecode", nlohmann::json::object()); };
  ASSERT_TRUE(wait_until([&] { return chase().value("state", "") == "locked"; }, 300s)) << logs();
  EXPECT_EQ(chase()["offset"], "01:00:00:00");

  // The API: show time 0 two seconds earlier on the timecode, so the show jumps 2 s on.
  const double before_s = console_status(http).value("show_time_s", 0.0);
  const test::HttpReply moved = console_command(http, R"({"command": "timecode", "offset": "00:59:58:00"})");
  EXPECT_EQ(moved.status, 200) << moved.body;
  EXPECT_EQ(moved.json()["reply"], "show time 0 at 00:59:58:00 from the next frame on");
  EXPECT_TRUE(wait_until([&] { return chase()["offset"] == "00:59:58:00"; }, 30s)) << chase().dump();  // next frame
  EXPECT_TRUE(wait_until([&] { return console_status(http).value("show_time_s", 0.0) > before_s + 2.0; }, 30s))
      << console_status(http).dump();
  const test::HttpReply refused = console_command(http, R"({"command": "timecode", "offset": "01:00:00:29"})");
  EXPECT_EQ(refused.status, 400) << refused.body;
  EXPECT_NE(refused.body.find("frames [0, 25)"), std::string::npos) << refused.body;
  EXPECT_NE(console_command(http, R"({"command": "pause"})").body.find("the show follows the house's timecode"),
            std::string::npos);

  // OSC.
  send_osc(osc, encode_osc_message({"/zenith/timecode/offset", {std::string("00:59:59:00")}}));
  EXPECT_TRUE(wait_until([&] { return chase()["offset"] == "00:59:59:00"; }, 30s)) << chase().dump();

  // The web console.
  if (test::browser_available()) {
    test::WebDriver browser(port_ + 5, dir_ / "chromedriver.log");
    browser.open("http://127.0.0.1:" + std::to_string(http) + "/");
    ASSERT_TRUE(wait_in_page(browser, "!document.getElementById('chase-controls').hidden", 60s));
    EXPECT_EQ(browser.script("return document.getElementById('clock-controls').hidden;"), true)
        << "the clock's controls give way to the chase's";
    EXPECT_TRUE(
        wait_in_page(browser, "document.getElementById('timecode-offset-now').textContent === '00:59:59:00'", 30s));
    EXPECT_TRUE(wait_in_page(browser, "document.getElementById('timecode-state').textContent === 'locked'", 30s));
    const std::string box = browser.element("#timecode-offset");
    browser.click(box);
    browser.type(box, "\ue009a\ue00001:00:00:00");  // Control-A, then the label
    browser.click(browser.element("#timecode-offset-apply"));
    EXPECT_TRUE(wait_until([&] { return chase()["offset"] == "01:00:00:00"; }, 30s)) << chase().dump();
    EXPECT_TRUE(
        wait_in_page(browser, "document.getElementById('timecode-offset-now').textContent === '01:00:00:00'", 30s));
    browser.screenshot(dir_ / "operator-console-chase.png");
  } else {
    std::printf("[ skipped  ] the web console's part: chromium and chromium-driver are not installed\n");
  }
  quit_in_sync(http, master);
  expect_in_master_log({"): timecode offset 00:59:58:00 → show time 0 at 00:59:58:00 from the next frame on",
                        "): timecode offset 00:59:59:00 → show time 0 at 00:59:59:00", "master: operator (osc "});
}

TEST_F(ClusterProcess, OperatorConsoleInABrowserChangesTurbidityAndTheNewVersionReachesEveryNode) {
  if (!test::browser_available()) GTEST_SKIP() << "chromium and chromium-driver are not installed (scripts/bootstrap)";
  const fs::path config = write_config(10);
  const int http = port_ + 2;
  const Child master =
      start_master(config, 0, 120000,
                   {"--sun-step-deg", "0", "--operator-port", std::to_string(http), "--debug-table-delay-ms", "4000"});
  for (const char* n : {"a", "b", "c"}) start_node(config, n);
  ASSERT_TRUE(wait_until([&] { return all_nodes(console_status(http), "ready"); }, 400s)) << logs();
  const std::string first_version = console_status(http)["atmospheres"][0]["version"];

  test::WebDriver browser(port_ + 5, dir_ / "chromedriver.log");
  browser.open("http://127.0.0.1:" + std::to_string(http) + "/");
  const std::string version_in_page =
      "document.querySelector('.atmosphere[data-body=\"Earth\"] .row[data-version]').dataset.version";
  ASSERT_TRUE(wait_in_page(browser, version_in_page + " === '" + first_version + "'", 60s));
  // The dome preview: on from the page, then the nodes' thumbnails in it (four 64² tiles: 128²).
  browser.click(browser.element("#preview-on"));
  ASSERT_TRUE(wait_in_page(browser, "document.getElementById('preview-image').naturalWidth === 128", 60s)) << logs();
  EXPECT_TRUE(wait_in_page(browser, "!document.getElementById('preview-image').hidden", 10s));
  const std::string turbidity = "input[type=number][data-pointer=\"/aerosol/scattering/turbidity\"]";
  /// Types a turbidity into the page's box over what it holds, and leaves it (Tab): the change event
  /// sends the command. WebDriver keys: \ue009 Control (held until \ue000), \ue004 Tab.
  const auto type_turbidity = [&](const std::string& value) {
    const std::string box = browser.element(turbidity);
    browser.click(box);
    browser.type(box, "\ue009a\ue000" + value + "\ue004");
  };
  // The first change (its tables prepared at once), then a second whose preparation takes 4 s
  // longer: the page shows its progress, then the version every node switched to.
  type_turbidity("2.75");
  ASSERT_TRUE(wait_in_page(browser, version_in_page + " !== '" + first_version + "'", 400s)) << logs();
  const std::string second_version = browser.script("return " + version_in_page + ";");
  type_turbidity("3.25");
  ASSERT_TRUE(wait_in_page(browser, "document.querySelector('.pending').dataset.stage === 'preparing'", 30s)) << logs();
  EXPECT_TRUE(wait_in_page(browser, "document.querySelector('.pending progress') !== null", 5s));
  browser.screenshot(dir_ / "operator-console-atmosphere.png");
  ASSERT_TRUE(wait_in_page(browser, version_in_page + " !== '" + second_version + "'", 400s)) << logs();
  const nlohmann::json status = console_status(http);
  const std::string third_version = status["atmospheres"][0]["version"];
  EXPECT_EQ(browser.script("return " + version_in_page + ";"), third_version);
  EXPECT_EQ(status["atmospheres"][0]["parameters"]["aerosol"]["scattering"]["turbidity"], 3.25);
  for (const auto& node : status["nodes"]) {
    const auto& held = node["tables_held"];
    EXPECT_NE(std::find(held.begin(), held.end(), third_version), held.end()) << node;
  }
  const std::uint64_t effective = status["atmospheres"][0]["effective_from_frame"];
  // Every node shows the three versions in order, each from the same frame on (in sync: the same
  // tables on every node at every frame).
  quit_in_sync(http, master, effective + 2);
  std::vector<std::string> seen;
  for (const Presented& p : presented(dir_ / "out/a"))
    if (seen.empty() || seen.back() != p.tables) seen.push_back(p.tables);
  EXPECT_EQ(seen,
            (std::vector<std::string>{"Earth=" + first_version, "Earth=" + second_version, "Earth=" + third_version}));
}

/// frame → "LEVEL R,G,B": the fade of each frame in a node's presented.log (frames of the picture alone are absent).
std::map<std::uint64_t, std::string> fades(const fs::path& node_dir) {
  std::map<std::uint64_t, std::string> out;
  std::ifstream in(node_dir / "presented.log");
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t at = line.find(" fade ");
    std::istringstream fields(line);
    std::string word;
    std::uint64_t frame = 0;
    if (at != std::string::npos && fields >> word >> frame) out[frame] = line.substr(at + 6);
  }
  return out;
}

/// The first number after `prefix` in `text` (the frame a reply or log line names); nullopt when absent.
std::optional<std::uint64_t> number_after(const std::string& text, const std::string& prefix) {
  const std::size_t at = text.find(prefix);
  if (at == std::string::npos) return std::nullopt;
  return std::stoull(text.substr(at + prefix.size()));
}

TEST_F(ClusterProcess, OperatorFadesEveryNodeAtOneFrameBlacksOutAtTheNextAndTheRecordingReplaysIt) {
  const fs::path config = write_config(10);
  const int http = port_ + 2, osc = port_ + 3;
  const fs::path recording = dir_ / "recording.json";
  // The sun stands still: every frame is the same picture, but for the fade.
  const Child master = start_operated_cluster(config, http, osc, {"--record", recording.string()});
  ASSERT_TRUE(wait_until([&] { return all_nodes(console_status(http), "ready") && all_nodes_past(1); }, 400s))
      << logs();

  // Out of range: refused with the range, nothing changes.
  test::HttpReply r = console_command(http, R"({"command": "fade", "level": 1, "seconds": -2})");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(r.json()["error"], "command: /seconds = -2: must be in [0, 3600] s") << r.body;
  // 1 s at 10 Hz: 10 frames toward orange, the midpoint (level ½) at its fifth.
  r = console_command(http, R"({"command": "fade", "level": 1, "seconds": 1, "colour": [1, 0.5, 0]})");
  ASSERT_EQ(r.status, 200) << r.body;
  const std::optional<std::uint64_t> start = number_after(r.json()["reply"].get<std::string>(), "), frames ");
  ASSERT_TRUE(start) << r.body;
  ASSERT_TRUE(wait_until([&] { return all_nodes_past(*start + 11); }, 120s)) << logs();
  EXPECT_EQ(console_status(http)["fade"]["level"], 1.0) << console_status(http).dump();
  // Blackout over OSC: black from the next frame on; then the picture again at once.
  send_osc(osc, encode_osc_message({"/zenith/blackout", {}}));
  ASSERT_TRUE(
      wait_until([&] { return read_text(dir_ / "master.log").find("blackout from frame") != std::string::npos; }, 60s))
      << logs();
  const std::optional<std::uint64_t> black = number_after(read_text(dir_ / "master.log"), "blackout from frame ");
  ASSERT_TRUE(black);
  ASSERT_TRUE(wait_until([&] { return all_nodes_past(*black + 1); }, 120s)) << logs();
  r = console_command(http, R"({"command": "blackout", "blackout": "off"})");
  ASSERT_EQ(r.status, 200) << r.body;
  const std::optional<std::uint64_t> picture = number_after(r.json()["reply"].get<std::string>(), "from frame ");
  ASSERT_TRUE(picture) << r.body;
  const auto live = quit_in_sync(http, master, *picture + 1);

  // Every node presented the same fade at every frame (the state digests include it).
  const auto faded = fades(dir_ / "out/a");
  EXPECT_EQ(fades(dir_ / "out/b"), faded);
  EXPECT_EQ(fades(dir_ / "out/c"), faded);
  EXPECT_EQ(faded.count(*start - 1), 0u) << "no fade before the command";
  EXPECT_EQ(faded.at(*start + 4), "0.5 1,0.5,0") << "the midpoint: u = 5/10, smoothstep ½";
  EXPECT_EQ(faded.at(*start + 9), "1 1,0.5,0");
  EXPECT_EQ(faded.at(*black - 1), "1 1,0.5,0");
  EXPECT_EQ(faded.at(*black), "1 0,0,0");
  EXPECT_EQ(faded.count(*picture), 0u);
  // The pixels: the midpoint is ½ picture + ½ orange in display-linear values on every output
  // (within one 8-bit code of the sRGB file), the blackout black, the picture afterwards frame 0's.
  const auto file = [&](const std::string& node, const std::string& output, std::uint64_t frame) {
    return dir_ / "out" / node / output / fmt::format("frame-{:06d}.png", frame);
  };
  const double orange[3] = {1.0, 0.5, 0.0};
  for (const auto& [node, output] : std::vector<std::pair<std::string, std::string>>{
           {"a", "top-left"}, {"a", "top-right"}, {"b", "bottom-left"}, {"c", "bottom-right"}}) {
    const image::LinearImage sky = image::read_image(file(node, output, 0));
    const image::LinearImage mid = image::read_image(file(node, output, *start + 4));
    ASSERT_EQ(mid.rgb.size(), sky.rgb.size());
    int off = 0;
    for (std::size_t i = 0; i < sky.rgb.size(); ++i) {
      const double expected = 0.5 * sky.rgb[i] + 0.5 * orange[i % 3];
      const auto code = [](double v) { return std::lround(255.0 * image::srgb_encode(static_cast<float>(v))); };
      if (std::abs(code(expected) - code(mid.rgb[i])) > 1) ++off;
    }
    EXPECT_EQ(off, 0) << node << " " << output;
    const image::LinearImage out = image::read_image(file(node, output, *black));
    EXPECT_EQ(*std::max_element(out.rgb.begin(), out.rgb.end()), 0.0f) << node << " " << output << ": blackout";
    EXPECT_EQ(read_text(file(node, output, *picture)), read_text(file(node, output, 0))) << node << " " << output;
  }

  // The recording on fresh nodes: the same states frame by frame, the same files byte for byte.
  fs::rename(dir_ / "out", dir_ / "out-live");
  for (const char* n : {"master", "a", "b", "c"})
    fs::rename(dir_ / (std::string(n) + ".log"), dir_ / (std::string(n) + "-live.log"));
  children_.clear();
  const Child replay = start_master(config, 0, 120000, {"--show", recording.string(), "--unpaced"});
  for (const char* n : {"a", "b", "c"}) start_node(config, n);
  ASSERT_EQ(wait_exit(replay, 400s), std::optional<int>(0)) << logs();
  expect_nodes_exit_cleanly(replay);
  const auto replayed = expect_in_sync(dir_ / "out", live.back().frame);
  ASSERT_EQ(replayed.size(), live.size());
  for (std::size_t i = 0; i < live.size(); ++i) EXPECT_EQ(replayed[i].digest, live[i].digest) << "frame " << i;
  EXPECT_EQ(fades(dir_ / "out/b"), faded);
  for (const std::uint64_t frame : {*start + 4, *black})
    EXPECT_EQ(read_text(file("b", "bottom-left", frame)),
              read_text(dir_ / "out-live/b/bottom-left" / fmt::format("frame-{:06d}.png", frame)))
        << "frame " << frame;
}

}  // namespace
}  // namespace zenith::cluster
