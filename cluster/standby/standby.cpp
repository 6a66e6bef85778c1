#include "cluster/standby/standby.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <stdexcept>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>

#include "cluster/link/link_exit.h"
#include "cluster/link/master_link.h"
#include "cluster/master/house_timecode.h"
#include "cluster/protocol/heartbeat.h"
#include "cluster/standby/standby_follower.h"
#include "cluster/standby/takeover_rule.h"
#include "core/strings.h"
#include "core/timing.h"
#include "show/show.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using core::cat;
using Clock = std::chrono::steady_clock;

struct Standby::Impl {
  StandbyOptions options;
  SharedSecret secret;
  asio::io_context io;
  asio::signal_set signals{io, SIGINT, SIGTERM};
  StandbyFollower follower;  ///< every table version and the last frames of the active master
  TakeoverRule rule;         ///< following, checking after a loss, taking over
  std::optional<MasterLink> link;
  /// The house's timecode, opened and chased while following: locked when it takes over.
  std::shared_ptr<HouseTimecode> timecode;
  bool timecode_locked_logged = false;
  LinkEnd end;  // the exit code, decided by the first finish()
  Clock::time_point lost_at;

  Impl(StandbyOptions o, SharedSecret s) : options(std::move(o)), secret(std::move(s)) {}

  const ClusterConfig& config() const { return options.master.config; }

  /// The link to the active master: the standby role, the active master alone,
  /// and one attempt of at most check_attempt_ms after a loss to tell a dead
  /// master from a lost connection.
  MasterLink::Setup link_setup() const {
    MasterLink::Setup setup;
    setup.cluster_name = config().name;
    setup.peer_name = standby_name(*config().standby);
    setup.role = PeerRole::standby;
    setup.who = "standby";
    setup.masters = {MasterAddress{config().master_host, options.master.port.value_or(config().master_port)}};
    setup.heartbeat_ms = config().heartbeat_ms;
    setup.rules.connect_timeout_ms = options.connect_timeout_ms;
    setup.rules.reconnect_ms = kDefaultReconnectMs;  // never reached: the first failed attempt decides
    setup.rules.attempt_timeout_ms = options.check_attempt_ms;
    return setup;
  }

  /// Ends following with `code` (first call wins): the signal wait and the link stop, io.run() returns.
  void finish(int code) {
    if (!end.finish(code, signals)) return;
    link->stop();
  }

  void on_welcomed() {
    follower.on_welcome();
    if (rule.welcomed())
      spdlog::warn(
          "standby: the active master at {} welcomed it again {:.1f} s after the loss: it is alive (the loss "
          "was this standby's own); following again",
          link->master_address(), core::ms_since(lost_at) / 1000.0);
    else
      spdlog::info("standby: following the active master at {}; taking over at {} when it is gone",
                   link->master_address(), config().standby->text());
    link->send(heartbeat_at(Clock::now()));  // an empty inventory: the master sends every set in full
  }

  void on_message(const Message& message) {
    const std::size_t versions = follower.versions().size();
    const std::uint64_t frames = follower.frames_seen();
    follower.on_message(message);
    if (follower.versions().size() > versions) {
      const TakeoverState::Version& v = follower.versions().back();
      spdlog::info("standby: holds table version {} of '{}' ({} bytes, SHA-256 verified)",
                   short_hex(v.definition.table_hash), v.definition.body_name, v.set.bytes->size());
    }
    if (frames == 0 && follower.frames_seen() == 1)
      spdlog::info("standby: the show runs: following from frame {}", follower.last_frame()->frame);
    if (timecode) chase_timecode();
  }

  /// The timecode read since the last message, into the chase; its first lock logged.
  void chase_timecode() {
    timecode->take_frames();
    if (timecode_locked_logged) return;
    const double now_s = std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
    const show::ChasePosition p = timecode->chase.position(now_s);
    if (p.state != show::ChaseState::locked) return;
    spdlog::info("standby: timecode locked while following (at {}, show time {:.3f} s): a takeover goes on from it",
                 p.last ? show::format_timecode(*p.last, p.rate) : std::string("?"), p.show_time_s);
    timecode_locked_logged = true;
  }

