#include "cluster/master/node_sessions.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cluster/protocol/heartbeat.h"
#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

namespace {

/// "1a2b3c4d5e6f7a8b": an instance id for messages.
std::string instance_text(std::uint64_t id) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(id));
  return text;
}

}  // namespace

double duplicate_alive_ms(std::uint32_t heartbeat_ms) { return std::max(2000.0, 2.0 * heartbeat_ms); }

NodeSession& NodeSessions::add(std::shared_ptr<Connection> connection, MasterHandshake handshake) {
  auto session = std::make_shared<NodeSession>();
  session->id = next_id_++;
  session->handshake.emplace(std::move(handshake));
  session->connection = std::move(connection);
  NodeSession& added = *session;
  sessions_.emplace(added.id, std::move(session));
  return added;
}

NodeSession* NodeSessions::find(Id id) {
  auto it = sessions_.find(id);
  return it == sessions_.end() ? nullptr : it->second.get();
}

std::shared_ptr<NodeSession> NodeSessions::take(Id id) {
  auto it = sessions_.find(id);
  if (it == sessions_.end()) return nullptr;
  std::shared_ptr<NodeSession> taken = std::move(it->second);
  sessions_.erase(it);
  return taken;
}

std::vector<NodeSessions::Id> NodeSessions::ids() const {
  std::vector<Id> ids;
  for (const auto& [id, session] : sessions_) ids.push_back(id);
  return ids;
}

std::vector<NodeSessions::Id> NodeSessions::handshake_ids() const {
  std::vector<Id> waiting;
  for (const auto& [id, session] : sessions_)
    if (session->state == NodeSession::State::handshake && session->connection->is_open()) waiting.push_back(id);
  return waiting;
}

std::vector<NodeSessions::Id> NodeSessions::ready_ids() const {
  std::vector<Id> ready;
  for (const auto& [id, session] : sessions_)
    if (session->state == NodeSession::State::ready && session->connection->is_open()) ready.push_back(id);
  return ready;
}

std::size_t NodeSessions::ready_count() const {
  return static_cast<std::size_t>(std::count_if(
      sessions_.begin(), sessions_.end(), [](const auto& p) { return p.second->state == NodeSession::State::ready; }));
}

void NodeSessions::send_to_standbys(const std::shared_ptr<const std::vector<std::uint8_t>>& frame) {
  for (auto& [id, session] : sessions_)
    if (session->role == PeerRole::standby && session->inventory_done && session->connection->is_open())
      session->connection->send_encoded(frame);
}

void NodeSessions::refuse(NodeSession& session, RejectReason reason, const std::string& text) {
  // Per reason: a flood of wrong secrets does not hide the first duplicate name.
  if (const std::optional<std::string> more =
          refusals_.admit(std::to_string(static_cast<int>(reason)), core::LogLimiter::Clock::now()))
    spdlog::warn("master: refused {}: {}{}", session.who(), core::escaped(text, 1024), *more);
  session.refuse(reason, text, false);
}

