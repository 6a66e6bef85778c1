// Cluster soak (docs/cluster.md, "Soak"): a long show on a local cluster with
// faults injected at random, to show that no single fault stops it and that
// nothing grows without bound.
//
// One `zenith master` and N `zenith node` processes on 127.0.0.1, started as
// the cluster tests start them, in a fresh folder holding a viewport config of
// N tiny fisheye outputs (--size, 16² by default) and a cluster config giving
// each node one (barrier timeout 2 s, heartbeat 200 ms: silence limit 10 s,
// reconnect time 60 s). The master presents --frames frames at --fps. Every
// --fault-interval-s (uniform in [MIN, MAX]) one fault, chosen at random:
//
//   kill       kill -9 of a node, then a new process for it at once (as
//              `zenith cluster --restart-nodes` does); the first node is never
//              killed, so one node process lives through the whole run
//   stop       SIGSTOP of a node for 0.3–3 s (it misses the barrier and comes
//              back), or with --long-stop-probability for 10.5–13 s, past the
//              master's silence limit (the master drops it; it reconnects)
//   garbage    a raw TCP connection to the master: random bytes, a frame
//              header with an impossible length, or a connection that stays
//              silent; each held open 0.5–6 s
//
// No fault is injected in the last --quiet-fraction of the show, nor one that
// would last into it (at the nominal frame rate), so every node is back for
// the end. Then, from each node's presented.log: frames
// presented, frames missed (between its first and last frame) and in how many
// runs, reconnections (its "welcomed again" log lines) and restarts; the frames
// whose state differs between nodes (must be 0); and the resident memory
// (VmRSS) of the master and of every node when the show started and at its
// end (a restarted node's end figure is its last process's).
//
// With --attacks the master also serves the operator console, the control
// socket and OSC, and half the turns are an attack instead of a fault
// (bench/soak_attacks.h: DNS rebinding, slowloris, a web page's request on the
// control socket, stray nodes with a taken name, pre-authentication floods,
// OSC floods with bad bytes), each checked for its answer; the first node is
// then never stopped either, and must present every frame from the first
// attack on. At the end `zenith cluster` is started on the same config and
// killed with kill -9: no process of its may outlive it.
//
// Exit status 0 when the master and every node ended with status 0, every
// node presented the last frame, no frame's state differs between nodes, and
// the RSS growth of the master and of the never-killed node is at most
// --max-rss-growth-mib (with --attacks also: every attack answered as it
// should, no gap in the first node's frames after the first attack, no
// orphan); 1 otherwise; 2 for bad options.
//
//   cluster_soak [--zenith PATH] [--frames 10000] [--nodes 3] [--size 16] [--fps 100]
//                [--fault-interval-s 1.5,4] [--long-stop-probability 0.15] [--quiet-fraction 0.1]
//                [--max-rss-growth-mib 32] [--seed 17] [--attacks] [--cache DIR] [--work DIR] [--timeout-s 3600]
//                [--keep]
#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/command_line.h"
#include "bench/soak_attacks.h"
#include "bench/tiny_cluster.h"
#include "core/files.h"
#include "core/process.h"
#include "core/strings.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr const char* kSecretVar = "ZENITH_CLUSTER_SOAK_SECRET";

constexpr const char* kUsage = R"(cluster_soak: a long show on a local cluster with random faults (kill -9 and restart,
stop/continue, garbage connections); frames per node, gaps, rejoins, memory (docs/cluster.md, "Soak")

  --zenith PATH                 the zenith binary (default: this build's)
  --frames N                    frames of the show (default 10000)
  --nodes N                     nodes, one tiny output each (default 3, at least 2)
  --size PX                     each output is PX×PX (default 16)
  --fps F                       the show's frame rate (default 100)
  --fault-interval-s MIN,MAX    time between faults, uniform (default 1.5,4)
  --long-stop-probability P     a stop lasts past the silence limit (10.5–13 s) with this probability (default 0.15)
  --quiet-fraction F            no faults in this last part of the show (default 0.1)
  --max-rss-growth-mib M        allowed RSS growth of the master and the never-killed node (default 32)
  --seed N                      the faults' random seed (default 17)
  --attacks                     half the turns are attacks on the console, control socket, OSC and cluster port
  --cache DIR                   the master's table cache (default WORK/table-cache)
  --work DIR                    run folder, logs (default $TMPDIR/zenith-cluster-soak)
  --timeout-s S                 give up after this long (default 3600)
  --keep                        keep the frames (the logs are always kept)
)";

