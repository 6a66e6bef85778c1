#include "cluster/link/master_link.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <boost/asio/connect.hpp>

#include "cluster/protocol/heartbeat.h"
#include "core/strings.h"
#include "core/timing.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::tcp;
using core::cat;
using core::ms_since;
using std::chrono::milliseconds;

MasterLink::MasterLink(asio::io_context& io, Setup setup, SharedSecret secret, Events events)
    : io_(io),
      setup_(std::move(setup)),
      events_(std::move(events)),
      protocol_(std::move(secret), setup_.cluster_name, setup_.peer_name, setup_.heartbeat_ms, setup_.rules,
                setup_.masters.size(), setup_.role),
      heartbeat_timer_(io),
      retry_timer_(io),
      attempt_timer_(io) {
  if (setup_.masters.empty()) throw std::invalid_argument("MasterLink: no master to connect to");
}

std::string MasterLink::master_address() const { return setup_.masters.at(protocol_.master_index()).text(); }

std::string MasterLink::listed() const {
  std::string text;
  for (const MasterAddress& m : setup_.masters) text += cat(text.empty() ? "" : ", ", m.text());
  return text;
}

void MasterLink::start() {
  connect_started_ = std::chrono::steady_clock::now();
  protocol_.begin(connect_started_);
  connect();
}

void MasterLink::connect() {
  const std::uint64_t generation = ++generation_;
  const MasterAddress& master = setup_.masters.at(protocol_.master_index());
  if (const std::optional<milliseconds> limit = protocol_.attempt_limit()) {
    attempt_timer_.expires_after(*limit);
    attempt_timer_.async_wait([this, generation, limit](const boost::system::error_code& te) {
      if (te || stopping_ || generation != generation_ || protocol_.welcomed()) return;
      connection_failed(fmt::format("no Welcome within {:.1f} s", static_cast<double>(limit->count()) / 1000.0));
    });
  }
  auto socket = std::make_shared<tcp::socket>(io_);
  connecting_ = socket;
  tcp::resolver resolver(io_);
  boost::system::error_code ec;
  const auto endpoints = resolver.resolve(master.host, std::to_string(master.port), ec);
  if (ec) {  // a name server may be unreachable for a while too: an attempt that failed
    connection_failed(cat("cannot resolve the master's host: ", ec.message()));
    return;
  }
  asio::async_connect(*socket, endpoints,
                      [this, socket, generation](const boost::system::error_code& e, const tcp::endpoint&) {
                        if (stopping_ || generation != generation_) return;
                        connecting_.reset();
                        if (e) {
                          connection_failed(e.message());
                          return;
                        }
                        on_connected(std::move(*socket));
                      });
}

void MasterLink::on_connected(tcp::socket socket) {
  const std::uint64_t generation = generation_;
  connection_ = std::make_shared<Connection>(std::move(socket), cat("master ", master_address()));
  connection_->start(
      [this, generation](Message&& m) {
        if (generation == generation_) on_message(std::move(m));
      },
      [this, generation](const std::string& reason) {
        if (generation == generation_) on_closed(reason);
      });
  connection_->send(protocol_.start());
  if (protocol_.reconnecting())
    spdlog::info("{}: connected to the master at {} again after {:.1f} s; authenticating", setup_.who, master_address(),
                 ms_since(lost_at_) / 1000.0);
  else
    spdlog::info("{}: connected to the master at {}", setup_.who, master_address());
  heartbeat_tick(generation);
}

void MasterLink::on_closed(const std::string& reason) {
  if (stopping_) return;
  connection_failed(protocol_.welcomed() ? cat("the connection closed without a Goodbye: ", reason)
                                         : cat("closed before Welcome: ", reason));
}

void MasterLink::connection_failed(const std::string& reason) {
  abandon_connect();  // a master whose machine dropped off the network never answers the SYN
  const bool was_welcomed = protocol_.welcomed();
  ++generation_;  // the handlers and timers of this connection do nothing any more
  heartbeat_timer_.cancel();
  attempt_timer_.cancel();
  const std::string address = master_address();  // the master that failed (the protocol moves on below)
  if (connection_) {
    connection_->close(reason);
    connection_.reset();
  }
  const auto now = std::chrono::steady_clock::now();
  const MasterLinkProtocol::Retry retry = protocol_.connection_failed(now);
  last_failure_ = reason;
  if (was_welcomed) {
    lost_at_ = now;
    if (retry.give_up) {  // reconnect time 0
      spdlog::error(
          "{}: lost the connection to the master at {} ({}); reconnecting is off "
          "(reconnect time 0): the master is gone; exiting",
          setup_.who, address, reason);
      events_.ended(kNodeExitMasterLost);
      return;
    }
    if (setup_.role == PeerRole::node)
      spdlog::warn(
          "{}: lost the connection to the master at {} ({}): keeping the last frame, reconnecting for "
          "up to {:.0f} s{}",
          setup_.who, address, reason, protocol_.rules().reconnect_ms / 1000.0,
          setup_.masters.size() > 1 ? cat(" (the listed masters in order: ", listed(), ")") : std::string());
    else
      spdlog::warn("{}: lost the connection to the active master at {} ({})", setup_.who, address, reason);
    events_.lost(reason);
    if (stopping_) return;  // the node stopped on the news
  } else if (retry.give_up) {
    if (protocol_.reconnecting())
      spdlog::error(
          "{}: could not reconnect to the master at {} within {:.0f} s ({} attempts; last: {}): "
          "the master is gone; exiting",
          setup_.who, listed(), protocol_.rules().reconnect_ms / 1000.0, protocol_.failed_attempts() + 1, reason);
    else
      spdlog::error("{}: cannot reach the master at {} within {} ms ({}): exiting", setup_.who, listed(),
                    protocol_.rules().connect_timeout_ms, reason);
    events_.ended(kNodeExitMasterLost);
    return;
  } else {
    spdlog::debug("{}: attempt to reach the master at {} failed ({}); next: {} in {} ms", setup_.who, address, reason,
                  master_address(), retry.delay.count());
    if (events_.attempt_failed) {
      events_.attempt_failed(reason);
      if (stopping_) return;  // stopped on the news
    }
  }
  const std::uint64_t generation = generation_;
  retry_timer_.expires_after(retry.delay);
  retry_timer_.async_wait([this, generation](const boost::system::error_code& te) {
    if (!te && !stopping_ && generation == generation_) connect();
  });
}

