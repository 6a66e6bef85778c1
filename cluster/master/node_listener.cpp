#include "cluster/master/node_listener.h"

#include <spdlog/spdlog.h>

#include <memory>
#include <stdexcept>

#include "cluster/link/connection.h"
#include "core/strings.h"

namespace zenith::cluster {

using boost::asio::ip::tcp;
using core::cat;

NodeListener::NodeListener(boost::asio::io_context& io, NodeSessions& sessions, SharedSecret secret,
                           std::string cluster_name, OnMessage on_message, OnClosed on_closed)
    : acceptor_(io),
      sessions_(sessions),
      secret_(std::move(secret)),
      cluster_name_(std::move(cluster_name)),
      on_message_(std::move(on_message)),
      on_closed_(std::move(on_closed)) {}

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
  boost::system::error_code ec;
  acceptor_.close(ec);
}

void NodeListener::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
    if (closed_) return;
    if (!ec) on_accept(std::move(socket));
    else spdlog::warn("master: accept failed: {}", ec.message());
    accept();
  });
}

void NodeListener::on_accept(tcp::socket socket) {
  boost::system::error_code ec;
  const tcp::endpoint remote = socket.remote_endpoint(ec);
  const std::string peer = ec ? std::string("unknown peer") : cat(remote.address().to_string(), ":", remote.port());
  NodeSession& session =
      sessions_.add(std::make_shared<Connection>(std::move(socket), peer), MasterHandshake(secret_, cluster_name_));
  const std::uint32_t id = session.id;
  spdlog::debug("master: connection from {}", peer);
  session.connection->start([this, id](Message&& m) { on_message_(id, std::move(m)); },
                            [this, id](const std::string& reason) { on_closed_(id, reason); });
}

}  // namespace zenith::cluster
