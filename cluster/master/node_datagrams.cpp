#include "cluster/master/node_datagrams.h"

#include <spdlog/spdlog.h>

#include "cluster/protocol/datagram.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::udp;

namespace {
std::uint64_t ns_now() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
          .count());
}
}  // namespace

NodeDatagrams::NodeDatagrams(asio::io_context& io, NodeSessions& sessions)
    : sessions_(sessions), io_(io), buffer_(max_datagram_bytes() + 1) {}

void NodeDatagrams::open(const std::string& host, std::uint16_t port) {
  boost::system::error_code ec;
  const asio::ip::address address = asio::ip::make_address(host, ec);
  udp::socket socket(io_);
  if (!ec) socket.open(address.is_v6() ? udp::v6() : udp::v4(), ec);
  if (!ec) socket.bind(udp::endpoint(address, port), ec);
  if (ec) {
    spdlog::warn(
        "master: cannot take UDP port {}:{} for the nodes' datagrams ({}): scheduled frames go over TCP, "
        "where a lost packet delays them by a retransmission (docs/cluster.md, \"Setting up the network\")",
        host, port, ec.message());
    return;
  }
  socket_.emplace(std::move(socket));
  receive();
}

void NodeDatagrams::close() {
  if (!socket_) return;
  boost::system::error_code ignored;
  socket_->close(ignored);
  socket_.reset();
}

bool NodeDatagrams::reaches(const NodeSession& s, Clock::time_point now) const {
  return socket_ && s.datagram_peer && now - s.last_datagram < kSilence;
}

void NodeDatagrams::check_links(Clock::time_point now, bool black) {
  sessions_.for_each([&](NodeSession& s) {
    if (!s.datagram_peer || s.link_quiet || now - s.last_datagram < kQuiet) return;
    s.link_quiet = true;
    spdlog::warn(
        "master: node '{}' unreachable: nothing from it for {} ms; its projectors {} once its scheduled "
        "frames ran out, the other nodes go on",
        s.name, kQuiet.count(), black ? "show black" : "hold the last frame");
  });
}

void NodeDatagrams::send(const NodeSession& s, std::shared_ptr<const std::vector<std::uint8_t>> datagram) {
  if (!socket_ || !s.datagram_peer) return;
  // Not resent: the frame goes again at the next tick (docs/protocol.md, "Datagrams").
  socket_->async_send_to(asio::buffer(*datagram), *s.datagram_peer,
                         [datagram](const boost::system::error_code&, std::size_t) {});
}

void NodeDatagrams::receive() {
  socket_->async_receive_from(asio::buffer(buffer_), sender_,
                              [this](const boost::system::error_code& ec, std::size_t n) {
                                if (!socket_ || ec == asio::error::operation_aborted) return;
                                if (!ec) on_datagram(n, sender_);
                                receive();
                              });
}

void NodeDatagrams::on_datagram(std::size_t bytes, const udp::endpoint& from) {
  const std::uint64_t received_ns = ns_now();
  const auto now = Clock::now();
  const std::span<const std::uint8_t> d(buffer_.data(), bytes);
  const auto refuse = [&](const std::string& why) {
    if (const auto more = refused_.admit(core::LogLimiters::kind_of(why), now))
      spdlog::warn("master: datagram from {}:{} dropped: {}{}", from.address().to_string(), from.port(), why, *more);
  };
  const std::optional<std::uint32_t> id = datagram_node_id(d);
  if (!id) return refuse("not a zenith datagram");
  NodeSession* s = sessions_.find(*id);
  if (s == nullptr || !s->datagram_key) return refuse("its node id names no authenticated connection");
  const auto opened = open_datagram(*s->datagram_key, d);
  if (const auto* refusal = std::get_if<DatagramRefusal>(&opened)) return refuse(refusal->what);
  for (const Message& m : std::get<OpenedDatagram>(opened).messages) {
    const auto* ping = std::get_if<ClockPing>(&m);
    if (ping == nullptr) return refuse(std::string(to_string(message_type(m))) + " is not sent by nodes");
    if (!s->datagram_peer || *s->datagram_peer != from) {
      spdlog::info("master: node '{}' takes its scheduled frames as datagrams at {}:{}", s->name,
                   from.address().to_string(), from.port());
      s->datagram_peer = from;
    }
    if (s->link_quiet) {
      spdlog::info("master: node '{}' reachable again after {:.2f} s; it presents from the next frame due", s->name,
                   std::chrono::duration<double>(now - s->last_datagram).count());
      s->link_quiet = false;
    }
    s->last_datagram = now;
    if (s->link_check_pings) s->link_check_pings->insert(ping->node_sent_ns);
    const std::vector<Message> pong = {ClockPong{ping->node_sent_ns, received_ns, ns_now()}};
    send(*s, std::make_shared<const std::vector<std::uint8_t>>(seal_datagram(*s->datagram_key, *id, pong)));
  }
}

}  // namespace zenith::cluster
