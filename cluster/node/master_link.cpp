#include "cluster/node/master_link.h"

#include <spdlog/spdlog.h>

#include <boost/asio/connect.hpp>

#include "cluster/heartbeat.h"
#include "core/json_reader.h"
#include "core/timing.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::tcp;
using config::cat;  // core/json_reader.h
using core::ms_since;
using std::chrono::milliseconds;

MasterLink::MasterLink(asio::io_context& io, const NodeOptions& options, SharedSecret secret, Events events)
    : io_(io),
      options_(options),
      events_(std::move(events)),
      protocol_(std::move(secret), options.config.name, options.node_name, options.config.heartbeat_ms,
                options.connect_timeout_ms),
      port_(options.port.value_or(options.config.master_port)),
      master_address_(cat(options.config.master_host, ":", port_)),
      heartbeat_timer_(io),
      retry_timer_(io) {}

void MasterLink::start() {
  connect_started_ = std::chrono::steady_clock::now();
  connect();
}

void MasterLink::connect() {
  auto socket = std::make_shared<tcp::socket>(io_);
  tcp::resolver resolver(io_);
  boost::system::error_code ec;
  const auto endpoints = resolver.resolve(options_.config.master_host, std::to_string(port_), ec);
  if (ec) {
    spdlog::error("node '{}': cannot resolve the master's host {}: {}", options_.node_name, master_address_,
                  ec.message());
    events_.ended(kNodeExitMasterLost);
    return;
  }
  asio::async_connect(*socket, endpoints, [this, socket](const boost::system::error_code& e, const tcp::endpoint&) {
    if (stopping_) return;
    if (e) {
      if (ms_since(connect_started_) > options_.connect_timeout_ms) {
        spdlog::error("node '{}': cannot reach the master at {} within {} ms ({}): exiting", options_.node_name,
                      master_address_, options_.connect_timeout_ms, e.message());
        events_.ended(kNodeExitMasterLost);
        return;
      }
      retry_timer_.expires_after(milliseconds(200));
      retry_timer_.async_wait([this](const boost::system::error_code& te) {
        if (!te && !stopping_) connect();
      });
      return;
    }
    on_connected(std::move(*socket));
  });
}

void MasterLink::on_connected(tcp::socket socket) {
  connection_ = std::make_shared<Connection>(std::move(socket), cat("master ", master_address_));
  connection_->start([this](Message&& m) { on_message(std::move(m)); },
                     [this](const std::string& reason) { on_closed(reason); });
  connection_->send(protocol_.start());
  spdlog::info("node '{}': connected to the master at {}", options_.node_name, master_address_);
  heartbeat_tick();
}

void MasterLink::on_closed(const std::string& reason) {
  if (stopping_) return;
  spdlog::error("node '{}': lost the connection to the master at {} without a Goodbye ({}): the master is gone; "
                "exiting",
                options_.node_name, master_address_, reason);
  events_.ended(kNodeExitMasterLost);
}

bool MasterLink::send(const Message& message) {
  if (stopping_ || !connection_) return false;
  connection_->send(message);
  return true;
}

void MasterLink::say_goodbye(const std::string& reason) {
  if (connection_ && connection_->is_open()) {
    connection_->send(Goodbye{reason.substr(0, kMaxReasonBytes)});
    stopping_ = true;  // the close handler must not report a lost master
    connection_->close_after_flush(reason);
  }
}

void MasterLink::stop() {
  stopping_ = true;
  heartbeat_timer_.cancel();
  retry_timer_.cancel();
  if (connection_ && connection_->is_open()) connection_->close_after_flush("node stopping");
}

void MasterLink::end(const std::string& close_reason, int exit_code) {
  stopping_ = true;
  connection_->close(close_reason);
  events_.ended(exit_code);
}

void MasterLink::on_message(Message&& message) {
  if (stopping_) return;
  using Meaning = MasterLinkProtocol::Meaning;
  try {
    const bool welcomed = protocol_.welcomed();
    MasterLinkProtocol::Step step = protocol_.on_message(message);
    switch (step.meaning) {
      case Meaning::reply:
        connection_->send(*step.reply);
        break;
      case Meaning::welcomed: {
        const Welcome& w = std::get<Welcome>(message);
        spdlog::info("node '{}': welcomed by the master as id {} at frame {} (heartbeat {} ms, barrier timeout {} ms)",
                     options_.node_name, w.node_id, w.current_frame, w.heartbeat_interval_ms, w.barrier_timeout_ms);
        events_.welcomed(w);
        break;
      }
      case Meaning::work:
        events_.message(message);
        break;
      case Meaning::heartbeat:
        break;
      case Meaning::rejected: {
        const Reject& r = std::get<Reject>(message);
        spdlog::error("node '{}': the master refused the connection ({}): {}", options_.node_name,
                      static_cast<int>(r.reason), r.text);
        end("rejected", kNodeExitRefused);
        break;
      }
      case Meaning::goodbye: {
        const Goodbye& g = std::get<Goodbye>(message);
        if (welcomed) {
          spdlog::info("node '{}': the master said goodbye: {}", options_.node_name, g.reason);
          end("goodbye", kNodeExitDone);
        } else {
          spdlog::error("node '{}': the master said goodbye during the handshake: {}", options_.node_name, g.reason);
          end("goodbye", kNodeExitRefused);
        }
        break;
      }
    }
  } catch (const HandshakeError& e) {
    spdlog::error("node '{}': the master at {} failed to authenticate: {}", options_.node_name, master_address_,
                  e.what());
    say_goodbye(cat("authentication failed: ", e.what()));
    events_.ended(kNodeExitRefused);
  } catch (const std::exception& e) {
    spdlog::error("node '{}': closing the connection to the master: {}", options_.node_name, e.what());
    say_goodbye(cat("error: ", e.what()));
    events_.ended(kNodeExitFailed);
  }
}

void MasterLink::heartbeat_tick() {
  if (stopping_ || !connection_) return;
  const auto now = std::chrono::steady_clock::now();
  switch (protocol_.tick(connection_->last_received(), now)) {
    case MasterLinkProtocol::Tick::master_gone:
      // Before Welcome the master may still be preparing tables: the connect timeout applies.
      spdlog::error("node '{}': nothing from the master at {} for {:.0f} ms{}: the master is gone; exiting",
                    options_.node_name, master_address_, protocol_.silence_limit_ms(),
                    protocol_.welcomed() ? "" : " (no Welcome)");
      end("heartbeat timeout", kNodeExitMasterLost);
      return;
    case MasterLinkProtocol::Tick::send_heartbeat:
      connection_->send(heartbeat_at(now));
      break;
    case MasterLinkProtocol::Tick::wait:
      break;
  }
  heartbeat_timer_.expires_after(milliseconds(protocol_.heartbeat_ms()));
  heartbeat_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) heartbeat_tick();
  });
}

}  // namespace zenith::cluster
