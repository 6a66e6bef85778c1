#include "cluster/check/link_check.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>
#include <memory>
#include <set>

#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "cluster/link/connection.h"
#include "cluster/master/heartbeat_monitor.h"
#include "cluster/master/node_datagrams.h"
#include "cluster/master/node_listener.h"
#include "cluster/master/node_sessions.h"
#include "core/strings.h"
#include "core/wall_clock.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using Clock = std::chrono::steady_clock;
using core::cat;

namespace {

constexpr std::size_t kFillChunkBytes = 256 << 10;

double ms_of_ns(std::uint64_t ns) { return static_cast<double>(ns) / 1e6; }
template <class Duration>
double seconds(Duration d) {
  return std::chrono::duration<double>(d).count();
}

/// The fill, encoded once and shared by every node's connection.
std::vector<std::shared_ptr<const std::vector<std::uint8_t>>> encode_fill(std::uint64_t bytes) {
  std::vector<std::shared_ptr<const std::vector<std::uint8_t>>> frames;
  std::vector<std::uint8_t> pattern(kFillChunkBytes);
  for (std::size_t i = 0; i < pattern.size(); ++i) pattern[i] = static_cast<std::uint8_t>(i * 131 + (i >> 9));
  for (std::uint64_t sent = 0; sent < bytes; sent += kFillChunkBytes) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(kFillChunkBytes, bytes - sent));
    LinkFill fill{static_cast<std::uint32_t>(frames.size()), {pattern.begin(), pattern.begin() + static_cast<long>(n)}};
    frames.push_back(std::make_shared<const std::vector<std::uint8_t>>(encode(fill)));
  }
  return frames;
}

}  // namespace

struct LinkChecker {
  const LinkCheckOptions& options;
  asio::io_context io;
  asio::signal_set signals{io, SIGINT, SIGTERM};
  asio::steady_timer tick_timer{io};
  NodeSessions sessions;
  NodeListener listener;
  NodeDatagrams datagrams{io, sessions};
  HeartbeatMonitor heartbeats{options.config.heartbeat_ms};
  std::vector<std::shared_ptr<const std::vector<std::uint8_t>>> fill = encode_fill(options.fill_bytes);

  /// Per configured node (by name): its measurement, and its check under way.
  std::map<std::string, LinkMeasurement> results;
  struct Running {
    std::uint32_t session = 0;
    Clock::time_point fill_due, give_up;
    bool filling = false;
  };
  std::map<std::string, Running> running;
  Clock::time_point started = Clock::now(), next_heartbeat = started;
  bool stopping = false;

  LinkChecker(const LinkCheckOptions& o, SharedSecret secret)
      : options(o),
        listener(
            io, sessions, std::move(secret), options.config.name,
            [this](std::uint32_t id, Message&& m) { on_message(id, std::move(m)); },
            [this](std::uint32_t id, const std::string& reason) { on_closed(id, reason); }) {
    for (const ClusterNodeConfig& node : options.config.nodes) {
      LinkMeasurement& m = results[node.name];
      m.node = node.name;
      m.problem = cat("nothing connected as '", node.name, "' within ", seconds(options.wait_for_nodes),
                      " s (is its service running? docs/cluster.md, \"A node as a service\")");
    }
  }

  void on_message(std::uint32_t id, Message&& message) {
    NodeSession* s = sessions.find(id);
    if (s == nullptr) return;
    try {
      if (s->state == NodeSession::State::handshake) {
        sessions.on_handshake_message(*s, message, options.config, 0);
        if (s->state != NodeSession::State::handshake && s->role == PeerRole::node) start(*s);
        return;
      }
    } catch (const HandshakeError& e) {
      sessions.refuse(*s, e.reason(), e.what());
      return;
    }
    if (const auto* report = std::get_if<LinkReport>(&message)) {
      on_report(*s, *report);
    } else if (const auto* goodbye = std::get_if<Goodbye>(&message)) {
      s->connection->close(cat("Goodbye: ", core::escaped(goodbye->reason)));
    } else if (!std::holds_alternative<Heartbeat>(message) && !std::holds_alternative<TableReady>(message) &&
               !std::holds_alternative<RenderDone>(message)) {
      s->close_for_protocol_violation(cat(to_string(message_type(message)), " is not sent by nodes"));
    }
  }

