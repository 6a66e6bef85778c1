// `zenith master`, `zenith node` and `zenith cluster` (docs/cluster.md): the
// command lines of the master and a render node of a networked cluster, and
// of a local cluster (cluster/launcher/local_cluster.h).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/cli_options.h"
#include "apps/commands.h"
#include "apps/default_configs.h"
#include "atmosphere/lut/table_cache.h"
#include "cluster/launcher/launcher_signals.h"
#include "cluster/launcher/local_cluster.h"
#include "cluster/link/cluster_config.h"
#include "cluster/master/master.h"
#include "cluster/node/node.h"
#include "cluster/protocol/handshake.h"
#include "cluster/standby/standby.h"
#include "core/strings.h"
#include "show/show.h"

namespace zenith::app {
namespace {

namespace fs = std::filesystem;
using core::cat;

/// --switch-atmosphere "FRAME:BODY:PRESET_OR_FILE"; throws std::invalid_argument naming the value.
cluster::AtmosphereSwitch parse_atmosphere_switch(const std::string& text) {
  const auto first = text.find(':');
  const auto second = first == std::string::npos ? std::string::npos : text.find(':', first + 1);
  if (second == std::string::npos || first == 0 || second == first + 1 || second + 1 >= text.size())
    throw std::invalid_argument(cat("--switch-atmosphere ", text, ": expected FRAME:BODY:PRESET_OR_FILE"));
  cluster::AtmosphereSwitch sw;
  try {
    std::size_t used = 0;
    sw.frame = std::stoull(text.substr(0, first), &used);
    if (used != first) throw std::invalid_argument("trailing characters");
  } catch (const std::exception&) {
    throw std::invalid_argument(cat("--switch-atmosphere ", text, ": FRAME must be a frame number"));
  }
  sw.body = text.substr(first + 1, second - first - 1);
  sw.atmosphere = text.substr(second + 1);
  return sw;
}

/// The cluster configuration to use: the one named, or the built-in default.
std::string cluster_path(const std::string& named) {
  return named.empty() ? default_config(kDefaultClusterName).string() : named;
}

/// The node's own table cache unless --cache is given: per cluster and node,
/// so nodes sharing a machine (and the master) never write each other's files.
fs::path default_node_cache(const cluster::ClusterConfig& config, const std::string& node) {
  return atmosphere::lut::default_cache_directory() / "cluster-nodes" / config.name / node;
}

cluster::SharedSecret load_secret(const cluster::ClusterConfig& config) {
  return cluster::load_shared_secret(config.secret_file, config.secret_env.c_str());
}

// ---------------------------------------------------------------------------
// zenith master

/// Playback options shared by `zenith master` and `zenith cluster` (docs/shows.md).
struct PlaybackArgs {
  std::string show, record, ltc_device, ltc_file, mtc_device;
  int ltc_channel = 0;
  std::optional<double> ltc_file_epoch_s;
  double fps = 0.0;
  bool loop = false, no_loop = false, console = false, unpaced = false;
  std::optional<int> control_port;