void NodeSessions::on_handshake_message(NodeSession& s, const Message& message, const ClusterConfig& config,
                                        std::uint64_t current_frame, std::chrono::steady_clock::time_point now) {
  if (const auto* hello = std::get_if<Hello>(&message)) {
    s.name = hello->node_name;
    s.role = hello->role;
    s.instance_id = hello->instance_id;
    const Challenge challenge = s.handshake->on_hello(*hello);  // wrong cluster / version
    if (hello->role == PeerRole::standby) {
      if (!config.standby)
        throw HandshakeError(RejectReason::wrong_role, cat("standby '", hello->node_name, "': the cluster config ",
                                                           config.source, " has no standby"));
      if (hello->node_name != standby_name(*config.standby))
        throw HandshakeError(
            RejectReason::wrong_role,
            cat("standby '", hello->node_name, "' is not this cluster's standby ('", standby_name(*config.standby),
                "' in ", config.source, "): do the master and the standby read the same cluster config?"));
    } else if (config.find_node(hello->node_name) == nullptr) {
      throw HandshakeError(RejectReason::unspecified,
                           cat("node '", hello->node_name, "' is not in the cluster config ", config.source));
    }
    s.connection->send(challenge);
  } else if (const auto* auth = std::get_if<Authenticate>(&message)) {
    s.handshake->on_authenticate(*auth);  // wrong secret → HandshakeError
    // A node that reconnects (the same process: its instance id) replaces its
    // old connection; another process with a name already connected is
    // refused while that connection is alive — two nodes never fight over a
    // name — and replaces one that fell silent (a machine that died).
    for (auto& [other_id, other] : sessions_) {
      if (other_id == s.id || other->name != s.name || other->state == NodeSession::State::handshake ||
          !other->connection->is_open())
        continue;
      const double silent_ms =
          std::chrono::duration<double, std::milli>(now - other->connection->last_received()).count();
      if (other->instance_id != s.instance_id && silent_ms < duplicate_alive_ms(config.heartbeat_ms))
        throw HandshakeError(
            RejectReason::duplicate_node,
            cat(to_string(s.role), " '", s.name, "' is already connected from ", other->connection->peer(),
                " (another process: instance ", instance_text(other->instance_id), ", this one ",
                instance_text(s.instance_id), "): refused; stop the other process, or give this one another name"));
      spdlog::warn(
          "master: {} '{}' reconnected from {}: closing its old connection{}", to_string(s.role),
          core::escaped(s.name, 64), s.connection->peer(),
          other->instance_id == s.instance_id
              ? std::string()
              : cat(" (another process, but the old connection was silent for ", std::lround(silent_ms), " ms)"));
      other->connection->close("replaced by a new connection of the same node");
      break;
    }
    s.connection->send(s.handshake->welcome(
        s.id, current_frame, config.heartbeat_ms, config.barrier_timeout_ms,
        static_cast<std::uint64_t>(
            std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count())));
    s.datagram_key = s.handshake->datagram_key();
    s.state = NodeSession::State::tables;
    s.connection->lift_payload_limit();  // it proved the secret: table sets and thumbnails may follow
    if (s.role == PeerRole::standby)
      spdlog::info(
          "master: the standby master '{}' authenticated from {} (id {}): it follows every table version "
          "and frame",
          s.name, s.connection->peer(), s.id);
    else
      spdlog::info("master: node '{}' authenticated from {} (id {}); waiting for its table inventory", s.name,
                   s.connection->peer(), s.id);
  } else if (std::holds_alternative<Goodbye>(message)) {
    s.connection->close(cat("Goodbye during the handshake: ", core::escaped(std::get<Goodbye>(message).reason)));
  } else {
    throw HandshakeError(RejectReason::protocol_error,
                         cat(to_string(message_type(message)), " before the handshake completed"));
  }
}

void NodeSessions::check_heartbeats(const HeartbeatMonitor& monitor, std::chrono::steady_clock::time_point now) {
  auto encoded = std::make_shared<const std::vector<std::uint8_t>>(encode(heartbeat_at(now)));
  for (const Id id : ids()) {
    NodeSession* s = find(id);
    if (s == nullptr || !s->connection->is_open()) continue;
    switch (monitor.check(s->state == NodeSession::State::handshake, s->connected_at, s->connection->last_received(),
                          now)) {
      case HeartbeatMonitor::Verdict::awaiting_handshake: break;
      case HeartbeatMonitor::Verdict::handshake_overdue:
        spdlog::warn("master: closing {}: no handshake within {:.0f} ms", s->who(), monitor.handshake_limit_ms());
        s->connection->close("handshake timeout");
        break;
      case HeartbeatMonitor::Verdict::silent:
        spdlog::warn("master: closing {}: nothing received for {:.0f} ms", s->who(), monitor.silence_limit_ms());
        s->connection->close("heartbeat timeout");
        break;
      case HeartbeatMonitor::Verdict::send_heartbeat: s->connection->send_encoded(encoded); break;
    }
  }
}

void NodeSessions::say_goodbye(const std::string& reason) {
  // Closing may erase a session (its close handler): work on a copy.
  std::vector<std::pair<std::shared_ptr<Connection>, bool>> connections;
  for (const auto& [id, s] : sessions_)
    connections.emplace_back(s->connection, s->state == NodeSession::State::handshake);
  for (auto& [connection, in_handshake] : connections) {
    if (in_handshake)
      connection->send(Reject{RejectReason::shutting_down, "the master is stopping"});
    else
      connection->send(Goodbye{reason});
    connection->close_after_flush("master stopping");
  }
}

}  // namespace zenith::cluster
