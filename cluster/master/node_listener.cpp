#include "cluster/master/node_listener.h"

#include <spdlog/spdlog.h>

#include <memory>
#include <stdexcept>

#include "cluster/link/connection.h"
#include "cluster/protocol/frame_decoder.h"
#include "core/strings.h"

namespace zenith::cluster {

using boost::asio::ip::tcp;
using core::cat;

NodeListener::NodeListener(boost::asio::io_context& io, NodeSessions& sessions, SharedSecret secret,
                           std::string cluster_name, OnMessage on_message, OnClosed on_closed)
    : acceptor_(io),
      accept_retry_(io, "cluster port"),
      sessions_(sessions),
      secret_(std::move(secret)),
      cluster_name_(std::move(cluster_name)),
      on_message_(std::move(on_message)),
      on_closed_(std::move(on_closed)) {}

void NodeListener::limit_unauthenticated(std::uint32_t max_connections) { max_unauthenticated_ = max_connections; }

void NodeListener::listen(const std::string& host, std::uint16_t port) {
  tcp::resolver resolver(acceptor_.get_executor());
  const tcp::endpoint endpoint = *resolver.resolve(host, std::to_string(port)).begin();
  acceptor_.open(endpoint.protocol());
  acceptor_.set_option(tcp::acceptor::reuse_address(true));
  boost::system::error_code ec;
  acceptor_.bind(endpoint, ec);
  if (ec) throw std::runtime_error(cat("master: cannot listen on ", host, ":", port, ": ", ec.message()));
  acceptor_.listen();
}

void NodeListener::start() { accept(); }

void NodeListener::close() {
  closed_ = true;
  accept_retry_.cancel();
  boost::system::error_code ec;
  acceptor_.close(ec);
}

void NodeListener::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
    if (closed_) return;
    if (ec) {
      accept_retry_.failed(ec, [this] { accept(); });  // EMFILE: back off, then accept again
      return;
    }
    accept_retry_.succeeded();
    on_accept(std::move(socket));
    accept();
  });
}

void NodeListener::on_accept(tcp::socket socket) {
  boost::system::error_code ec;
  const tcp::endpoint remote = socket.remote_endpoint(ec);
  const std::string peer = ec ? std::string("unknown peer") : cat(remote.address().to_string(), ":", remote.port());
  // At most max_unauthenticated_ connections in the handshake: the oldest
  // makes room (a node's handshake takes milliseconds; a stray peer's slot
  // goes to the next connection).
  const std::vector<NodeSessions::Id> waiting = sessions_.handshake_ids();
  if (waiting.size() >= max_unauthenticated_) {
    NodeSession* oldest = sessions_.find(waiting.front());
    if (const std::optional<std::string> more = refusals_.admit(core::LogLimiter::Clock::now()))
      spdlog::warn(
          "master: closing {}: still unauthenticated, and a new connection came from {} ({} unauthenticated "
          "connections at most: limits.max_unauthenticated_connections){}",
          oldest->who(), peer, max_unauthenticated_, *more);
    oldest->connection->close("too many unauthenticated connections");
  }
  auto connection = std::make_shared<Connection>(std::move(socket), peer);
  connection->limit_payload(max_handshake_payload_bytes(), "before the handshake");
  NodeSession& session = sessions_.add(std::move(connection), MasterHandshake(secret_, cluster_name_));
  const std::uint32_t id = session.id;
  spdlog::debug("master: connection from {}", peer);
  session.connection->start([this, id](Message&& m) { on_message_(id, std::move(m)); },
                            [this, id](const std::string& reason) { on_closed_(id, reason); });
}

}  // namespace zenith::cluster
