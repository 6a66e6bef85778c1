// Cluster benchmark: what the frame barrier and the table broadcast cost when
// the network path dominates (docs/cluster-performance.md).
//
// Every run is a real cluster: one `zenith master` and N `zenith node`
// processes on 127.0.0.1, started with the same command lines as the cluster
// tests (tests/cluster/cluster_process_test.cpp), in a fresh folder holding a
// viewport config of N tiny outputs (--size, 16×16 by default; fisheye 180°)
// and a cluster config giving each node one output. The master's table cache
// (--cache) is shared by every run, so the tables are precomputed once; every
// node starts with an empty cache of its own, so every run transfers them.
//
// Part 1, the barrier: for N in --nodes (1, 2, 4, 8) the show runs --frames
// frames unpaced (`zenith master --unpaced`: the master starts a frame as
// soon as the last one is presented) with --frame-tables tables. Per frame:
//
//   period       the time between the master's "present frame K" log lines
//                (spdlog stamps, 1 ms resolution; the mean over the frames is
//                (t_last − t_first) / (frames − 1), exact to 1 ms / frames)
//   barrier      the master's own figure in that line: FrameState sent → the
//                last RenderDone received (0.1 ms, steady clock)
//   slowest      the largest render_ms the nodes reported for the frame (their
//                debug line "frame K rendered in X ms", the value RenderDone
//                carries: from FrameState decoded to PNG written)
//
// and the figures: fps = 1000 / mean period; barrier overhead per frame =
// mean period − mean slowest render (everything the cluster adds on top of
// the slowest node's rendering: messages, decoding, scheduling, presenting,
// the master's loop); of which in-barrier = barrier − slowest (FrameState out
// and RenderDone back). Frame 0 is left out (first-use costs).
//
// Part 2, the table broadcast: for each size set in --tables (small, paper,
// large) and N in --broadcast-nodes (1, 4), a show of 2 frames; from the
// master's log, the first "authenticated … sending N table sets" (the
// TableAnnounce and chunks follow it at once) to the last "is ready" (the
// node's TableReady arrived); split into transfer (to the last node's "tables
// … received" line: bytes on the wire, SHA-256 check, cache write) and the rest
// (the node loads the tables and renders once before TableReady).
//
// Part 3, a paced dome (docs/cluster.md, "Pacing, swap groups and late
// frames"): --pacing-nodes nodes (4) of one --pacing-size output each, paced
// at --pacing-hz (60) for --pacing-frames frames, a live show (no frame
// files), the nodes in windows with --pacing-windows (needs a display). From
// the master's log: the frame time (FrameState out → Present out, its own
// steady-clock figure) and the interval between Presents (log stamps, 1 ms)
// as percentiles; the frames presented more than a period after they were due
// (the master's "pacing at … Hz" line: each one a frame shown twice); with
// windows, every node's late presents (missed vblanks). Written to
// --pacing-csv, one row per run.
//
// Output: the tables on stdout and CSV (--csv), one row per run:
//
//   part, nodes, tables, table_bytes, frames, fps, period_ms, slowest_render_ms,
//   overhead_ms, barrier_ms, in_barrier_ms, in_barrier_p90_ms, broadcast_s,
//   transfer_s, warmup_ms_max, mb_per_s
//
// (figures a part does not measure are empty).
//
//   cluster_bench [--zenith PATH] [--nodes 1,2,4,8] [--frames 300] [--size 16]
//                 [--frame-tables small] [--tables small,paper,large]
//                 [--broadcast-nodes 1,4] [--orders 1] [--cache DIR] [--work DIR]
//                 [--csv FILE] [--timeout-s 600] [--keep]
//                 [--pacing-nodes 4] [--pacing-hz 60] [--pacing-size 32] [--pacing-frames 600]
//                 [--pacing-windows] [--pacing-csv FILE]
#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/command_line.h"
#include "bench/tiny_cluster.h"
#include "core/files.h"
#include "core/process.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr const char* kSecretVar = "ZENITH_CLUSTER_BENCH_SECRET";