  void add_to(CLI::App& cmd) {
    cmd.add_option("--show", show, "Play this show file (configs/shows/; docs/shows.md) instead of the default show");
    cmd.add_option("--record", record, "Record every presented frame state into this show file (a recording)");
    cmd.add_option("--fps", fps,
                   "Frames per second of show time (default: the cluster's frame rate; a recording's own)")
        ->check(CLI::Range(0.001, 1000.0));
    cmd.add_flag("--loop", loop, "Loop the show");
    cmd.add_flag("--no-loop", no_loop, "Play the show once even if it says loop");
    cmd.add_flag("--console", console,
                 "Read playback commands from standard input (play, pause, seek S, rate R, loop on|off, quit)");
    cmd.add_option("--control-port", control_port, "Playback commands on a control socket at 127.0.0.1:PORT")
        ->check(CLI::Range(1, 65535));
    cmd.add_flag("--unpaced", unpaced, "Start each frame as soon as the last is presented (offline rendering)");
    cmd.add_option("--ltc-device", ltc_device,
                   "Chase the house's LTC timecode from this ALSA capture device, e.g. hw:1,0 (the show needs a "
                   "\"timecode\" block; docs/shows.md, \"Chasing timecode\")");
    cmd.add_option("--ltc-file", ltc_file,
                   "Chase the LTC of this audio file, played in real time from the master's start (a rehearsal)")
        ->excludes("--ltc-device");
    cmd.add_option("--ltc-file-epoch", ltc_file_epoch_s,
                   "When the --ltc-file's first sample sounds, in Unix seconds (default: the master's start; `zenith "
                   "cluster`: its own start, for its master and standby alike), so that two masters chase one "
                   "rehearsal")
        ->needs("--ltc-file")
        ->check(CLI::Range(0.0, 1e11));
    cmd.add_option("--ltc-channel", ltc_channel, "The channel carrying the LTC, 0 the first (default 0)")
        ->check(CLI::Range(0, 63));
    cmd.add_option("--mtc-device", mtc_device,
                   "Chase MIDI timecode from this ALSA raw MIDI port, e.g. hw:1,0,0 (amidi -l lists them)")
        ->excludes("--ltc-device")
        ->excludes("--ltc-file");
  }
  void apply(cluster::MasterOptions& options) const {
    if (!show.empty()) options.show = fs::path(show);
    if (!record.empty()) options.record = fs::path(record);
    options.show_fps = fps;
    if (loop && no_loop) throw std::invalid_argument("--loop and --no-loop contradict each other");
    if (loop) options.loop = true;
    if (no_loop) options.loop = false;
    options.console = console;
    if (control_port) options.control_port = static_cast<std::uint16_t>(*control_port);
    options.paced = !unpaced;
    options.ltc_device = ltc_device;
    options.mtc_device = mtc_device;
    if (!ltc_file.empty()) options.ltc_file = fs::path(ltc_file);
    options.ltc_channel = ltc_channel;
    options.ltc_file_epoch_s = ltc_file_epoch_s;
  }
  /// The same options as command-line arguments for a child master.
  std::vector<std::string> arguments() const {
    std::vector<std::string> args;
    if (!show.empty()) args.insert(args.end(), {"--show", show});
    if (!record.empty()) args.insert(args.end(), {"--record", record});
    if (fps > 0.0) args.insert(args.end(), {"--fps", fmt::format("{}", fps)});
    if (loop) args.push_back("--loop");
    if (no_loop) args.push_back("--no-loop");
    if (console) args.push_back("--console");
    if (control_port) args.insert(args.end(), {"--control-port", std::to_string(*control_port)});
    if (unpaced) args.push_back("--unpaced");
    if (!ltc_device.empty()) args.insert(args.end(), {"--ltc-device", ltc_device});
    if (!ltc_file.empty()) {
      // The rehearsal plays from this instant for the master and for a standby that takes over from it.
      const double epoch_s = ltc_file_epoch_s.value_or(
          std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count());
      args.insert(args.end(), {"--ltc-file", ltc_file, "--ltc-file-epoch", fmt::format("{:.3f}", epoch_s)});
    }
    if (!mtc_device.empty()) args.insert(args.end(), {"--mtc-device", mtc_device});
    if (ltc_channel != 0) args.insert(args.end(), {"--ltc-channel", std::to_string(ltc_channel)});
    return args;
  }
};

/// The operator console's options, shared by `zenith master` and `zenith
/// cluster` (docs/operator.md). The token is never an argument: a file or
/// the environment.
struct OperatorArgs {
  std::optional<int> http_port, osc_port;
  std::string http_host = "127.0.0.1", token_file, osc_host = "127.0.0.1";
  std::vector<std::string> osc_allow, http_names;

