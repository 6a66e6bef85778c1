// The cluster across a real network, measured (docs/cluster.md, "Measured on
// the rig"): a master and --nodes nodes, each host in its own network
// namespace on a bridge (tests/rig/network_rig.h), paced at --hz for
// --frames frames, one node's link ("n1") impaired in each case:
//
//   none          no impairment
//   loss1, loss5  1 % / 5 % of its packets dropped, each way (nftables)
//   partition2s   its link cut for 2 s, one second into the show
//   latency5      5 ms ± 1 ms each way on every node's link (the delaying
//                 relay, tests/rig/delay_relay.cpp: the kernel has no netem)
//   clockstep     n1's clock runs 300 ppm fast and jumps 20 ms ahead, then
//                 back, every 2 s (`zenith node --debug-clock-*`: only as its
//                 clock synchronisation reads it): "clock ms" shows a jump
//                 until it is seen, "clock p50" the rest, "apart" how many
//                 frames the nodes' moments were more than 2 ms apart
//   join1g, join100m   n1 joins mid-show (started once the others are warmed
//                 up) over a link of 1 Gbit/s / 100 Mbit/s toward it (tc
//                 tbf): the tables it lacks travel while the others play;
//                 table_mb and table_s are the master's log of its join
//                 (sent, received and loaded); its own rows count the
//                 frames before it joined as missing
//
// each with the frame barrier (timing.lookahead_frames 0, what zenith did
// before) and the frame schedule (--lookahead frames). The impairment starts
// once the nodes are warmed up (frame 0 presented). From every node's
// presents.csv (CLOCK_MONOTONIC, the same clock in every namespace):
//
//   presented     frames 1 … frames − 1 the node presented, of those expected
//   missing       frames it never presented
//   in_order      whether its frame numbers only grew
//   longest_ms    the longest interval between two of its presents
//   over_2T       intervals longer than two frame periods (a frame held
//                 twice or more: what the projector's audience sees)
//   over_100ms    intervals longer than 100 ms (a visible freeze)
//   latest_ms     the latest present after its scheduled moment (scheduled only)
//
// and per case the spread of the nodes' present times for one frame (max −
// min over the nodes, for the frames every node presented): its largest,
// 99th percentile and median, and the frames over 1 ms apart; and, scheduled, the spread of the moments the nodes had
// for one frame — on one machine all share CLOCK_MONOTONIC, so that is the
// clock synchronisation's error alone (the present spread adds how promptly
// each node's render thread got a core). Needs root (network namespaces).
//
//   cluster_rig_bench [--zenith PATH] [--nodes 4] [--hz 60] [--frames 600] [--lookahead 3]
//                     [--present-priority realtime|normal]
//                     [--cases none,loss1,loss5,partition2s,latency5,clockstep,join1g,join100m]
//                     [--schedules barrier,scheduled] [--size 32] [--tables small]
//                     [--scene configs/scenes/earth-sunset.json] [--work DIR] [--cache DIR]
//                     [--csv bench/results/cluster_rig.csv]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/command_line.h"
#include "tests/rig/network_rig.h"
#include "tests/rig/rig_cluster.h"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using zenith::testing::NetworkRig;
using zenith::testing::NodeTimeline;
using zenith::testing::RigCluster;
using zenith::testing::RigClusterSetup;

constexpr const char* kUsage = R"(cluster_rig_bench: the cluster across network namespaces, one link impaired
(docs/cluster.md, "Measured on the rig"); needs root

  --zenith PATH        the zenith binary (default: this build's)
  --nodes N            render nodes (default 4)
  --hz R               frame rate (default 60)
  --frames N           frames per run, the warm-up frame 0 included (default 600)
  --lookahead N        the schedule's lookahead in frames (default 3)
  --present-priority P timing.present_priority: realtime or normal (default: not written, realtime)
  --cases LIST         none, loss1, loss5, partition2s, latency5, clockstep, join1g, join100m
                       (default: the first four)
  --schedules LIST     barrier, scheduled (default both)
  --size PX            each node's output is PX×PX (default 32)
  --tables SIZE        table sizes (default small)
  --scene FILE         the scene (default configs/scenes/earth-sunset.json; three-worlds.json: three atmospheres)
  --work DIR           run folders (default $TMPDIR/zenith-cluster-rig-bench)
  --cache DIR          the master's table cache (default WORK/table-cache)
  --csv FILE           results (default bench/results/cluster_rig.csv)
)";