constexpr const char* kUsage = R"(cluster_bench: barrier overhead and frames per second of a local cluster, and
table broadcast time per size (docs/cluster-performance.md)

  --zenith PATH            the zenith binary (default: this build's)
  --nodes LIST             node counts of the barrier runs (default 1,2,4,8; "none": skip)
  --frames N               frames per barrier run (default 300)
  --size PX                each output is PX×PX (default 16)
  --frame-tables SIZE      table sizes of the barrier runs (default small)
  --tables LIST            table sizes of the broadcast runs (default small,paper,large; "none": skip)
  --broadcast-nodes LIST   node counts of the broadcast runs (default 1,4)
  --orders N               scattering orders of the tables (default 1)
  --cache DIR              the master's table cache (default WORK/table-cache)
  --work DIR               run folders, logs (default $TMPDIR/zenith-cluster-bench)
  --csv FILE               results (default bench/results/cluster_bench.csv)
  --timeout-s S            per run (default 600)
  --keep                   keep the run folders (logs, frames)
  --pacing-nodes N         nodes of the paced dome (default 4; 0 skips it)
  --pacing-hz R            its frame rate (default 60)
  --pacing-size PX         each of its outputs is PX×PX (default 32)
  --pacing-frames N        its frames (default 600)
  --pacing-windows         its nodes present in windows (needs DISPLAY; late presents counted)
  --pacing-csv FILE        its results (default bench/results/dome_pacing.csv)
)";

struct Options : zenith::bench::TinyRunOptions {
  std::vector<int> nodes = {1, 2, 4, 8};
  int frames = 300;
  std::string frame_tables = "small";
  std::vector<std::string> tables = {"small", "paper", "large"};
  std::vector<int> broadcast_nodes = {1, 4};
  int orders = 1;
  fs::path csv = fs::path(ZENITH_SOURCE_DIR) / "bench/results/cluster_bench.csv";
  int pacing_nodes = 4;
  double pacing_hz = 60.0;
  int pacing_size = 32;
  int pacing_frames = 600;
  bool pacing_windows = false;
  fs::path pacing_csv = fs::path(ZENITH_SOURCE_DIR) / "bench/results/dome_pacing.csv";
};

Options parse_options(int argc, char** argv) {
  Options o;
  o.zenith = ZENITH_BINARY;
  o.work = fs::temp_directory_path() / "zenith-cluster-bench";
  o.timeout_s = 600;
  for (zenith::bench::CommandLine args(argc, argv); args.next();) {
    const std::string& a = args.option();
    if (o.read(args, kUsage)) continue;
    if (a == "--nodes") {
      const std::string v = args.value();
      o.nodes = v == "none" ? std::vector<int>{} : zenith::bench::split_int_list(v);
    } else if (a == "--frames")
      o.frames = std::stoi(args.value());
    else if (a == "--frame-tables")
      o.frame_tables = args.value();
    else if (a == "--tables") {
      o.tables = zenith::bench::split_list(args.value());
      if (o.tables == std::vector<std::string>{"none"}) o.tables.clear();
    } else if (a == "--broadcast-nodes")
      o.broadcast_nodes = zenith::bench::split_int_list(args.value());
    else if (a == "--orders")
      o.orders = std::stoi(args.value());
    else if (a == "--csv")
      o.csv = args.value();
    else if (a == "--pacing-nodes")
      o.pacing_nodes = std::stoi(args.value());
    else if (a == "--pacing-hz")
      o.pacing_hz = std::stod(args.value());
    else if (a == "--pacing-size")
      o.pacing_size = std::stoi(args.value());
    else if (a == "--pacing-frames")
      o.pacing_frames = std::stoi(args.value());
    else if (a == "--pacing-windows")
      o.pacing_windows = true;
    else if (a == "--pacing-csv")
      o.pacing_csv = args.value();
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (o.frames < 3) throw std::invalid_argument("--frames must be at least 3");
  if (o.size_px < 1) throw std::invalid_argument("--size must be positive");
  for (int n : o.nodes)
    if (n < 1) throw std::invalid_argument("--nodes: counts must be positive");
  return o;
}

// ---- processes (as the cluster tests start them) -----------------------------

struct Child {
  pid_t pid = -1;
  fs::path log;
};

Child spawn(const fs::path& binary, const std::vector<std::string>& args, const fs::path& log) {
  return Child{zenith::core::spawn_process(binary, args, log, zenith::core::LogMode::truncate), log};
}

/// The exit status (128 + signal when killed), or nullopt when `deadline` passes.
std::optional<int> wait_exit(const Child& c, Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  const std::optional<int> status = zenith::core::wait_for_exit(c.pid, std::max(left, std::chrono::milliseconds(0)));
  if (status && *status < 0) return std::nullopt;
  return status;
}

void kill_hard(const Child& c) {
  kill(c.pid, SIGKILL);
  wait_exit(c, Clock::now() + 5s);
}

// ---- logs ---------------------------------------------------------------------

/// One spdlog line: "[2025-01-02 03:04:05.678] [zenith] [info] text", its stamp in ms.
struct LogLine {
  double t_ms;
  std::string text;
};

std::vector<LogLine> read_log(const fs::path& path) {
  std::vector<LogLine> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::tm tm{};
    int ms = 0;
    if (std::sscanf(line.c_str(), "[%d-%d-%d %d:%d:%d.%d]", &tm.tm_year, &tm.tm_mon, &tm.tm_mday, &tm.tm_hour,
                    &tm.tm_min, &tm.tm_sec, &ms) != 7)
      continue;
    tm.tm_year -= 1900;
    tm.tm_mon -= 1;
    const double t = static_cast<double>(timegm(&tm)) * 1000.0 + ms;
    // Skip the bracketed fields (stamp, logger name, level) before the message.
    std::size_t text_at = 0;
    while (text_at < line.size() && line[text_at] == '[') {
      const auto close = line.find("] ", text_at);
      if (close == std::string::npos) break;
      text_at = close + 2;
    }
    out.push_back({t, line.substr(text_at)});
  }
  return out;
}