  void on_attempt_failed(const std::string& reason) {
    if (!rule.attempt_failed()) return;
    spdlog::warn("standby: the active master is gone ({:.2f} s after the loss: {}): taking over on {}",
                 core::ms_since(lost_at) / 1000.0, reason, config().standby->text());
    finish(kNodeExitDone);  // run() goes on with take_over()
  }

  /// Runs the master this standby becomes: on its own address, with what it followed.
  int take_over() {
    if (const std::optional<std::string> problem = follower.takeover_problem()) {
      spdlog::error("standby: cannot continue the show: {}", *problem);
      return kNodeExitFailed;
    }
    MasterOptions master = options.master;
    if (master.record) {  // the recording is the active master's file: never overwritten by a partial one
      spdlog::warn("standby: not recording into {} after the takeover (the active master's recording)",
                   master.record->string());
      master.record.reset();
    }
    const auto state = std::make_shared<const TakeoverState>(follower.takeover_state());
    master.config.master_host = config().standby->host;
    master.port = config().standby->port;
    if (state->last_frame) {
      if (master.frames != 0) {
        if (state->next_frame() >= master.frames) {
          spdlog::info("standby: the active master had sent the show's last frame ({}): nothing left to show",
                       state->last_frame->frame);
          return kNodeExitDone;
        }
        master.frames -= state->next_frame();  // the same last frame as the active master's
      }
      master.wait_for_nodes_ms = std::min(master.wait_for_nodes_ms, options.takeover_wait_ms);
    } else {
      spdlog::info("standby: the active master had not started the show: starting it from frame 0");
    }
    master.takeover = state;
    if (timecode) timecode->take_frames();
    master.house_timecode = std::move(timecode);
    Master taken_over(std::move(master), secret);
    return taken_over.run();
  }

  int run() {
    if (!config().standby)
      throw std::invalid_argument(cat("zenith master --standby: the cluster config ", config().source,
                                      " has no \"standby\" entry (docs/cluster.md, \"Standby master\")"));
    link.emplace(io, link_setup(), secret,
                 MasterLink::Events{[this](const Welcome&) { on_welcomed(); },
                                    [this](const std::string&) {
                                      lost_at = Clock::now();
                                      rule.lost();
                                      spdlog::info(
                                          "standby: checking whether the active master is gone (one more "
                                          "attempt, at most {:.1f} s)",
                                          options.check_attempt_ms / 1000.0);
                                    },
                                    [this](const Message& m) { on_message(m); }, [this](int code) { finish(code); },
                                    [this](const std::string& reason) { on_attempt_failed(reason); }});
    signals.async_wait([this](const boost::system::error_code& ec, int signal) {
      if (ec || end.finished) return;
      spdlog::info("standby: {} received: leaving", signal == SIGINT ? "SIGINT" : "SIGTERM");
      link->say_goodbye("standby stopped by a signal");
      finish(kNodeExitDone);
    });
    spdlog::info("standby: cluster '{}': following the active master at {}, standing by to take over on {}",
                 config().name, link->master_address(), config().standby->text());
    if (chases_timecode(options.master)) {
      // Its own input of the house's timecode, chased from now on (the show file names its rate and start).
      std::optional<show::Show> show;
      if (options.master.show) show.emplace(show::load_show(*options.master.show));
      try {
        timecode = open_house_timecode(options.master, show ? &*show : nullptr);
        spdlog::info("standby: chasing {} while it follows", timecode->summary);
      } catch (const std::runtime_error& e) {
        // A sound device opens once: on the master's own machine the master holds it until it dies.
        if (options.master.ltc_file) throw;
        spdlog::warn(
            "standby: cannot open the timecode input while following ({}); it opens it when it takes over "
            "(then the show holds its last frame until the timecode locks). Give the standby an input of its "
            "own on its own machine (docs/shows.md, \"Chasing timecode\")",
            e.what());
      }
    }
    link->start();
    io.run();
    if (rule.phase() != TakeoverRule::Phase::taking_over) return end.exit_code;
    link.reset();
    return take_over();
  }
};

Standby::Standby(StandbyOptions options, SharedSecret secret)
    : impl_(std::make_unique<Impl>(std::move(options), std::move(secret))) {}
Standby::~Standby() = default;
int Standby::run() { return impl_->run(); }

}  // namespace zenith::cluster