struct Options {
  fs::path zenith = ZENITH_BINARY;
  int nodes = 4;
  double hz = 60.0;
  std::uint64_t frames = 600;
  int lookahead = 3;
  std::string present_priority;  ///< empty: the key not written (the config's default; older builds lack it)
  std::vector<std::string> cases = {"none", "loss1", "loss5", "partition2s"};
  std::vector<std::string> schedules = {"barrier", "scheduled"};
  int size_px = 32;
  std::string tables = "small";
  fs::path scene = fs::path(ZENITH_SOURCE_DIR) / "configs/scenes/earth-sunset.json";
  fs::path work = fs::temp_directory_path() / "zenith-cluster-rig-bench";
  std::optional<fs::path> cache;
  fs::path csv = fs::path(ZENITH_SOURCE_DIR) / "bench/results/cluster_rig.csv";
};

Options parse(int argc, char** argv) {
  Options o;
  for (zenith::bench::CommandLine args(argc, argv); args.next();) {
    const std::string& a = args.option();
    if (a == "--zenith")
      o.zenith = args.value();
    else if (a == "--nodes")
      o.nodes = std::stoi(args.value());
    else if (a == "--hz")
      o.hz = std::stod(args.value());
    else if (a == "--frames")
      o.frames = std::stoull(args.value());
    else if (a == "--lookahead")
      o.lookahead = std::stoi(args.value());
    else if (a == "--present-priority")
      o.present_priority = args.value();
    else if (a == "--cases")
      o.cases = zenith::bench::split_list(args.value());
    else if (a == "--schedules")
      o.schedules = zenith::bench::split_list(args.value());
    else if (a == "--size")
      o.size_px = std::stoi(args.value());
    else if (a == "--tables")
      o.tables = args.value();
    else if (a == "--scene")
      o.scene = fs::absolute(args.value());  // the config is written elsewhere
    else if (a == "--work")
      o.work = args.value();
    else if (a == "--cache")
      o.cache = fs::path(args.value());
    else if (a == "--csv")
      o.csv = args.value();
    else
      zenith::bench::help_or_unknown_option(a, kUsage);
  }
  if (o.nodes < 2) throw std::invalid_argument("--nodes: at least 2 (node n1 is the impaired one)");
  if (o.frames < 10) throw std::invalid_argument("--frames: at least 10");
  if (o.lookahead < 1 || o.lookahead > 30) throw std::invalid_argument("--lookahead: in [1, 30]");
  if (!o.present_priority.empty() && o.present_priority != "realtime" && o.present_priority != "normal")
    throw std::invalid_argument("--present-priority: realtime or normal");
  const std::vector<std::string> known = {"none",     "loss1",     "loss5",  "partition2s",
                                          "latency5", "clockstep", "join1g", "join100m"};
  for (const std::string& c : o.cases)
    if (std::find(known.begin(), known.end(), c) == known.end())
      throw std::invalid_argument("--cases: unknown case '" + c + "'");
  for (const std::string& s : o.schedules)
    if (s != "barrier" && s != "scheduled") throw std::invalid_argument("--schedules: barrier or scheduled");
  return o;
}

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

struct Row {
  std::string schedule, case_name, node;
  std::uint64_t presented = 0, expected = 0, missing = 0, over_2t = 0, over_100ms = 0;
  bool in_order = true;
  double longest_ms = 0.0, latest_ms = 0.0, spread_max_ms = 0.0, spread_p99_ms = 0.0, spread_p50_ms = 0.0,
         moment_max_ms = 0.0, moment_p50_ms = 0.0;
  std::uint64_t moments_apart = 0;       ///< frames whose moments lay more than 2 ms apart on the nodes
  std::uint64_t swaps_apart = 0;         ///< frames the nodes presented more than 1 ms apart
  double table_mb = 0.0, table_s = 0.0;  ///< the joining node's (join cases), from the master's log
};