  /// A node authenticated: its pings now, its fill after the duration.
  void start(NodeSession& s) {
    LinkMeasurement& m = results[s.name];
    if (m.reported) return;  // a node that reconnects after its report is not checked again
    m.connected = true;
    m.address = s.connection->peer();
    m.problem = "the check did not finish";
    const auto now = Clock::now();
    running[s.name] = {s.id, now + options.duration, now + options.duration + options.fill_timeout, false};
    s.link_check_pings.emplace();
    s.connection->send(LinkCheck{static_cast<std::uint32_t>(options.duration.count()),
                                 static_cast<std::uint32_t>(options.ping_interval.count()), options.fill_bytes});
    spdlog::info("check: node '{}' connected from {}: pinging for {:.1f} s", s.name, m.address,
                 seconds(options.duration));
  }

  void on_report(NodeSession& s, const LinkReport& r) {
    const auto it = running.find(s.name);
    if (it == running.end() || it->second.session != s.id) {
      s.close_for_protocol_violation("LinkReport without a LinkCheck");
      return;
    }
    LinkMeasurement& m = results[s.name];
    m.reported = true;
    m.problem.clear();
    m.pings_sent = r.pings_sent;
    m.pongs = r.pongs_received;
    // The master's count: the distinct pings it heard that the node sent during the check.
    const std::set<std::uint64_t>& heard = *s.link_check_pings;
    m.pings_heard = static_cast<std::uint32_t>(std::count_if(
        heard.begin(), heard.end(), [&](std::uint64_t t) { return t >= r.first_ping_ns && t <= r.last_ping_ns; }));
    m.pings_heard = std::max(m.pings_heard, m.pongs);  // every pong answered a ping heard
    m.round_trip_min_ms = ms_of_ns(r.round_trip_min_ns);
    m.round_trip_p50_ms = ms_of_ns(r.round_trip_p50_ns);
    m.round_trip_p99_ms = ms_of_ns(r.round_trip_p99_ns);
    m.round_trip_max_ms = ms_of_ns(r.round_trip_max_ns);
    m.clock_uncertainty_ms = ms_of_ns(r.clock_uncertainty_ns);
    m.clock_drift_ppm = r.clock_drift_ppm;
    m.clock_steps = r.clock_steps;
    m.clock_offset_ms = (static_cast<double>(r.master_steady_ns) - static_cast<double>(r.node_steady_ns)) / 1e6;
    // The master's wall clock when its steady clock read master_steady_ns (the
    // node's estimate of the report's moment), against the node's wall clock then.
    const core::WallAtSteady clocks = core::wall_at_steady();
    const double master_wall_ns = static_cast<double>(clocks.wall_ns) - static_cast<double>(clocks.steady_ns) +
                                  static_cast<double>(r.master_steady_ns);
    m.wall_clock_offset_ms = (static_cast<double>(r.node_wall_ns) - master_wall_ns) / 1e6;
    m.fill_bytes = r.fill_bytes;
    m.fill_seconds = static_cast<double>(r.fill_ns) / 1e9;
    if (r.fill_timed_bytes > 0 && r.fill_ns > 0)
      m.throughput_bits_per_s = 8.0 * static_cast<double>(r.fill_timed_bytes) / m.fill_seconds;
    s.link_check_pings.reset();
    running.erase(it);
    spdlog::info("check: node '{}' reported", s.name);
    s.connection->send(Goodbye{"link check done"});
    s.connection->close_after_flush("link check done");
    if (finished(Clock::now())) stop("every node reported");
  }