/// The number right after `key` in `text`, if `key` occurs.
std::optional<double> number_after(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  if (at == std::string::npos) return std::nullopt;
  return std::strtod(text.c_str() + at + key.size(), nullptr);
}

using zenith::core::read_text;

// ---- one run --------------------------------------------------------------------

struct RunSetup {
  int nodes = 1;
  int frames = 3;
  std::string tables = "small";
  double paced_hz = 0.0;  ///< > 0: a paced live show at this rate (no frame files); 0: unpaced, frames written
  int size_px = 0;        ///< 0: --size
  bool windows = false;   ///< the nodes present in windows
};

/// What the logs of one run say.
struct RunLogs {
  std::vector<LogLine> master;
  std::map<std::string, std::vector<LogLine>> nodes;  ///< by node name
  double run_s = 0;
};

using zenith::bench::tiny_node_name;

/// Writes the configs, runs master + nodes to the end of the show, returns the logs.
RunLogs run_cluster(const Options& opt, const RunSetup& setup, const fs::path& cache, int port) {
  const fs::path dir = opt.work / fmt::format("{}-nodes{}-{}f{}", setup.tables, setup.nodes, setup.frames,
                                              setup.paced_hz > 0 ? fmt::format("-{}hz", setup.paced_hz) : "");
  const bool paced = setup.paced_hz > 0;
  fs::remove_all(dir);
  fs::create_directories(dir);

  // N tiny fisheye outputs, one per node.
  port = zenith::core::free_loopback_port(port);  // other runs share the machine
  const fs::path config = zenith::bench::write_tiny_cluster(
      dir, {"bench", setup.nodes, setup.size_px > 0 ? setup.size_px : opt.size_px, port,
            // The barrier (lookahead 0) is what this benchmark measures; scheduled
            // frames are cluster_rig_bench's.
            fmt::format(
                R"({{"heartbeat_ms": 250, "barrier_timeout_ms": 60000, "frame_rate_hz": {}, "lookahead_frames": 0}})",
                paced ? setup.paced_hz : 240.0),
            kSecretVar, setup.tables, opt.orders});
  std::vector<Child> children;
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::seconds(opt.timeout_s);
  std::vector<std::string> master_args = {"--log-level",
                                          "debug",
                                          "master",
                                          "--cluster",
                                          config.string(),
                                          "--frames",
                                          std::to_string(setup.frames),
                                          "--cache",
                                          cache.string(),
                                          "--wait-for-nodes-ms",
                                          std::to_string(opt.timeout_s * 1000)};
  if (!paced) master_args.insert(master_args.begin() + 3, "--unpaced");
  children.push_back(spawn(opt.zenith, master_args, dir / "master.log"));
  for (int i = 0; i < setup.nodes; ++i) {
    std::vector<std::string> args = {"--log-level",
                                     "debug",
                                     "node",
                                     "--cluster",
                                     config.string(),
                                     "--name",
                                     tiny_node_name(i),
                                     "--cache",
                                     (dir / "node-cache" / tiny_node_name(i)).string(),
                                     "--connect-timeout-ms",
                                     std::to_string(opt.timeout_s * 1000)};
    if (!paced) args.insert(args.end(), {"--out", (dir / "out").string()});  // a live show writes no frames
    if (setup.windows) args.push_back("--window");
    children.push_back(spawn(opt.zenith, args, dir / (tiny_node_name(i) + ".log")));
  }

  std::string failure;
  for (std::size_t i = 0; i < children.size(); ++i) {
    const auto status = wait_exit(children[i], deadline);
    if (!status)
      failure += fmt::format(" {} did not finish within {} s;", children[i].log.stem().string(), opt.timeout_s);
    else if (*status != 0)
      failure += fmt::format(" {} exited with {};", children[i].log.stem().string(), *status);
  }
  for (const Child& c : children)
    if (kill(c.pid, 0) == 0) kill_hard(c);
  if (!failure.empty())
    throw std::runtime_error(
        fmt::format("run {}:{}\n---- master.log\n{}", dir.string(), failure, read_text(dir / "master.log")));

  RunLogs logs;
  logs.run_s = std::chrono::duration<double>(Clock::now() - start).count();
  logs.master = read_log(dir / "master.log");
  for (int i = 0; i < setup.nodes; ++i) logs.nodes[tiny_node_name(i)] = read_log(dir / (tiny_node_name(i) + ".log"));
  if (!opt.keep) fs::remove_all(dir);
  return logs;
}