struct Options : zenith::bench::TinyRunOptions {
  int frames = 10000;
  int nodes = 3;
  double fps = 100.0;
  double fault_min_s = 1.5, fault_max_s = 4.0;
  double long_stop_probability = 0.15;
  double quiet_fraction = 0.1;
  double max_rss_growth_mib = 32.0;
  unsigned seed = 17;
  bool attacks = false;
};

Options parse_options(int argc, char** argv) {
  Options o;
  o.zenith = ZENITH_BINARY;
  o.work = fs::temp_directory_path() / "zenith-cluster-soak";
  o.timeout_s = 3600;
  for (zenith::bench::CommandLine args(argc, argv); args.next();) {
    const std::string& a = args.option();
    if (o.read(args, kUsage)) continue;
    if (a == "--frames")
      o.frames = std::stoi(args.value());
    else if (a == "--nodes")
      o.nodes = std::stoi(args.value());
    else if (a == "--fps")
      o.fps = std::stod(args.value());
    else if (a == "--fault-interval-s") {
      const std::string v = args.value();
      const auto comma = v.find(',');
      if (comma == std::string::npos) throw std::invalid_argument("--fault-interval-s: expected MIN,MAX");
      o.fault_min_s = std::stod(v.substr(0, comma));
      o.fault_max_s = std::stod(v.substr(comma + 1));
    } else if (a == "--long-stop-probability")
      o.long_stop_probability = std::stod(args.value());
    else if (a == "--quiet-fraction")
      o.quiet_fraction = std::stod(args.value());
    else if (a == "--max-rss-growth-mib")
      o.max_rss_growth_mib = std::stod(args.value());
    else if (a == "--seed")
      o.seed = static_cast<unsigned>(std::stoul(args.value()));
    else if (a == "--attacks")
      o.attacks = true;
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (o.frames < 10) throw std::invalid_argument("--frames must be at least 10");
  if (o.nodes < 2 || o.nodes > 16) throw std::invalid_argument("--nodes must be in [2, 16]");
  if (o.size_px < 1) throw std::invalid_argument("--size must be positive");
  if (!(o.fps > 0.0 && o.fps <= 1000.0)) throw std::invalid_argument("--fps must be in (0, 1000]");
  if (!(o.fault_min_s > 0.0 && o.fault_min_s <= o.fault_max_s))
    throw std::invalid_argument("--fault-interval-s: need 0 < MIN <= MAX");
  if (!(o.long_stop_probability >= 0.0 && o.long_stop_probability <= 1.0))
    throw std::invalid_argument("--long-stop-probability must be in [0, 1]");
  if (!(o.quiet_fraction >= 0.0 && o.quiet_fraction < 1.0))
    throw std::invalid_argument("--quiet-fraction must be in [0, 1)");
  return o;
}

using zenith::bench::tiny_node_name;

using zenith::core::count_of;
using zenith::core::read_text;

/// VmRSS of `pid` in MiB; nullopt when it cannot be read (the process is gone).
std::optional<double> rss_mib(pid_t pid) {
  std::ifstream in(fmt::format("/proc/{}/status", pid));
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  return std::nullopt;
}

/// The last frame number in a presented.log, read from its tail.
std::optional<std::uint64_t> last_presented(const fs::path& log) {
  std::ifstream in(log, std::ios::binary | std::ios::ate);
  if (!in) return std::nullopt;
  const std::streamoff size = in.tellg();
  const std::streamoff from = std::max<std::streamoff>(0, size - 512);
  in.seekg(from);
  std::string tail(static_cast<std::size_t>(size - from), '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  std::optional<std::uint64_t> last;
  std::istringstream lines(tail);
  for (std::string line; std::getline(lines, line);) {
    unsigned long long frame = 0;
    char digest[80];
    if (std::sscanf(line.c_str(), "frame %llu state %79s", &frame, digest) == 2) last = frame;
  }
  return last;
}

/// frame → state digest, from a presented.log.
std::map<std::uint64_t, std::string> presented(const fs::path& log) {
  std::map<std::uint64_t, std::string> out;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string word, state, digest;
    std::uint64_t frame = 0;
    if (fields >> word >> frame >> state >> digest) out[frame] = digest;
  }
  return out;
}

// ---- garbage connections ------------------------------------------------------

/// An open garbage connection, closed at `close_at`.
struct Garbage {
  int fd;
  Clock::time_point close_at;
};

// ---- orphans ------------------------------------------------------------------

using zenith::core::process_gone;

/// Starts `zenith cluster` on `config` (its master on `port`), waits until its
/// first node presented a frame, kills it with kill -9 and waits up to 30 s
/// for every child it logged to end; "" when none is left, else which are.
std::string launcher_orphans(const Options& opt, const fs::path& config, const fs::path& cache, const fs::path& dir,
                             int port) {
  const fs::path log = dir / "launcher.log";
  const pid_t launcher =
      zenith::core::spawn_process(opt.zenith,
                                  {"cluster", "--cluster", config.string(), "--port", std::to_string(port), "--frames",
                                   "100000", "--out", (dir / "launcher-out").string(), "--cache", cache.string()},
                                  log, zenith::core::LogMode::truncate);
  const auto deadline = Clock::now() + 180s;
  while (Clock::now() < deadline && !last_presented(dir / "launcher-out" / tiny_node_name(0) / "presented.log"))
    std::this_thread::sleep_for(100ms);
  kill(launcher, SIGKILL);
  zenith::core::wait_for_exit(launcher, 5000ms);
  std::vector<pid_t> children;
  const std::string text = read_text(log);
  for (std::size_t at = text.find("started (pid "); at != std::string::npos; at = text.find("started (pid ", at + 1))
    children.push_back(static_cast<pid_t>(std::stol(text.substr(at + 13))));
  if (children.empty()) return "the launcher logged no child (see " + log.string() + ")";
  const auto gone_by = Clock::now() + 30s;
  while (Clock::now() < gone_by && !std::all_of(children.begin(), children.end(), process_gone))
    std::this_thread::sleep_for(100ms);
  std::string left;
  for (const pid_t pid : children)
    if (!process_gone(pid)) {
      left += fmt::format("{}pid {}", left.empty() ? "" : ", ", pid);
      kill(pid, SIGKILL);
    }
  return left.empty() ? std::string() : fmt::format("orphans after kill -9 of the launcher: {}", left);
}

// ---- the soak -----------------------------------------------------------------

struct Node {
  std::string name;
  std::vector<std::string> args;
  fs::path log;
  pid_t pid = -1;
  int restarts = 0;
  std::optional<Clock::time_point> stopped_until;
  /// A killed node's new process, until it presents a frame: when it was
  /// started and the last frame its predecessor presented.
  std::optional<Clock::time_point> restarted_at;
  std::optional<std::uint64_t> last_before_restart;
  std::optional<double> rss_start;  ///< when the show started (its first process)
  std::optional<double> rss_end;    ///< the last sample of its current process
  /// Set once its process left at the master's Goodbye (reaped: never signal its pid again).
  std::optional<int> exit_status;
};

int run(const Options& opt) {
  const fs::path dir = opt.work;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path cache = opt.cache.value_or(opt.work.parent_path() / "zenith-cluster-soak-cache");
  setenv(kSecretVar, "cluster-soak-secret-0123456789abcdef", 1);
  // The cluster port, then (with --attacks) the console, the control socket, OSC and a launcher's port.
  const int port = zenith::core::free_loopback_port(static_cast<int>(20000 + (getpid() * 17) % 29000), 5);
  const zenith::bench::AttackPorts ports{port, port + 1, port + 2, port + 3};
  std::mt19937 rng(opt.seed);
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };

  const fs::path config = zenith::bench::write_tiny_cluster(
      dir, {"soak", opt.nodes, opt.size_px, port,
            // The barrier: the soak counts every frame each surviving node presents.
            fmt::format(R"({{"heartbeat_ms": 200, "barrier_timeout_ms": 2000, "frame_rate_hz": {}, "reconnect_s": 60, )"
                        R"("lookahead_frames": 0}})",
                        opt.fps),
            kSecretVar, "small", 1});
  const auto started = Clock::now();
  const auto deadline = started + std::chrono::seconds(opt.timeout_s);

  std::vector<std::string> master_args = {
      "master",  "--cluster",    config.string(),       "--frames", std::to_string(opt.frames),
      "--cache", cache.string(), "--wait-for-nodes-ms", "300000"};
  if (opt.attacks)
    master_args.insert(master_args.end(), {"--operator-port", std::to_string(ports.console), "--control-port",
                                           std::to_string(ports.control), "--osc-port", std::to_string(ports.osc)});
  const pid_t master =
      zenith::core::spawn_process(opt.zenith, master_args, dir / "master.log", zenith::core::LogMode::truncate);
  zenith::bench::SoakAttacks attacks(
      opt.zenith, {"node", "--cluster", config.string(), "--connect-timeout-ms", "60000"}, dir, ports);
  std::optional<std::uint64_t> first_attack_frame;
  std::vector<Node> nodes;
  for (int i = 0; i < opt.nodes; ++i) {
    Node n;
    n.name = tiny_node_name(i);
    n.args = {"node",
              "--cluster",
              config.string(),
              "--name",
              n.name,
              "--out",
              (dir / "out").string(),
              "--cache",
              (dir / "node-cache" / n.name).string(),
              "--connect-timeout-ms",
              "300000"};
    n.log = dir / (n.name + ".log");
    n.pid = zenith::core::spawn_process(opt.zenith, n.args, n.log, zenith::core::LogMode::truncate);
    nodes.push_back(std::move(n));
  }
  const auto presented_log = [&](const Node& n) { return dir / "out" / n.name / "presented.log"; };
  const auto current_frame = [&]() {
    std::optional<std::uint64_t> f;
    for (const Node& n : nodes)
      if (const auto l = last_presented(presented_log(n))) f = std::max(f.value_or(0), *l);
    return f;
  };

  std::string failure;
  std::optional<double> master_rss_start, master_rss_end;
  std::optional<int> master_status;
  int kills = 0, short_stops = 0, long_stops = 0, garbage_count = 0;
  // How long a killed node takes to present again (a new process: start,
  // tables from its cache, the warm-up render): at first the time the nodes
  // took to start the show, then the longest rejoin seen. A kill is made only
  // when that much is left before the quiet part (on a loaded machine the
  // warm-up alone takes seconds, and a node not back by the end fails the run).
  double rejoin_s = 2.0;
  std::vector<Garbage> garbage;
  const std::uint64_t quiet_from = static_cast<std::uint64_t>(opt.frames * (1.0 - opt.quiet_fraction));
  auto next_fault = Clock::now();
  bool show_started = false;
  auto last_report = Clock::now();

  while (!master_status) {
    if (Clock::now() > deadline) {
      failure = fmt::format("the show did not end within {} s", opt.timeout_s);
      break;
    }
    master_status = zenith::core::wait_for_exit(master, 50ms);
    if (master_status) break;
    const auto now = Clock::now();
    const std::optional<std::uint64_t> frame = current_frame();
    // The show started once every node presented a frame: the memory figures start here.
    if (!show_started && std::all_of(nodes.begin(), nodes.end(),
                                     [&](const Node& n) { return last_presented(presented_log(n)).has_value(); })) {
      show_started = true;
      rejoin_s = std::max(rejoin_s, std::chrono::duration<double>(now - started).count());
      master_rss_start = rss_mib(master);
      for (Node& n : nodes) n.rss_start = rss_mib(n.pid);
      next_fault = now + std::chrono::milliseconds(static_cast<int>(1000 * uniform(opt.fault_min_s, opt.fault_max_s)));
      fmt::print("soak: the show started; master RSS {:.1f} MiB\n", master_rss_start.value_or(0));
    }
    // The memory figures end with the last sample before the master's Goodbye.
    if (const auto r = rss_mib(master)) master_rss_end = r;
    for (Node& n : nodes)
      if (const auto r = n.exit_status ? std::nullopt : rss_mib(n.pid)) n.rss_end = r;
    // Resume stopped nodes; close garbage connections whose time is up.
    for (Node& n : nodes)
      if (n.stopped_until && now >= *n.stopped_until) {
        if (!n.exit_status) kill(n.pid, SIGCONT);
        n.stopped_until.reset();
      }
    std::erase_if(garbage, [&](const Garbage& g) {
      if (now < g.close_at) return false;
      close(g.fd);
      return true;
    });
    // A killed node's new process (its old one is reaped here too).
    for (Node& n : nodes)
      if (const auto s = n.exit_status ? std::nullopt : zenith::core::wait_for_exit(n.pid, 0ms); s && *s >= 0) {
        if (*s == 128 + SIGKILL) {
          n.pid = zenith::core::spawn_process(opt.zenith, n.args, n.log, zenith::core::LogMode::append);
          ++n.restarts;
          n.restarted_at = now;
          n.last_before_restart = last_presented(presented_log(n));
        } else if (*s == 0 && read_text(n.log).find("the master said goodbye") != std::string::npos) {
          // The show's end: the node leaves at the master's Goodbye, which can be before the master
          // process itself exits (it lingers while its connections flush and close).
          n.exit_status = 0;
        } else {
          failure = fmt::format("node '{}' exited with status {} during the show (see {})", n.name, *s, n.log.string());
        }
      }
    if (!failure.empty()) break;
    for (Node& n : nodes)  // a restarted node is back once it presents a frame
      if (n.restarted_at && last_presented(presented_log(n)) > n.last_before_restart) {
        rejoin_s = std::max(rejoin_s, std::chrono::duration<double>(now - *n.restarted_at).count());
        n.restarted_at.reset();
      }
    attacks.poll();
    if (show_started && frame && *frame < quiet_from && now >= next_fault) {
      next_fault = now + std::chrono::milliseconds(static_cast<int>(1000 * uniform(opt.fault_min_s, opt.fault_max_s)));
      // A fault must be over (the node back) before the quiet part, at the nominal frame rate.
      const auto fits = [&](double seconds) {
        return static_cast<double>(*frame) + (seconds + 2.0) * opt.fps <= static_cast<double>(quiet_from);
      };
      // An attack's answers come within seconds (a stray node starts, connects and is refused).
      if (opt.attacks && uniform(0.0, 1.0) < 0.5) {
        if (fits(3.0)) {
          if (!first_attack_frame) first_attack_frame = *frame;
          attacks.launch(rng);
        }
        continue;
      }
      const double pick = uniform(0.0, 3.0);
      const std::size_t victim = static_cast<std::size_t>(uniform(0.0, static_cast<double>(opt.nodes) - 1e-9));
      Node& n = nodes[victim];
      if (n.exit_status) continue;  // the show is over for it
      if (pick < 1.0 && victim != 0 && !n.stopped_until && !n.restarted_at && fits(rejoin_s)) {
        kill(n.pid, SIGKILL);  // restarted above, at the next poll
        ++kills;
      } else if (pick < 2.0 && !n.stopped_until && !(opt.attacks && victim == 0)) {
        bool long_stop = uniform(0.0, 1.0) < opt.long_stop_probability;
        if (long_stop && !fits(13.0)) long_stop = false;
        const double seconds = long_stop ? uniform(10.5, 13.0) : uniform(0.3, 3.0);
        if (fits(seconds)) {
          kill(n.pid, SIGSTOP);
          n.stopped_until = now + std::chrono::milliseconds(static_cast<int>(seconds * 1000));
          ++(long_stop ? long_stops : short_stops);
        }
      } else {
        const int fd = zenith::core::connect_loopback(port);
        if (fd >= 0) {
          ++garbage_count;
          const double kind = uniform(0.0, 3.0);
          std::vector<std::uint8_t> bytes;
          if (kind < 1.0) {
            bytes.resize(static_cast<std::size_t>(uniform(1.0, 4096.0)));
            for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
          } else if (kind < 2.0) {
            // The magic, then a header whose length is far past any limit (and whose CRC is wrong).
            bytes = {'Z', 'N', 'T', 'H', 0, 1, 0, 1, 0x7F, 0xFF, 0xFF, 0xFF, 0, 0, 0, 0, 0, 0, 0, 0};
          }
          if (!bytes.empty()) (void)::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
          garbage.push_back({fd, now + std::chrono::milliseconds(static_cast<int>(1000 * uniform(0.5, 6.0)))});
        }
      }
    }
    if (now - last_report > 10s) {
      last_report = now;
      fmt::print("soak: frame {} of {}, {:.0f} s; faults so far: {} kills, {} short stops, {} long stops, {} garbage\n",
                 frame.value_or(0), opt.frames, std::chrono::duration<double>(now - started).count(), kills,
                 short_stops, long_stops, garbage_count);
      std::fflush(stdout);
    }
  }
  for (const Garbage& g : garbage) close(g.fd);
  for (Node& n : nodes)
    if (n.stopped_until && !n.exit_status) kill(n.pid, SIGCONT);
  attacks.finish();
  const double run_s = std::chrono::duration<double>(Clock::now() - started).count();
  if (!master_status) {
    kill(master, SIGKILL);
    zenith::core::wait_for_exit(master, 5000ms);
  } else if (*master_status != 0 && failure.empty()) {
    failure = fmt::format("the master exited with status {} (see {})", *master_status, (dir / "master.log").string());
  }
  std::vector<int> node_status;
  for (Node& n : nodes) {
    std::optional<int> s = n.exit_status ? n.exit_status : zenith::core::wait_for_exit(n.pid, 20000ms);
    if (!s || *s < 0) {
      kill(n.pid, SIGKILL);
      zenith::core::wait_for_exit(n.pid, 5000ms);
      s = -1;
    }
    node_status.push_back(*s);
    if (*s != 0 && failure.empty()) failure = fmt::format("node '{}' ended with status {}", n.name, *s);
  }

  // ---- the report ----
  fmt::print("\nsoak: {} frames at {} fps on {} nodes ({}x{} px each), seed {}, {:.0f} s\n", opt.frames, opt.fps,
             opt.nodes, opt.size_px, opt.size_px, opt.seed, run_s);
  fmt::print(
      "faults: {} kill -9 (and restart), {} short stops (0.3-3 s), {} long stops (10.5-13 s), {} garbage "
      "connections\n\n",
      kills, short_stops, long_stops, garbage_count);
  fmt::print("{:<6} {:>10} {:>14} {:>10} {:>11} {:>9} {:>11} {:>11} {:>7}\n", "node", "presented", "missed frames",
             "gap runs", "reconnects", "restarts", "RSS start", "RSS end", "exit");
  std::vector<std::map<std::uint64_t, std::string>> logs;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    logs.push_back(presented(presented_log(n)));
    const auto& p = logs.back();
    std::uint64_t missed = 0, runs = 0;
    if (!p.empty()) {
      std::uint64_t expect = p.begin()->first;
      for (const auto& [frame, digest] : p) {
        if (frame > expect) {
          missed += frame - expect;
          ++runs;
        }
        expect = frame + 1;
      }
    }
    const std::size_t reconnects = count_of(read_text(n.log), "welcomed again by the master");
    const auto mib = [](const std::optional<double>& v) {
      return v ? fmt::format("{:.1f} MiB", *v) : std::string("-");
    };
    fmt::print("{:<6} {:>10} {:>14} {:>10} {:>11} {:>9} {:>11} {:>11} {:>7}\n", n.name, p.size(), missed, runs,
               reconnects, n.restarts, mib(n.rss_start), mib(n.rss_end), node_status[i]);
    if ((p.empty() || p.rbegin()->first + 1 != static_cast<std::uint64_t>(opt.frames)) && failure.empty())
      failure = fmt::format("node '{}' did not present the last frame ({})", n.name, opt.frames - 1);
  }
  std::size_t differing = 0;
  for (const auto& [frame, digest] : logs[0])
    for (std::size_t i = 1; i < logs.size(); ++i)
      if (const auto it = logs[i].find(frame); it != logs[i].end() && it->second != digest) ++differing;
  fmt::print("\nframes whose state differs between nodes: {}\n", differing);
  if (differing && failure.empty()) failure = fmt::format("{} frames differ between nodes", differing);
  const auto growth = [](const std::optional<double>& a, const std::optional<double>& b) {
    return a && b ? *b - *a : 0.0;
  };
  const double master_growth = growth(master_rss_start, master_rss_end);
  const double node_growth = growth(nodes[0].rss_start, nodes[0].rss_end);
  fmt::print("master RSS: {:.1f} MiB at the start, {:.1f} MiB at the end ({:+.1f} MiB; bound {:.0f} MiB)\n",
             master_rss_start.value_or(0), master_rss_end.value_or(0), master_growth, opt.max_rss_growth_mib);
  fmt::print(
      "node {} (never killed) RSS: {:.1f} MiB at the start, {:.1f} MiB at the end ({:+.1f} MiB; bound {:.0f} MiB)\n",
      nodes[0].name, nodes[0].rss_start.value_or(0), nodes[0].rss_end.value_or(0), node_growth, opt.max_rss_growth_mib);
  if (failure.empty() && (!master_rss_start || !nodes[0].rss_start)) failure = "the show never started";
  if (failure.empty() && master_growth > opt.max_rss_growth_mib) failure = "the master's memory grew past the bound";
  if (failure.empty() && node_growth > opt.max_rss_growth_mib) failure = "the node's memory grew past the bound";
  if (opt.attacks) {
    fmt::print("\nattacks ({} in all, from frame {}):\n", attacks.launched(),
               first_attack_frame ? std::to_string(*first_attack_frame) : std::string("-"));
    for (const std::string& line : attacks.report()) fmt::print("  {}\n", line);
    for (const std::string& f : attacks.failures()) {
      fmt::print("  FAILED: {}\n", f);
      if (failure.empty()) failure = f;
    }
    // Node 0 is never stopped or killed with --attacks: no attack may cost it a frame.
    std::uint64_t gaps = 0;
    if (first_attack_frame)
      for (std::uint64_t f = *first_attack_frame; f < static_cast<std::uint64_t>(opt.frames); ++f)
        gaps += logs[0].count(f) ? 0 : 1;
    fmt::print("node {} frames missing from frame {} (the first attack) to the last: {}\n", nodes[0].name,
               first_attack_frame.value_or(0), gaps);
    if (gaps && failure.empty())
      failure = fmt::format("node {} missed {} frames during the attacks", nodes[0].name, gaps);
    const std::string master_log = read_text(dir / "master.log");
    fmt::print("master log: {} lines, {:.1f} KiB; forged lines: {}\n", count_of(master_log, "\n"),
               static_cast<double>(master_log.size()) / 1024.0, count_of(master_log, "\nmaster: quit"));
    if (count_of(master_log, "\nmaster: quit") && failure.empty()) failure = "an OSC address forged a log line";
    const std::string orphans = launcher_orphans(opt, config, cache, dir, port + 4);
    fmt::print("launcher killed with kill -9: {}\n", orphans.empty() ? "no orphan" : orphans);
    if (!orphans.empty() && failure.empty()) failure = orphans;
  }
  if (!opt.keep)  // the frames: tens of thousands of tiny files; presented.log stays
    for (const Node& n : nodes)
      if (fs::is_directory(dir / "out" / n.name))
        for (const auto& entry : fs::directory_iterator(dir / "out" / n.name))
          if (entry.is_directory()) fs::remove_all(entry.path());
  fmt::print("logs: {}\n", dir.string());
  if (!failure.empty()) {
    fmt::print("soak FAILED: {}\n", failure);
    return 1;
  }
  fmt::print("soak passed\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  try {
    opt = parse_options(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "cluster_soak: {}\n{}", e.what(), kUsage);
    return 2;
  }
  try {
    return run(opt);
  } catch (const std::exception& e) {
    fmt::print(stderr, "cluster_soak: {}\n", e.what());
    return 1;
  }
}