  void on_closed(std::uint32_t id, const std::string& reason) {
    const std::shared_ptr<NodeSession> s = sessions.take(id);
    if (s == nullptr) return;
    asio::post(io, [keep = s] {});  // released once the connection's handlers returned
    if (s->state == NodeSession::State::handshake || s->role != PeerRole::node) return;
    const auto it = running.find(s->name);
    if (it == running.end() || it->second.session != id) return;
    running.erase(it);
    results[s->name].problem = cat("the connection closed during the check: ", reason);
    if (!stopping) spdlog::warn("check: node '{}': the connection closed during the check: {}", s->name, reason);
  }

  /// Whether nothing more can come: every node reported, or nothing runs and the wait for nodes is over.
  bool finished(Clock::time_point now) const {
    const bool all_reported =
        std::all_of(results.begin(), results.end(), [](const auto& r) { return r.second.reported; });
    return all_reported || (running.empty() && now - started >= options.wait_for_nodes);
  }

  void tick() {
    const auto now = Clock::now();
    if (now >= next_heartbeat) {
      sessions.check_heartbeats(heartbeats, now);
      next_heartbeat = now + std::chrono::milliseconds(heartbeats.interval_ms());
    }
    for (auto& [name, r] : running) {
      NodeSession* s = sessions.find(r.session);
      if (s == nullptr) continue;
      if (!r.filling && now >= r.fill_due) {
        r.filling = true;
        for (const auto& frame : fill) s->connection->send_encoded(frame);
      }
    }
    for (auto it = running.begin(); it != running.end();) {
      if (now < it->second.give_up) {
        ++it;
        continue;
      }
      results[it->first].problem =
          cat("no report within ", std::chrono::duration<double>(options.duration + options.fill_timeout).count(),
              " s (the fill of ", options.fill_bytes, " bytes did not arrive: under ",
              8.0 * static_cast<double>(options.fill_bytes) / 1e6 / seconds(options.fill_timeout),
              " Mbit/s, or the link is cut)");
      spdlog::warn("check: node '{}': {}", it->first, results[it->first].problem);
      if (NodeSession* s = sessions.find(it->second.session)) s->connection->close("no link report in time");
      it = running.erase(it);
    }
    if (finished(now)) return stop("done");
    tick_timer.expires_after(std::chrono::milliseconds(5));
    tick_timer.async_wait([this](const boost::system::error_code& ec) {
      if (!ec && !stopping) tick();
    });
  }

  void stop(const std::string& reason) {
    if (stopping) return;
    stopping = true;
    spdlog::info("check: {}", reason);
    listener.close();
    datagrams.close();
    tick_timer.cancel();
    boost::system::error_code ignored;
    signals.cancel(ignored);
    sessions.say_goodbye("link check done");
  }

  std::vector<LinkMeasurement> run() {
    const std::uint16_t port = options.port.value_or(options.config.master_port);
    listener.listen(options.config.master_host, port);
    datagrams.open(options.config.master_host, port);
    listener.limit_unauthenticated(options.config.max_unauthenticated_connections);
    listener.start();
    spdlog::info("check: cluster '{}': listening on {}:{} for {} node{}", options.config.name,
                 options.config.master_host, port, options.config.nodes.size(),
                 options.config.nodes.size() == 1 ? "" : "s");
    if (options.on_listening) options.on_listening();
    signals.async_wait([this](const boost::system::error_code& ec, int) {
      if (!ec) stop("stopped by a signal");
    });
    tick();
    io.run();
    std::vector<LinkMeasurement> out;
    for (const ClusterNodeConfig& node : options.config.nodes) out.push_back(results[node.name]);
    return out;
  }
};

std::vector<LinkMeasurement> check_links(const LinkCheckOptions& options, SharedSecret secret) {
  LinkChecker checker(options, std::move(secret));
  return checker.run();
}

}  // namespace zenith::cluster
