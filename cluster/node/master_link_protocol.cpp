#include "cluster/node/master_link_protocol.h"

#include <stdexcept>
#include <utility>

#include "cluster/cluster_config.h"
#include "core/json_reader.h"

namespace zenith::cluster {

MasterLinkProtocol::MasterLinkProtocol(SharedSecret secret, std::string cluster_name, std::string node_name,
                                       std::uint32_t heartbeat_ms, std::uint32_t connect_timeout_ms)
    : secret_(std::move(secret)),
      cluster_name_(std::move(cluster_name)),
      node_name_(std::move(node_name)),
      heartbeat_ms_(heartbeat_ms),
      connect_timeout_ms_(connect_timeout_ms) {}

Hello MasterLinkProtocol::start() {
  handshake_.emplace(secret_, cluster_name_, node_name_);
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
    heartbeat_ms_ = w->heartbeat_interval_ms;
    return {Meaning::welcomed, std::nullopt};
  }
  if (std::holds_alternative<Reject>(message)) return {Meaning::rejected, std::nullopt};
  if (std::holds_alternative<Goodbye>(message)) return {Meaning::goodbye, std::nullopt};
  throw std::runtime_error(config::cat(to_string(message_type(message)), " from the master before Welcome"));
}

double MasterLinkProtocol::silence_limit_ms() const {
  return welcomed_ ? cluster::silence_limit_ms(heartbeat_ms_) : static_cast<double>(connect_timeout_ms_);
}

MasterLinkProtocol::Tick MasterLinkProtocol::tick(Clock::time_point last_received, Clock::time_point now) const {
  if (std::chrono::duration<double, std::milli>(now - last_received).count() > silence_limit_ms())
    return Tick::master_gone;
  return welcomed_ ? Tick::send_heartbeat : Tick::wait;
}

}  // namespace zenith::cluster