/// The master's line for a node becoming ready: its tables' megabytes and seconds (nothing without it).
std::optional<std::pair<double, double>> join_of(const fs::path& master_log, const std::string& node) {
  std::ifstream in(master_log);
  const std::regex line("node '" + node +
                        "' is ready: ([0-9.]+) MB of tables sent to it, received and loaded in ([0-9.]+) s");
  std::optional<std::pair<double, double>> found;
  std::smatch m;
  for (std::string text; std::getline(in, text);)
    if (std::regex_search(text, m, line)) found = std::make_pair(std::stod(m[1]), std::stod(m[2]));
  return found;
}

std::vector<Row> run_case(const Options& o, const std::string& schedule, const std::string& case_name) {
  NetworkRig rig("bench");
  RigClusterSetup setup;
  setup.zenith = o.zenith;
  setup.work = o.work / (schedule + "-" + case_name);
  setup.cache = o.cache.value_or(o.work / "table-cache");
  setup.scene = o.scene;
  setup.nodes = o.nodes;
  setup.frame_rate_hz = o.hz;
  setup.frames = o.frames;
  setup.lookahead_frames = schedule == "scheduled" ? o.lookahead : 0;
  setup.present_priority = o.present_priority;
  setup.output_px = o.size_px;
  setup.tables = o.tables;
  const bool join = case_name == "join1g" || case_name == "join100m";
  if (case_name == "latency5") setup.relay = RigClusterSetup::Relay{ZENITH_DELAY_RELAY, 5.0, 1.0, 0.0, 0.0};
  if (case_name == "clockstep")
    setup.node_args[1] = {"--debug-clock-drift-ppm",    "300", "--debug-clock-step-ms", "20",
                          "--debug-clock-step-every-s", "2"};
  if (join) {
    setup.late_nodes = {1};
    setup.late_node_niceness = 19;    // its loading on its own PC's cores, as on a dome (rig_cluster.h)
    setup.wait_for_nodes_ms = 60000;  // frame 0 with the others, once they are ready
  }
  RigCluster cluster(rig, setup);
  if (join) rig.set_rate("n1", case_name == "join1g" ? 1e9 : 100e6, NetworkRig::Way::to_host);
  cluster.start();
  if (!cluster.wait_until_warmed_up(1200s))
    throw std::runtime_error("no warm-up frame; see " + cluster.log("master").string());
  const std::int64_t from = now_ns();
  if (join) cluster.join(1);
  if (case_name == "loss1") rig.set_loss("n1", 1.0);
  if (case_name == "loss5") rig.set_loss("n1", 5.0);
  if (case_name == "partition2s") {
    std::this_thread::sleep_for(1s);
    rig.partition("n1");
    std::this_thread::sleep_for(2s);
    rig.heal("n1");
  }
  const auto timeout =
      std::chrono::milliseconds(static_cast<long long>(static_cast<double>(o.frames) * 1000.0 / o.hz) + 120000);
  const std::optional<int> status = cluster.wait_for_master(timeout);
  if (!status || *status != 0)
    throw std::runtime_error("the master did not finish cleanly; see " + cluster.log("master").string());
  cluster.wait_for_nodes(60s);

  std::vector<std::vector<zenith::testing::NodePresent>> all;
  std::vector<Row> rows;
  for (int k = 0; k < o.nodes; ++k) {
    all.push_back(cluster.presents(k));
    const NodeTimeline t = zenith::testing::timeline_of(all.back(), 1, o.frames - 1, from, 2.0 * cluster.period_ms());
    const NodeTimeline freezes = zenith::testing::timeline_of(all.back(), 1, o.frames - 1, from, 100.0);
    Row r{schedule, case_name, RigCluster::node_name(k)};
    r.expected = o.frames - 1;
    r.missing = t.missing.size();
    r.presented = r.expected - r.missing;
    r.in_order = t.in_order;
    r.longest_ms = t.longest_interval_ms;
    r.over_2t = t.long_intervals;
    r.over_100ms = freezes.long_intervals;
    r.latest_ms = t.latest_ms;
    if (join && k == 1)
      if (const auto tables = join_of(cluster.log("master"), "n1")) std::tie(r.table_mb, r.table_s) = *tables;
    rows.push_back(r);
  }
  const std::vector<double> spreads = zenith::testing::swap_spreads_ms(all);
  const std::vector<double> moments = zenith::testing::moment_spreads_ms(all);
  for (Row& r : rows) {
    r.spread_max_ms = spreads.empty() ? 0.0 : *std::max_element(spreads.begin(), spreads.end());
    r.spread_p99_ms = zenith::testing::percentile(spreads, 0.99);
    r.spread_p50_ms = zenith::testing::percentile(spreads, 0.5);
    r.swaps_apart =
        static_cast<std::uint64_t>(std::count_if(spreads.begin(), spreads.end(), [](double ms) { return ms > 1.0; }));
    r.moment_max_ms = moments.empty() ? 0.0 : *std::max_element(moments.begin(), moments.end());
    r.moment_p50_ms = zenith::testing::percentile(moments, 0.5);
    r.moments_apart =
        static_cast<std::uint64_t>(std::count_if(moments.begin(), moments.end(), [](double ms) { return ms > 2.0; }));
  }
  return rows;
}