// ---- figures ------------------------------------------------------------------

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

struct BarrierResult {
  int nodes = 0, frames = 0;
  double fps = 0, period_ms = 0, slowest_ms = 0, overhead_ms = 0, barrier_ms = 0, in_barrier_ms = 0,
         in_barrier_p90_ms = 0;
};

BarrierResult barrier_figures(const RunSetup& setup, const RunLogs& logs) {
  std::map<std::uint64_t, double> presented_at, barrier;  // by frame
  for (const LogLine& l : logs.master) {
    if (l.text.rfind("master: present frame ", 0) != 0) continue;
    const auto frame = static_cast<std::uint64_t>(*number_after(l.text, "present frame "));
    presented_at[frame] = l.t_ms;
    barrier[frame] = number_after(l.text, " (").value_or(0.0);
  }
  std::map<std::uint64_t, double> slowest;
  for (const auto& [name, lines] : logs.nodes)
    for (const LogLine& l : lines) {
      const auto at = l.text.find("': frame ");
      if (at == std::string::npos || l.text.find(" rendered in ") == std::string::npos) continue;
      const auto frame = static_cast<std::uint64_t>(std::strtod(l.text.c_str() + at + 9, nullptr));
      double& s = slowest[frame];
      s = std::max(s, *number_after(l.text, " rendered in "));
    }
  if (presented_at.size() != static_cast<std::size_t>(setup.frames))
    throw std::runtime_error(
        fmt::format("{} nodes: the master presented {} of {} frames", setup.nodes, presented_at.size(), setup.frames));
  // Frame 0 is left out: the first frame after the warm-up pays first-use costs.
  std::vector<double> slow, barr, in_barrier;
  for (const auto& [frame, b] : barrier) {
    if (frame == 0) continue;
    const double s = slowest.count(frame) ? slowest[frame] : 0.0;
    slow.push_back(s);
    barr.push_back(b);
    in_barrier.push_back(b - s);
  }
  BarrierResult r;
  r.nodes = setup.nodes;
  r.frames = setup.frames;
  const double first = presented_at.at(1), last = presented_at.rbegin()->second;
  r.period_ms = (last - first) / static_cast<double>(presented_at.size() - 2);
  r.fps = r.period_ms > 0 ? 1000.0 / r.period_ms : 0.0;
  // The period of frames 2..F-1 is measured between presents of frames 1..F-1:
  // it spans the renders of frames 2..F-1, so compare with those.
  std::vector<double> slow_spanned(slow.begin() + 1, slow.end());
  r.slowest_ms = mean(slow_spanned);
  r.overhead_ms = r.period_ms - r.slowest_ms;
  r.barrier_ms = mean(barr);
  r.in_barrier_ms = quantile(in_barrier, 0.5);
  r.in_barrier_p90_ms = quantile(in_barrier, 0.9);
  return r;
}