  void add_to(CLI::App& cmd) {
    cmd.add_option("--operator-port", http_port,
                   "Serve the operator console (web page, JSON API) on this port (docs/operator.md)")
        ->check(CLI::Range(1, 65535));
    cmd.add_option("--operator-host", http_host,
                   "Address the console listens on (default 127.0.0.1; any other needs an operator token)");
    cmd.add_option("--operator-name", http_names,
                   "With an operator token: a host name the console is reached by (besides its IP addresses; "
                   "repeatable; other Host names are refused)");
    cmd.add_option(
        "--operator-token-file", token_file,
        "File (mode 600) holding the operator token (default: the environment variable ZENITH_OPERATOR_TOKEN)");
    cmd.add_option("--osc-port", osc_port, "Receive OSC cues on this UDP port (docs/operator.md)")
        ->check(CLI::Range(1, 65535));
    cmd.add_option("--osc-host", osc_host,
                   "Address OSC is received on (default 127.0.0.1; any other needs --osc-allow)");
    cmd.add_option("--osc-allow", osc_allow, "Accept OSC only from this sender address (repeatable)");
  }
  void apply(cluster::MasterOptions& options) const {
    cluster::OperatorConsoleOptions& console = options.operator_console;
    if (http_port) console.http_port = static_cast<std::uint16_t>(*http_port);
    console.http_host = http_host;
    console.token = load_operator_token();
    console.http_names = http_names;
    if (osc_port) console.osc_port = static_cast<std::uint16_t>(*osc_port);
    console.osc_host = osc_host;
    console.osc_allow = osc_allow;
  }
  /// The token from --operator-token-file or ZENITH_OPERATOR_TOKEN, if either is given.
  std::optional<cluster::SharedSecret> load_operator_token() const {
    if (token_file.empty() && std::getenv(kOperatorTokenVariable) == nullptr) return std::nullopt;
    try {
      cluster::SharedSecret token = cluster::load_shared_secret(
          token_file.empty() ? std::nullopt : std::optional<fs::path>(token_file), kOperatorTokenVariable);
      for (const std::uint8_t c : token.bytes())
        if (c < 0x21 || c > 0x7e)
          throw std::runtime_error("must be printable ASCII without spaces (it travels in an HTTP header)");
      return token;
    } catch (const std::exception& e) {
      throw std::runtime_error(cat(
          "operator token (", token_file.empty() ? std::string(kOperatorTokenVariable) : token_file, "): ", e.what()));
    }
  }
  /// The same options as command-line arguments for a child master.
  std::vector<std::string> arguments() const {
    std::vector<std::string> args;
    if (http_port)
      args.insert(args.end(), {"--operator-port", std::to_string(*http_port), "--operator-host", http_host});
    if (!token_file.empty()) args.insert(args.end(), {"--operator-token-file", token_file});
    for (const std::string& n : http_names) args.insert(args.end(), {"--operator-name", n});
    if (osc_port) args.insert(args.end(), {"--osc-port", std::to_string(*osc_port), "--osc-host", osc_host});
    for (const std::string& a : osc_allow) args.insert(args.end(), {"--osc-allow", a});
    return args;
  }
  static constexpr const char* kOperatorTokenVariable = "ZENITH_OPERATOR_TOKEN";
};

struct MasterArgs {
  std::string cluster, cache_dir;
  PlaybackArgs playback;
  OperatorArgs operator_console;
  std::uint64_t frames = 0;
  std::optional<int> port;
  double sun_step_deg = 0.1;
  std::uint32_t wait_for_nodes_ms = 30000;
  bool cpu_precompute = false;
  bool standby = false;               ///< run the config's standby master instead
  std::vector<std::string> switches;  ///< --switch-atmosphere FRAME:BODY:PRESET_OR_FILE
  std::uint32_t debug_table_delay_ms = 0;
  std::optional<int> ready_fd;  ///< set by `zenith cluster`: written once the master listens
};

/// Runs the master, or with --standby the standby master; returns the exit code.
int run_master(const MasterArgs& a) {
  die_with_launcher();
  cluster::MasterOptions options;
  if (a.ready_fd) options.on_listening = [fd = *a.ready_fd] { signal_ready(fd); };
  a.playback.apply(options);
  a.operator_console.apply(options);
  options.config = cluster::load_cluster_config(cluster_path(a.cluster));
  options.frames = a.frames;
  options.sun_step_deg = a.sun_step_deg;
  if (a.port) options.port = static_cast<std::uint16_t>(*a.port);
  if (!a.cache_dir.empty()) options.cache_directory = fs::path(a.cache_dir);
  options.cpu_precompute = a.cpu_precompute;
  options.wait_for_nodes_ms = a.wait_for_nodes_ms;
  options.debug_table_delay_ms = a.debug_table_delay_ms;
  for (const std::string& text : a.switches) options.atmosphere_switches.push_back(parse_atmosphere_switch(text));
  cluster::SharedSecret secret = load_secret(options.config);
  spdlog::info("{}: shared secret from {}", a.standby ? "standby" : "master", secret.source());
  if (a.standby) {
    cluster::Standby standby(cluster::StandbyOptions{std::move(options)}, std::move(secret));
    return standby.run();
  }
  cluster::Master master(std::move(options), std::move(secret));
  return master.run();
}

// ---------------------------------------------------------------------------
// zenith node

struct NodeArgs {
  std::string cluster, name, out, record_frames, cache_dir, scene, layout = "per-node";
  std::optional<int> port;
  std::uint32_t connect_timeout_ms = 15000;
  std::optional<double> reconnect_s;
  std::vector<std::string> atmosphere_files;
  std::uint32_t debug_render_delay_ms = 0;
  double debug_clock_drift_ppm = 0.0, debug_clock_step_ms = 0.0, debug_clock_step_every_s = 0.0;
  bool window = false;
};

int run_node(const NodeArgs& a) {
  die_with_launcher();
  cluster::NodeOptions options;
  options.config = cluster::load_cluster_config(cluster_path(a.cluster));
  options.node_name = a.name;
  // A live node writes frames only when asked (--out, --record-frames); an offline render always does.
  options.output_directory = !a.record_frames.empty() ? fs::path(a.record_frames)
                             : a.out.empty()          ? options.config.output_directory
                                                      : fs::path(a.out);
  options.write_frames = !a.out.empty() || !a.record_frames.empty() || a.layout == "offline";
  options.cache_directory = a.cache_dir.empty() ? default_node_cache(options.config, a.name) : fs::path(a.cache_dir);
  if (a.port) options.port = static_cast<std::uint16_t>(*a.port);
  options.connect_timeout_ms = a.connect_timeout_ms;
  if (a.reconnect_s) options.reconnect_ms = static_cast<std::uint32_t>(std::lround(*a.reconnect_s * 1000.0));
  for (const std::string& f : a.atmosphere_files) options.atmosphere_files.emplace_back(f);
  options.debug_render_delay_ms = a.debug_render_delay_ms;
  options.debug_clock_faults.drift_ppm = a.debug_clock_drift_ppm;
  options.debug_clock_faults.step_ns = std::llround(a.debug_clock_step_ms * 1e6);
  options.debug_clock_faults.step_every = std::chrono::nanoseconds(std::llround(a.debug_clock_step_every_s * 1e9));
  if (!a.scene.empty()) options.scene = fs::path(a.scene);
  options.window = a.window;
  options.layout = a.layout == "offline" ? cluster::FrameFileLayout::offline : cluster::FrameFileLayout::per_node;
  cluster::SharedSecret secret = load_secret(options.config);
  cluster::Node node(std::move(options), std::move(secret));
  return node.run();
}

// ---------------------------------------------------------------------------
// zenith cluster

struct ClusterArgs {
  std::string cluster, out, record_frames, cache_dir;
  PlaybackArgs playback;
  OperatorArgs operator_console;
  std::optional<std::uint64_t> frames;  ///< default 10 without a show, the whole show with one
  std::optional<int> port;
  double sun_step_deg = 0.1;
  std::optional<std::uint64_t> stitch_frame;
  std::vector<std::string> switches;  ///< passed to the master
  bool windows = false;               ///< local nodes show their frames in windows
  bool restart_nodes = false;         ///< restart a local node that died
  std::uint32_t max_restarts = 5;     ///< … at most this often
  double restart_window_s = 60.0;     ///< … within this many seconds
};

void run_cluster(const ClusterArgs& a) {
  LocalClusterOptions o;
  o.config_path = cluster_path(a.cluster);
  o.config = cluster::load_cluster_config(o.config_path.string());
  // A show brings its own scene: master and nodes render it instead of the configuration's.
  std::uint64_t show_frames = 0;
  if (!a.playback.show.empty()) {
    const show::Show loaded = show::load_show(a.playback.show);  // errors before any child starts
    o.scene = loaded.scene_path();
    const double fps = a.playback.fps > 0.0                           ? a.playback.fps
                       : loaded.kind() == show::Show::Kind::recording ? loaded.frame_rate_hz()
                                                                      : o.config.frame_rate_hz;
    show_frames = loaded.frame_count(fps);
  }
  const std::uint64_t frames = a.frames.value_or(o.scene ? 0 : 10);
  if (!a.out.empty() || !a.record_frames.empty()) {  // a live show writes no frame files unless asked
    o.frame_directory = !a.record_frames.empty() ? fs::path(a.record_frames) : fs::path(a.out);
    if (const std::uint64_t last = frames > 0 ? frames : show_frames; last > 0)
      o.stitch_frame = a.stitch_frame.value_or(last - 1);
  }
  o.port = a.port;
  o.master_options = {"--frames", std::to_string(frames), "--sun-step-deg", fmt::format("{}", a.sun_step_deg)};
  const std::vector<std::string> playback = a.playback.arguments();
  o.master_options.insert(o.master_options.end(), playback.begin(), playback.end());
  const std::vector<std::string> console = a.operator_console.arguments();
  o.master_options.insert(o.master_options.end(), console.begin(), console.end());
  if (!a.cache_dir.empty()) {
    o.master_options.insert(o.master_options.end(), {"--cache", a.cache_dir});
    o.cache_directory = a.cache_dir;
  }
  // Nodes need no atmosphere files: the master sends each version's parameters (AtmosphereDefinition).
  for (const std::string& text : a.switches)
    o.master_options.insert(o.master_options.end(), {"--switch-atmosphere", text});
  o.windows = a.windows;
  o.restart_nodes = a.restart_nodes;
  o.max_restarts = a.max_restarts;
  o.restart_window_s = a.restart_window_s;
  run_local_cluster(o);
}

// Options the master, a node and a local cluster share.

/// --port: the config's master port overridden (1..65535).
void add_master_port_option(CLI::App* cmd, std::optional<int>& port) {
  cmd->add_option("--port", port, "Override the config's master port")->check(CLI::Range(1, 65535));
}

/// --cluster FILE, required: the master's and a node's cluster config.
void add_required_cluster_option(CLI::App* cmd, std::string& cluster) {
  cmd->add_option("--cluster", cluster, "Cluster config JSON (configs/clusters/)")->required();
}

/// --out DIR and --record-frames DIR (one of them at most): where presented frames are written.
void add_frame_output_options(CLI::App* cmd, std::string& out, std::string& record_frames, const std::string& out_help,
                              const std::string& record_help) {
  cmd->add_option("--out", out, out_help);
  cmd->add_option("--record-frames", record_frames, record_help)->excludes("--out");
}

}  // namespace

void register_cluster_commands(CLI::App& app) {
  {
    auto a = std::make_shared<MasterArgs>();
    CLI::App* cmd =
        app.add_subcommand("master", "Run the master of a cluster: tables, frame barrier (docs/cluster.md)");
    add_required_cluster_option(cmd, a->cluster);
    a->playback.add_to(*cmd);
    a->operator_console.add_to(*cmd);
    cmd->add_option("--frames", a->frames,
                    "Present this many frames, then stop the nodes (default 0: until SIGTERM, or the end of a show)");
    add_master_port_option(cmd, a->port);
    cmd->add_option("--cache", a->cache_dir, "Table cache directory (default $XDG_CACHE_HOME/zenith)");
    add_cpu_precompute_flag(cmd, a->cpu_precompute);
    cmd->add_option("--sun-step-deg", a->sun_step_deg, "Default show: the sun turns this much per frame (default 0.1)")
        ->check(CLI::Range(-10.0, 10.0));
    cmd->add_option("--wait-for-nodes-ms", a->wait_for_nodes_ms,
                    "Start when every node is ready, or after this long with those that are (default 30000)");
    cmd->add_option("--switch-atmosphere", a->switches,
                    "FRAME:BODY:PRESET_OR_FILE: from FRAME on, prepare that atmosphere's tables in the background and "
                    "switch every node to them at one frame (repeatable; docs/cluster.md)");
    cmd->add_option("--debug-table-delay-ms", a->debug_table_delay_ms,
                    "Test hook: every table set prepared in the background after the first takes this much longer "
                    "(plays a slow precompute)");
    cmd->add_option("--ready-fd", a->ready_fd,
                    "Set by zenith cluster: a pipe written to once the master listens on its port")
        ->group("");
    cmd->add_flag("--standby", a->standby,
                  "Run the config's standby master: follow the master, take over on the standby's address when it "
                  "is gone (give it the master's options; docs/cluster.md, \"Standby master\")");
    cmd->callback([a] {
      const int code = run_master(*a);
      if (code != 0) std::exit(code);  // a standby's NodeExit code (docs/cluster.md)
    });
  }
  {
    auto a = std::make_shared<NodeArgs>();
    CLI::App* cmd = app.add_subcommand("node", "Run one render node of a cluster (docs/cluster.md)");
    add_required_cluster_option(cmd, a->cluster);
    cmd->add_option("--name", a->name, "This node's name in the config")->required();
    add_frame_output_options(
        cmd, a->out, a->record_frames,
        "Write every presented frame to OUT/<node>/<output>/ (default: no frame files; presented.log goes to the "
        "config's output directory)",
        "Write every presented frame to DIR/<node>/<output>/ (as --out; one file per presented frame)");
    cmd->add_option("--cache", a->cache_dir,
                    "This node's table cache (default $XDG_CACHE_HOME/zenith/cluster-nodes/<cluster>/<node>)");
    add_master_port_option(cmd, a->port);
    cmd->add_option("--connect-timeout-ms", a->connect_timeout_ms,
                    "Keep trying to reach the master this long (default 15000)");
    cmd->add_option("--reconnect-s", a->reconnect_s,
                    "After losing the master, keep the last frame and try to rejoin this long before exiting with "
                    "status 3 (default: the config's timing.reconnect_s, 300; 0: exit at once)")
        ->check(CLI::Range(0.0, cluster::kMaxReconnectS));
    cmd->add_option("--scene", a->scene, "Render this scene instead of the config's (a show's scene)");
    cmd->add_option("--layout", a->layout,
                    "per-node: OUT/<node>/<output>/frame-N.png (default); offline: OUT/<output>/<output>.N.png "
                    "(zenith show render --cluster)")
        ->check(CLI::IsMember({"per-node", "offline"}));
    cmd->add_option("--atmosphere", a->atmosphere_files,
                    "An atmosphere file the master may switch to (besides the scene's and the presets; repeatable)");
    cmd->add_flag("--window", a->window,
                  "Show each presented frame on this machine's displays: each output in the window its viewport "
                  "config gives it, the others side by side in one window (needs a display; docs/window.md)");
    cmd->add_option("--debug-render-delay-ms", a->debug_render_delay_ms,
                    "Test hook: sleep this long before rendering each frame (plays a slow node)");
    // A rehearsal of a PC whose clock misbehaves; the machine's time is never touched.
    const double max_step_ms = static_cast<double>(cluster::LocalClock::kMaxStepNs) / 1e6;
    cmd->add_option("--debug-clock-drift-ppm", a->debug_clock_drift_ppm,
                    "Test hook: the node's clock, as its clock synchronisation reads it, runs this many ppm fast "
                    "(negative: slow)")
        ->check(CLI::Range(-cluster::LocalClock::kMaxDriftPpm, cluster::LocalClock::kMaxDriftPpm));
    CLI::Option* step_every =
        cmd->add_option("--debug-clock-step-every-s", a->debug_clock_step_every_s,
                        "Test hook: with --debug-clock-step-ms, the interval between the clock's jumps")
            ->check(CLI::Range(0.1, 3600.0));
    cmd->add_option("--debug-clock-step-ms", a->debug_clock_step_ms,
                    "Test hook: the node's clock jumps this far ahead (negative: back) every "
                    "--debug-clock-step-every-s, and back again the next time")
        ->check(CLI::Range(-max_step_ms, max_step_ms))
        ->needs(step_every);
    cmd->callback([a] {
      const int code = run_node(*a);
      if (code != 0) std::exit(code);  // the NodeExit code (docs/cluster.md)
    });
  }
  {
    auto a = std::make_shared<ClusterArgs>();
    CLI::App* cmd = app.add_subcommand(
        "cluster",
        "Run a local cluster: the master and every node of this machine as child processes (docs/cluster.md)");
    cmd->add_option("--cluster", a->cluster,
                    fmt::format("Cluster config JSON (default configs/{}, built in)", kDefaultClusterName));
    a->playback.add_to(*cmd);
    a->operator_console.add_to(*cmd);
    cmd->add_option("--frames", a->frames, "Frames to present (default 10; with --show, the whole show)")
        ->check(CLI::Range(1, 100000000));
    add_frame_output_options(
        cmd, a->out, a->record_frames,
        "Write every presented frame under OUT/<node>/ and stitch the last (default: no frame files)",
        "The same as --out DIR: record every presented frame");
    add_master_port_option(cmd, a->port);
    cmd->add_option("--cache", a->cache_dir, "Master table cache; nodes use CACHE/nodes/<node>");
    cmd->add_option("--sun-step-deg", a->sun_step_deg, "The sun turns this much per frame (default 0.1)")
        ->check(CLI::Range(-10.0, 10.0));
    cmd->add_flag("--windows", a->windows,
                  "Each local node shows its frames on the displays, in the windows its outputs' config gives "
                  "(needs a display; docs/window.md)");
    cmd->add_option("--stitch-frame", a->stitch_frame, "Frame to stitch into OUT/stitched/ (default: the last)");
    cmd->add_option("--switch-atmosphere", a->switches,
                    "FRAME:BODY:PRESET_OR_FILE: switch that atmosphere mid-show (passed to the master; repeatable)");
    cmd->add_flag("--restart-nodes", a->restart_nodes,
                  "Restart a local node that dies (non-zero exit or a signal); it rejoins with its cached tables");
    cmd->add_option(
           "--max-restarts", a->max_restarts,
           "With --restart-nodes: a node that died this often within --restart-window-s stays down (default 5)")
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--restart-window-s", a->restart_window_s,
                    "With --restart-nodes: the window of --max-restarts (default 60)")
        ->check(CLI::Range(1.0, 86400.0));
    register_cluster_check(*cmd);
    cmd->callback([a, cmd] {
      if (!cmd->got_subcommand("check")) run_cluster(*a);
    });
  }
}

}  // namespace zenith::app
