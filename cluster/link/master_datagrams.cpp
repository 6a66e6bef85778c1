#include "cluster/link/master_datagrams.h"

#include <spdlog/spdlog.h>

#include <cmath>

#include "cluster/protocol/datagram.h"

namespace zenith::cluster {

namespace asio = boost::asio;
using asio::ip::udp;

MasterDatagrams::MasterDatagrams(asio::io_context& io, std::string who, FrameHandler on_frame, LocalClock local)
    : io_(io),
      who_(std::move(who)),
      on_frame_(std::move(on_frame)),
      ping_timer_(io),
      buffer_(max_datagram_bytes() + 1),
      local_(local) {}

void MasterDatagrams::start(const udp::endpoint& master, std::uint32_t node_id, const Digest& key,
                            std::uint64_t master_time_ns, Clock::time_point welcomed) {
  stop();
  ++generation_;
  if (master != master_) {  // another master (a standby took over): another clock
    clock_ = ClockSync{};
    synchronized_logged_ = false;
  }
  master_ = master;
  node_id_ = node_id;
  key_ = key;
  if (!clock_.synchronized()) clock_.seed(static_cast<std::int64_t>(master_time_ns), local_.read_ns(welcomed));
  boost::system::error_code ec;
  socket_.emplace(io_);
  socket_->open(master.protocol(), ec);
  if (!ec) socket_->connect(master, ec);  // only the master's datagrams reach a connected socket
  if (ec) {
    spdlog::warn(
        "{}: no datagram socket to the master at {}:{} ({}): frames come over TCP only, and the clock "
        "offset is the Welcome's one-way estimate",
        who_, master.address().to_string(), master.port(), ec.message());
    socket_.reset();
    return;
  }
  receive();
  ping();
}

void MasterDatagrams::stop() {
  ++generation_;
  ping_timer_.cancel();
  if (socket_) {
    boost::system::error_code ignored;
    socket_->close(ignored);
    socket_.reset();
  }
}

MasterDatagrams::Clock::time_point MasterDatagrams::to_local(std::uint64_t master_ns) const {
  return local_.steady_at(clock_.to_node(static_cast<std::int64_t>(master_ns)));
}

void MasterDatagrams::start_probe(std::chrono::microseconds interval, Clock::time_point until) {
  probe_ = PingProbe{};
  probe_interval_ = interval;
  probe_until_ = until;
  ping_timer_.cancel();  // the next ping now, at the probe's rate
  ++ping_chain_;         // a wait that already ended sends nothing more
  if (socket_) ping();
}

void MasterDatagrams::end_probe() { probe_until_ = Clock::time_point{}; }

void MasterDatagrams::ping() {
  if (!socket_) return;
  const auto now = Clock::now();
  const bool probing = now < probe_until_;
  const auto t1 = static_cast<std::uint64_t>(local_.read_ns(now));
  if (probing) probe_.sent(t1);
  const std::vector<Message> message = {ClockPing{t1}};
  auto datagram = std::make_shared<std::vector<std::uint8_t>>(seal_datagram(key_, node_id_, message));
  // A send that fails (the link is down, no route) is the same as a lost datagram: the next ping tries again.
  socket_->async_send(asio::buffer(*datagram), [datagram](const boost::system::error_code&, std::size_t) {});
  const std::uint64_t generation = generation_, chain = ping_chain_;
  ping_timer_.expires_after(probing ? std::chrono::duration_cast<Clock::duration>(probe_interval_)
                                    : std::chrono::duration_cast<Clock::duration>(kPingInterval));
  ping_timer_.async_wait([this, generation, chain](const boost::system::error_code& ec) {
    if (!ec && generation == generation_ && chain == ping_chain_) ping();
  });
}

void MasterDatagrams::receive() {
  const std::uint64_t generation = generation_;
  socket_->async_receive(asio::buffer(buffer_), [this, generation](const boost::system::error_code& ec, std::size_t n) {
    if (generation != generation_ || !socket_) return;
    // ICMP "port unreachable" surfaces here as connection_refused: the master
    // is not listening for datagrams (yet); keep receiving.
    if (!ec) on_datagram(n);
    receive();
  });
}

void MasterDatagrams::on_datagram(std::size_t bytes) {
  const auto now = Clock::now();
  const auto opened = open_datagram(key_, std::span<const std::uint8_t>(buffer_.data(), bytes));
  if (const auto* refusal = std::get_if<DatagramRefusal>(&opened)) {
    if (const auto more = refused_.admit(now)) spdlog::warn("{}: datagram dropped: {}{}", who_, refusal->what, *more);
    return;
  }
  const OpenedDatagram& d = std::get<OpenedDatagram>(opened);
  if (d.node_id != node_id_) return;
  last_heard_ = now;
  std::optional<FrameSchedule> schedule;
  for (const Message& m : d.messages) {
    if (const auto* pong = std::get_if<ClockPong>(&m)) {
      const std::int64_t t4 = local_.read_ns(now);
      const std::int64_t round_trip = (t4 - static_cast<std::int64_t>(pong->node_sent_ns)) -
                                      static_cast<std::int64_t>(pong->master_sent_ns - pong->master_received_ns);
      if (round_trip >= 0) probe_.answered(pong->node_sent_ns, static_cast<std::uint64_t>(round_trip));
      clock_.add({static_cast<std::int64_t>(pong->node_sent_ns), static_cast<std::int64_t>(pong->master_received_ns),
                  static_cast<std::int64_t>(pong->master_sent_ns), t4});
      if (clock_.steps() > steps_logged_) {
        steps_logged_ = clock_.steps();
        spdlog::warn(
            "{}: its clock and the master's stepped apart (three exchanges in a row more than 2 ms off the "
            "estimate): the estimate starts afresh; scheduled frames follow it within a few pings ({} step{} so far)",
            who_, steps_logged_, steps_logged_ == 1 ? "" : "s");
      }
      if (!drift_logged_ && std::abs(clock_.drift_ppm()) > kDriftWarnPpm) {
        drift_logged_ = true;
        spdlog::warn(
            "{}: its clock runs {:.0f} ppm off the master's (crystals differ by tens): followed, but check "
            "the PC's clock",
            who_, clock_.drift_ppm());
      }
      if (!synchronized_logged_ && clock_.synchronized()) {
        synchronized_logged_ = true;
        spdlog::info("{}: clock synchronized with the master over datagrams (offset {:.3f} ms, round trip {:.3f} ms)",
                     who_, static_cast<double>(clock_.offset_ns(t4)) / 1e6,
                     static_cast<double>(clock_.round_trip_ns().value_or(0)) / 1e6);
      }
    } else if (const auto* s = std::get_if<FrameSchedule>(&m)) {
      schedule = *s;
    } else if (const auto* f = std::get_if<FrameState>(&m)) {
      if (schedule && schedule->frame == f->frame) on_frame_(ScheduledFrame{*schedule, *f});
      schedule.reset();
    }
  }
}

}  // namespace zenith::cluster