struct BroadcastResult {
  int nodes = 0;
  std::string tables;
  double bytes = 0, broadcast_s = 0, transfer_s = 0, warmup_ms_max = 0;
};

BroadcastResult broadcast_figures(const RunSetup& setup, const RunLogs& logs) {
  BroadcastResult r;
  r.nodes = setup.nodes;
  r.tables = setup.tables;
  std::optional<double> first_announce, last_ready, last_received;
  for (const LogLine& l : logs.master) {
    if (l.text.find("ready to share: ") != std::string::npos) r.bytes += number_after(l.text, " (").value_or(0.0);
    if (l.text.find("' authenticated from ") != std::string::npos)
      first_announce = std::min(first_announce.value_or(l.t_ms), l.t_ms);
    if (l.text.find("' is ready: ") != std::string::npos) last_ready = std::max(last_ready.value_or(l.t_ms), l.t_ms);
  }
  for (const auto& [name, lines] : logs.nodes)
    for (const LogLine& l : lines) {
      if (l.text.find(" received (") != std::string::npos && l.text.find("tables of '") != std::string::npos)
        last_received = std::max(last_received.value_or(l.t_ms), l.t_ms);
      if (const auto w = number_after(l.text, "tables loaded and shaders ready ("))
        r.warmup_ms_max = std::max(r.warmup_ms_max, *w);
    }
  if (!first_announce || !last_ready || !last_received)
    throw std::runtime_error(
        fmt::format("{} tables, {} nodes: the logs lack the table lines", setup.tables, setup.nodes));
  r.broadcast_s = (*last_ready - *first_announce) / 1000.0;
  r.transfer_s = (*last_received - *first_announce) / 1000.0;
  return r;
}

struct PacingResult {
  int nodes = 0, frames = 0, size_px = 0;
  double hz = 0;
  double frame_p50_ms = 0, frame_p90_ms = 0, frame_p99_ms = 0, frame_max_ms = 0;
  double interval_p50_ms = 0, interval_p99_ms = 0, interval_max_ms = 0;
  int late_frames = 0, slips = 0;
  std::optional<int> late_presents;  ///< with windows: the nodes' missed vblanks, summed
};

PacingResult pacing_figures(const RunSetup& setup, int size_px, const RunLogs& logs) {
  PacingResult r;
  r.nodes = setup.nodes;
  r.frames = setup.frames;
  r.size_px = size_px;
  r.hz = setup.paced_hz;
  std::vector<double> frame_ms, interval_ms;
  std::optional<double> previous;
  bool pacing_line = false;
  for (const LogLine& l : logs.master) {
    if (l.text.rfind("master: present frame ", 0) == 0) {
      frame_ms.push_back(number_after(l.text, " (").value_or(0.0));
      if (previous) interval_ms.push_back(l.t_ms - *previous);
      previous = l.t_ms;
    } else if (l.text.rfind("master: pacing at ", 0) == 0) {
      pacing_line = true;
      r.late_frames = static_cast<int>(number_after(l.text, " frames presented, ").value_or(-1));
      r.slips = static_cast<int>(number_after(l.text, " the schedule moved ").value_or(-1));
    }
  }
  if (frame_ms.size() != static_cast<std::size_t>(setup.frames) || !pacing_line)
    throw std::runtime_error(fmt::format("paced run: the master presented {} of {} frames{}", frame_ms.size(),
                                         setup.frames, pacing_line ? "" : " and logged no pacing line"));
  r.frame_p50_ms = quantile(frame_ms, 0.5);
  r.frame_p90_ms = quantile(frame_ms, 0.9);
  r.frame_p99_ms = quantile(frame_ms, 0.99);
  r.frame_max_ms = quantile(frame_ms, 1.0);
  r.interval_p50_ms = quantile(interval_ms, 0.5);
  r.interval_p99_ms = quantile(interval_ms, 0.99);
  r.interval_max_ms = quantile(interval_ms, 1.0);
  if (setup.windows)
    for (const auto& [name, lines] : logs.nodes)
      for (const LogLine& l : lines)
        if (const auto late = number_after(l.text, " frames in its windows, "))
          r.late_presents = r.late_presents.value_or(0) + static_cast<int>(*late);
  return r;
}