int run(int argc, char** argv) {
  const Options o = parse(argc, argv);
  if (const std::optional<std::string> why = NetworkRig::unavailable())
    throw std::runtime_error("no network rig here: " + *why);
  fs::create_directories(o.work);
  fmt::print("cluster_rig_bench: {} nodes at {} Hz, {} frames, {}x{} px outputs, {} tables, lookahead {}\n", o.nodes,
             o.hz, o.frames, o.size_px, o.size_px, o.tables, o.lookahead);
  fmt::print(
      "{:<10} {:<12} {:<4} {:>9} {:>8} {:>6} {:>11} {:>7} {:>9} {:>10} {:>10} {:>10} {:>10} {:>7} {:>10} {:>10} "
      "{:>9} {:>8}\n",
      "schedule", "case", "node", "presented", "missing", "order", "longest ms", "> 2T", "> 100 ms", "latest ms",
      "spread ms", "p99 ms", "p50 ms", "> 1 ms", "clock ms", "clock p50", "apart", "table MB", "table s");
  std::vector<Row> rows;
  for (const std::string& schedule : o.schedules)
    for (const std::string& c : o.cases)
      for (const Row& r : run_case(o, schedule, c)) {
        fmt::print(
            "{:<10} {:<12} {:<4} {:>9} {:>8} {:>6} {:>11.1f} {:>7} {:>9} {:>10.1f} {:>10.2f} {:>10.2f} {:>10.2f} "
            "{:>7} {:>10.3f} {:>10.3f} {:>6} {:>9.1f} {:>8.2f}\n",
            r.schedule, r.case_name, r.node, r.presented, r.missing, r.in_order ? "yes" : "NO", r.longest_ms, r.over_2t,
            r.over_100ms, r.latest_ms, r.spread_max_ms, r.spread_p99_ms, r.spread_p50_ms, r.swaps_apart,
            r.moment_max_ms, r.moment_p50_ms, r.moments_apart, r.table_mb, r.table_s);
        std::fflush(stdout);
        rows.push_back(r);
      }
  fs::create_directories(o.csv.parent_path());
  std::ofstream csv(o.csv);
  csv << "schedule,case,node,hz,frames_expected,presented,missing,in_order,longest_interval_ms,"
         "intervals_over_2_periods,intervals_over_100ms,latest_after_moment_ms,swap_spread_max_ms,swap_spread_p99_ms,"
         "moment_spread_max_ms,table_mb,table_s,moment_spread_p50_ms,frames_moments_over_2ms_apart,swap_spread_p50_ms,"
         "frames_swaps_over_1ms_apart\n";
  for (const Row& r : rows)
    csv << fmt::format(
        "{},{},{},{},{},{},{},{},{:.2f},{},{},{:.2f},{:.3f},{:.3f},{:.3f},{:.2f},{:.3f},{:.3f},{},{:.3f},{}\n",
        r.schedule, r.case_name, r.node, o.hz, r.expected, r.presented, r.missing, r.in_order ? 1 : 0, r.longest_ms,
        r.over_2t, r.over_100ms, r.latest_ms, r.spread_max_ms, r.spread_p99_ms, r.moment_max_ms, r.table_mb, r.table_s,
        r.moment_p50_ms, r.moments_apart, r.spread_p50_ms, r.swaps_apart);
  fmt::print("csv: {}\n", o.csv.string());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return zenith::bench::main_reporting_errors("cluster_rig_bench", argc, argv, run); }