bool MasterLink::send(const Message& message) {
  if (stopping_ || !connection_ || !protocol_.welcomed()) return false;
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

void MasterLink::abandon_connect() {
  if (!connecting_) return;
  boost::system::error_code ignored;
  connecting_->close(ignored);  // its async_connect ends now (operation_aborted), not after the kernel's SYN retries
  connecting_.reset();
}

void MasterLink::stop() {
  stopping_ = true;
  heartbeat_timer_.cancel();
  retry_timer_.cancel();
  attempt_timer_.cancel();
  abandon_connect();
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
    const bool rejoining = protocol_.reconnecting();
    MasterLinkProtocol::Step step = protocol_.on_message(message);
    switch (step.meaning) {
      case Meaning::reply: connection_->send(*step.reply); break;
      case Meaning::welcomed: {
        const Welcome& w = std::get<Welcome>(message);
        if (rejoining)
          spdlog::info(
              "{}: welcomed again by the master at {} as id {} at frame {} {:.1f} s after the loss "
              "(rejoin {}): it rejoins at a frame boundary",
              setup_.who, master_address(), w.node_id, w.current_frame, ms_since(lost_at_) / 1000.0,
              protocol_.rejoins());
        else
          spdlog::info("{}: welcomed by the master at {} as id {} at frame {} (heartbeat {} ms, barrier timeout {} ms)",
                       setup_.who, master_address(), w.node_id, w.current_frame, w.heartbeat_interval_ms,
                       w.barrier_timeout_ms);
        events_.welcomed(w);
        break;
      }
      case Meaning::work: events_.message(message); break;
      case Meaning::heartbeat: break;
      case Meaning::rejected: {
        const Reject& r = std::get<Reject>(message);
        spdlog::error("{}: the master at {} refused the connection ({}): {}", setup_.who, master_address(),
                      static_cast<int>(r.reason), core::escaped(r.text, kMaxReasonBytes));
        end("rejected", kNodeExitRefused);
        break;
      }
      case Meaning::goodbye: {
        const Goodbye& g = std::get<Goodbye>(message);
        if (welcomed) {
          spdlog::info("{}: the master said goodbye: {}", setup_.who, core::escaped(g.reason, kMaxReasonBytes));
          end("goodbye", kNodeExitDone);
        } else {
          spdlog::error("{}: the master said goodbye during the handshake: {}", setup_.who,
                        core::escaped(g.reason, kMaxReasonBytes));
          end("goodbye", kNodeExitRefused);
        }
        break;
      }
    }
  } catch (const HandshakeError& e) {
    spdlog::error("{}: the master at {} failed to authenticate: {}", setup_.who, master_address(), e.what());
    say_goodbye(cat("authentication failed: ", e.what()));
    events_.ended(kNodeExitRefused);
  } catch (const std::exception& e) {
    spdlog::error("{}: closing the connection to the master: {}", setup_.who, e.what());
    say_goodbye(cat("error: ", e.what()));
    events_.ended(kNodeExitFailed);
  }
}

void MasterLink::heartbeat_tick(std::uint64_t generation) {
  if (stopping_ || !connection_ || generation != generation_) return;
  const auto now = std::chrono::steady_clock::now();
  switch (protocol_.tick(connection_->last_received(), now)) {
    case MasterLinkProtocol::Tick::silent:
      if (protocol_.welcomed())
        connection_failed(fmt::format("nothing from the master for {:.1f} s, past its silence limit of {:.0f} s",
                                      ms_since(connection_->last_received()) / 1000.0,
                                      protocol_.silence_limit_ms() / 1000.0));
      else
        connection_failed("no Welcome in time");
      return;
    case MasterLinkProtocol::Tick::send_heartbeat: connection_->send(heartbeat_at(now)); break;
    case MasterLinkProtocol::Tick::wait: break;
  }
  heartbeat_timer_.expires_after(milliseconds(protocol_.heartbeat_ms()));
  heartbeat_timer_.async_wait([this, generation](const boost::system::error_code& ec) {
    if (!ec) heartbeat_tick(generation);
  });
}

std::optional<boost::asio::ip::tcp::endpoint> MasterLink::master_endpoint() const {
  if (!connection_ || !protocol_.welcomed()) return std::nullopt;
  return connection_->remote_endpoint();
}

std::optional<Digest> MasterLink::datagram_key() const {
  if (!connection_ || !protocol_.welcomed()) return std::nullopt;
  return protocol_.datagram_key();
}

}  // namespace zenith::cluster