std::string cpu_name() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

int run(int argc, char** argv) {
  const Options opt = parse_options(argc, argv);
  if (!fs::exists(opt.zenith)) throw std::runtime_error("no zenith binary at " + opt.zenith.string() + " (--zenith)");
  setenv(kSecretVar, "cluster-bench-secret-0123456789abcdef", 1);
  fs::create_directories(opt.work);
  const fs::path cache = opt.cache.value_or(opt.work / "table-cache");
  fs::create_directories(cache);
  int port = static_cast<int>(20000 + (getpid() * 13) % 25000);

  fmt::print("cluster_bench: {} ({} hardware threads), zenith {}\n", cpu_name(), std::thread::hardware_concurrency(),
             opt.zenith.string());
  fmt::print("outputs {}x{} px, one per node, all on 127.0.0.1; table orders {}; master cache {}\n", opt.size_px,
             opt.size_px, opt.orders, cache.string());

  // Precompute (or load) every table size once, so that no timed run pays it.
  std::vector<std::string> sizes = opt.tables;
  if (std::find(sizes.begin(), sizes.end(), opt.frame_tables) == sizes.end()) sizes.push_back(opt.frame_tables);
  for (const std::string& s : sizes) {
    const auto t0 = Clock::now();
    run_cluster(opt, {1, 3, s}, cache, port++);
    fmt::print("tables '{}' ready in the master's cache ({:.1f} s incl. a 3-frame show)\n", s,
               std::chrono::duration<double>(Clock::now() - t0).count());
  }

  std::vector<BarrierResult> barriers;
  fmt::print("\nbarrier: {} frames, {} tables, unpaced; frame 0 left out\n", opt.frames, opt.frame_tables);
  fmt::print("{:>5} {:>8} {:>10} {:>12} {:>11} {:>10} {:>11} {:>9}\n", "nodes", "fps", "period ms", "slowest ms",
             "overhead", "barrier", "in-barrier", "p90");
  for (int n : opt.nodes) {
    const RunSetup setup{n, opt.frames, opt.frame_tables};
    const BarrierResult r = barrier_figures(setup, run_cluster(opt, setup, cache, port++));
    fmt::print("{:>5} {:>8.1f} {:>10.2f} {:>12.2f} {:>11.2f} {:>10.2f} {:>11.2f} {:>9.2f}\n", r.nodes, r.fps,
               r.period_ms, r.slowest_ms, r.overhead_ms, r.barrier_ms, r.in_barrier_ms, r.in_barrier_p90_ms);
    barriers.push_back(r);
  }

  std::vector<BroadcastResult> broadcasts;
  if (!opt.tables.empty()) {
    fmt::print("\ntable broadcast: first TableAnnounce -> last TableReady\n");
    fmt::print("{:>7} {:>5} {:>10} {:>12} {:>11} {:>10} {:>11}\n", "tables", "nodes", "MB", "broadcast s", "transfer s",
               "MB/s", "warmup ms");
  }
  for (const std::string& t : opt.tables)
    for (int n : opt.broadcast_nodes) {
      const RunSetup setup{n, 2, t};
      const BroadcastResult r = broadcast_figures(setup, run_cluster(opt, setup, cache, port++));
      const double mb = r.bytes / 1e6;
      fmt::print("{:>7} {:>5} {:>10.2f} {:>12.3f} {:>11.3f} {:>10.1f} {:>11.0f}\n", r.tables, r.nodes, mb,
                 r.broadcast_s, r.transfer_s, r.transfer_s > 0 ? mb * n / r.transfer_s : 0.0, r.warmup_ms_max);
      broadcasts.push_back(r);
    }

  std::optional<PacingResult> pacing;
  if (opt.pacing_nodes > 0) {
    const RunSetup setup{opt.pacing_nodes, opt.pacing_frames, opt.frame_tables,
                         opt.pacing_hz,    opt.pacing_size,   opt.pacing_windows};
    fmt::print("\npaced dome: {} nodes of one {}x{} output each at {} Hz, {} frames, {} tables, a live show{}\n",
               setup.nodes, opt.pacing_size, opt.pacing_size, opt.pacing_hz, setup.frames, opt.frame_tables,
               setup.windows ? ", in windows" : " (headless)");
    pacing = pacing_figures(setup, opt.pacing_size, run_cluster(opt, setup, cache, port++));
    const PacingResult& r = *pacing;
    fmt::print(
        "frame time (FrameState -> Present) ms: p50 {:.2f}  p90 {:.2f}  p99 {:.2f}  max {:.2f}  (period {:.2f})\n",
        r.frame_p50_ms, r.frame_p90_ms, r.frame_p99_ms, r.frame_max_ms, 1000.0 / r.hz);
    fmt::print("interval between Presents ms: p50 {:.0f}  p99 {:.0f}  max {:.0f}  (1 ms log stamps)\n",
               r.interval_p50_ms, r.interval_p99_ms, r.interval_max_ms);
    fmt::print("late frames (presented more than a period after due): {} of {}; schedule moved {} times{}\n",
               r.late_frames, r.frames, r.slips,
               r.late_presents ? fmt::format("; late presents on the nodes (missed vblanks): {}", *r.late_presents)
                               : std::string());
    if (opt.pacing_csv.has_parent_path()) fs::create_directories(opt.pacing_csv.parent_path());
    std::ofstream pcsv(opt.pacing_csv);
    pcsv << "nodes,size_px,hz,frames,windows,frame_p50_ms,frame_p90_ms,frame_p99_ms,frame_max_ms,interval_p50_ms,"
            "interval_p99_ms,interval_max_ms,late_frames,schedule_slips,late_presents\n";
    pcsv << fmt::format("{},{},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.0f},{:.0f},{:.0f},{},{},{}\n", r.nodes,
                        r.size_px, r.hz, r.frames, setup.windows ? 1 : 0, r.frame_p50_ms, r.frame_p90_ms,
                        r.frame_p99_ms, r.frame_max_ms, r.interval_p50_ms, r.interval_p99_ms, r.interval_max_ms,
                        r.late_frames, r.slips, r.late_presents ? std::to_string(*r.late_presents) : std::string());
    fmt::print("pacing csv: {}\n", opt.pacing_csv.string());
  }

  if (opt.csv.has_parent_path()) fs::create_directories(opt.csv.parent_path());
  std::ofstream csv(opt.csv);
  csv << "part,nodes,tables,table_bytes,frames,fps,period_ms,slowest_render_ms,overhead_ms,barrier_ms,in_barrier_ms,"
         "in_barrier_p90_ms,broadcast_s,transfer_s,warmup_ms_max,mb_per_s\n";
  for (const BarrierResult& r : barriers)
    csv << fmt::format("barrier,{},{},,{},{:.2f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},,,,\n", r.nodes,
                       opt.frame_tables, r.frames, r.fps, r.period_ms, r.slowest_ms, r.overhead_ms, r.barrier_ms,
                       r.in_barrier_ms, r.in_barrier_p90_ms);
  for (const BroadcastResult& r : broadcasts)
    csv << fmt::format("broadcast,{},{},{:.0f},2,,,,,,,,{:.3f},{:.3f},{:.0f},{:.1f}\n", r.nodes, r.tables, r.bytes,
                       r.broadcast_s, r.transfer_s, r.warmup_ms_max,
                       r.transfer_s > 0 ? r.bytes / 1e6 * r.nodes / r.transfer_s : 0.0);
  fmt::print("\ncsv: {}\n", opt.csv.string());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return zenith::bench::main_reporting_errors("cluster_bench", argc, argv, run); }
