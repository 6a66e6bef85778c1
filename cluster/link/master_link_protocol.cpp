#include "cluster/link/master_link_protocol.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "cluster/link/cluster_config.h"
#include "core/strings.h"

namespace zenith::cluster {

using std::chrono::milliseconds;

std::vector<MasterAddress> listed_masters(const ClusterConfig& config, std::optional<std::uint16_t> port) {
  std::vector<MasterAddress> masters = {{config.master_host, port.value_or(config.master_port)}};
  if (config.standby) masters.push_back(*config.standby);
  return masters;
}

std::uint32_t attempt_timeout_ms_for(std::size_t masters) { return masters > 1 ? 3000 : 0; }

MasterLinkProtocol::MasterLinkProtocol(SharedSecret secret, std::string cluster_name, std::string node_name,
                                       std::uint32_t heartbeat_ms, ReconnectRules rules, std::size_t masters,
                                       PeerRole role)
    : secret_(std::move(secret)),
      cluster_name_(std::move(cluster_name)),
      node_name_(std::move(node_name)),
      heartbeat_ms_(heartbeat_ms),
      rules_(rules),
      masters_(std::max<std::size_t>(masters, 1)),
      role_(role) {}

void MasterLinkProtocol::begin(Clock::time_point now) {
  welcomed_ = false;
  reconnecting_ = false;
  failed_attempts_ = 0;
  failed_rounds_ = 0;
  master_index_ = 0;
  deadline_ = now + milliseconds(rules_.connect_timeout_ms);
}

std::optional<milliseconds> MasterLinkProtocol::attempt_limit() const {
  if (!reconnecting_ || rules_.attempt_timeout_ms == 0) return std::nullopt;
  return milliseconds(rules_.attempt_timeout_ms);
}

Hello MasterLinkProtocol::start() {
  handshake_.emplace(secret_, cluster_name_, node_name_, role_, instance_id_);
  welcomed_ = false;
  return handshake_->start();
}

MasterLinkProtocol::Step MasterLinkProtocol::on_message(const Message& message) {
  if (welcomed_) {
    if (std::holds_alternative<Heartbeat>(message)) return {Meaning::heartbeat, std::nullopt};
    if (std::holds_alternative<Goodbye>(message)) return {Meaning::goodbye, std::nullopt};
    return {Meaning::work, std::nullopt};
  }
  if (!handshake_) throw std::logic_error("MasterLinkProtocol: a message before start()");
  if (const auto* c = std::get_if<Challenge>(&message)) return {Meaning::reply, Message{handshake_->on_challenge(*c)}};
  if (const auto* w = std::get_if<Welcome>(&message)) {
    handshake_->on_welcome(*w);  // throws when the master does not know the secret
    welcomed_ = true;
    if (ever_welcomed_) ++rejoins_;
    ever_welcomed_ = true;
    // Success: the attempts and the deadline start afresh at the next loss.
    reconnecting_ = false;
    failed_attempts_ = 0;
    failed_rounds_ = 0;
    heartbeat_ms_ = w->heartbeat_interval_ms;
    return {Meaning::welcomed, std::nullopt};
  }
  if (std::holds_alternative<Reject>(message)) return {Meaning::rejected, std::nullopt};
  if (std::holds_alternative<Goodbye>(message)) return {Meaning::goodbye, std::nullopt};
  throw std::runtime_error(core::cat(to_string(message_type(message)), " from the master before Welcome"));
}

double MasterLinkProtocol::silence_limit_ms() const { return cluster::silence_limit_ms(heartbeat_ms_); }

MasterLinkProtocol::Tick MasterLinkProtocol::tick(Clock::time_point last_received, Clock::time_point now) const {
  if (!welcomed_) return now > deadline_ ? Tick::silent : Tick::wait;
  if (std::chrono::duration<double, std::milli>(now - last_received).count() > silence_limit_ms()) return Tick::silent;
  return Tick::send_heartbeat;
}

MasterLinkProtocol::Retry MasterLinkProtocol::connection_failed(Clock::time_point now) {
  if (welcomed_) {  // a loss: the reconnect time starts now
    welcomed_ = false;
    reconnecting_ = true;
    failed_attempts_ = 0;
    failed_rounds_ = 0;
    master_index_ = 0;  // the active master first again
    deadline_ = now + milliseconds(rules_.reconnect_ms);
    if (rules_.reconnect_ms == 0) return {true, milliseconds(0)};
    return {false, milliseconds(0)};
  }
  ++failed_attempts_;
  if (now >= deadline_) return {true, milliseconds(0)};
  if (master_index_ + 1 < masters_) {  // the next listed master, at once
    ++master_index_;
    return {false, milliseconds(0)};
  }
  master_index_ = 0;
  ++failed_rounds_;
  const double nominal = static_cast<double>(backoff(rules_, failed_rounds_).count());
  const auto wait =
      milliseconds(static_cast<std::int64_t>(nominal * jitter_factor(rules_, node_name_, failed_rounds_)));
  const auto left = std::chrono::duration_cast<milliseconds>(deadline_ - now);
  // The last attempt is made at the deadline, not after it.
  return {false, std::min(wait, left)};
}

milliseconds MasterLinkProtocol::backoff(const ReconnectRules& rules, std::uint32_t failed) {
  std::uint64_t wait = rules.first_retry_ms;
  for (std::uint32_t i = 1; i < failed && wait < rules.max_retry_ms; ++i) wait *= 2;
  return milliseconds(std::min<std::uint64_t>(wait, rules.max_retry_ms));
}

double MasterLinkProtocol::jitter_factor(const ReconnectRules& rules, const std::string& node_name,
                                         std::uint32_t failed) {
  // FNV-1a of the name and the attempt: the same for a node and attempt, spread across nodes.
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&h](std::uint8_t byte) {
    h ^= byte;
    h *= 1099511628211ull;
  };
  for (const char c : node_name) mix(static_cast<std::uint8_t>(c));
  for (int i = 0; i < 4; ++i) mix(static_cast<std::uint8_t>(failed >> (8 * i)));
  h ^= h >> 33;                                                         // spread the low bits
  const double unit = static_cast<double>(h % 1000001ull) / 1000000.0;  // [0, 1]
  return 1.0 - rules.jitter + 2.0 * rules.jitter * unit;
}

}  // namespace zenith::cluster
