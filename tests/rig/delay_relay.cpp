// zenith_delay_relay: a delaying relay for the network rig (docs/cluster.md,
// "The network rig"), where the kernel has no netem. It runs in a node's
// namespace in front of the node: the node connects to it as to its master
// (TCP and UDP on the same port), and it forwards everything to the master
// and back, each way
//
//   * delayed by --delay-ms ± --jitter-ms (uniform), per TCP read or datagram;
//     a TCP byte stream stays in order (a chunk never leaves before the one
//     before it), datagrams leave when their own delay is over, so jitter
//     larger than their spacing reorders them, as on a real network;
//   * datagrams duplicated (--duplicate-percent: the copy leaves with the
//     original) and held back (--reorder-percent: --reorder-extra-ms more),
//     as a switch or a Wi-Fi bridge can do.
//
// Test tooling only (not part of zenith): a seeded generator, counts of what
// it did on SIGTERM, and nothing but the one master address it is given.
//
//   zenith_delay_relay --listen 127.0.0.1:47100 --to 198.18.0.10:47100
//                      --delay-ms 5 --jitter-ms 1 [--duplicate-percent 2] [--reorder-percent 2] [--seed 7]
#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <deque>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>

namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;

struct Settings {
  std::string listen_host = "127.0.0.1", to_host;
  unsigned short listen_port = 0, to_port = 0;
  double delay_ms = 0, jitter_ms = 0, duplicate_percent = 0, reorder_percent = 0, reorder_extra_ms = 50;
  unsigned seed = 1;
};

struct Counts {
  unsigned long long tcp_chunks = 0, datagrams = 0, duplicated = 0, held_back = 0;
};

/// The delays: uniform in [delay − jitter, delay + jitter], never negative.
class Delays {
 public:
  explicit Delays(const Settings& s) : s_(s), random_(s.seed) {}
  Clock::duration next() {
    const double ms =
        std::max(0.0, s_.delay_ms + std::uniform_real_distribution<double>(-1, 1)(random_) * s_.jitter_ms);
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(ms));
  }
  bool chance(double percent) { return std::uniform_real_distribution<double>(0, 100)(random_) < percent; }

 private:
  const Settings& s_;
  std::mt19937 random_;
};

/// One direction of a TCP connection: read, hold each chunk its delay, write in order.
class TcpPipe : public std::enable_shared_from_this<TcpPipe> {
 public:
  TcpPipe(std::shared_ptr<tcp::socket> from, std::shared_ptr<tcp::socket> to, Delays& delays, Counts& counts)
      : from_(std::move(from)), to_(std::move(to)), timer_(from_->get_executor()), delays_(delays), counts_(counts) {}
  void start() { read(); }

 private:
  struct Chunk {
    Clock::time_point release;
    std::vector<char> bytes;
  };
  void read() {
    auto self = shared_from_this();
    from_->async_read_some(asio::buffer(buffer_), [this, self](const boost::system::error_code& ec, std::size_t n) {
      if (ec) {  // the end of one side ends the other once what it sent before is delivered
        ended_ = true;
        if (queue_.empty()) shut_down();
        return;
      }
      ++counts_.tcp_chunks;
      Clock::time_point release = Clock::now() + delays_.next();
      if (!queue_.empty()) release = std::max(release, queue_.back().release);  // a stream stays in order
      queue_.push_back({release, std::vector<char>(buffer_.begin(), buffer_.begin() + static_cast<long>(n))});
      if (queue_.size() == 1) send_next();
      read();
    });
  }
  void shut_down() {
    boost::system::error_code ignored;
    to_->shutdown(tcp::socket::shutdown_send, ignored);
  }
  void send_next() {
    if (queue_.empty()) {
      if (ended_) shut_down();
      return;
    }
    auto self = shared_from_this();
    timer_.expires_at(queue_.front().release);
    timer_.async_wait([this, self](const boost::system::error_code& ec) {
      if (ec) return;
      asio::async_write(*to_, asio::buffer(queue_.front().bytes),
                        [this, self](const boost::system::error_code& e, std::size_t) {
                          if (e) {
                            boost::system::error_code ignored;
                            from_->close(ignored);
                            return;
                          }
                          queue_.pop_front();
                          send_next();
                        });
    });
  }

  std::shared_ptr<tcp::socket> from_, to_;
  asio::steady_timer timer_;
  Delays& delays_;
  Counts& counts_;
  std::array<char, 65536> buffer_{};
  std::deque<Chunk> queue_;
  bool ended_ = false;  ///< the sending side closed: shut the other down once the queue is empty
};

/// Datagrams both ways between the node (whichever endpoint last sent to the
/// listening socket) and the master, each held its own delay.
class UdpRelay {
 public:
  UdpRelay(asio::io_context& io, const udp::endpoint& listen, const udp::endpoint& master, Delays& delays,
           const Settings& settings, Counts& counts)
      : io_(io), near_(io, listen), far_(io), master_(master), delays_(delays), settings_(settings), counts_(counts) {
    far_.open(master.protocol());
    far_.connect(master);
    receive_near();
    receive_far();
  }

 private:
  void forward(udp::socket& socket, const udp::endpoint& to, std::vector<char> bytes) {
    ++counts_.datagrams;
    int copies = 1;
    if (delays_.chance(settings_.duplicate_percent)) {
      ++copies;
      ++counts_.duplicated;
    }
    Clock::duration delay = delays_.next();
    if (delays_.chance(settings_.reorder_percent)) {
      ++counts_.held_back;
      delay += std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double, std::milli>(settings_.reorder_extra_ms));
    }
    auto data = std::make_shared<std::vector<char>>(std::move(bytes));
    auto timer = std::make_shared<asio::steady_timer>(io_, delay);
    timer->async_wait([&socket, to, data, timer, copies](const boost::system::error_code& ec) {
      if (ec) return;
      for (int c = 0; c < copies; ++c)
        socket.async_send_to(asio::buffer(*data), to, [data](const boost::system::error_code&, std::size_t) {});
    });
  }
  void receive_near() {
    near_.async_receive_from(
        asio::buffer(near_buffer_), node_sender_, [this](const boost::system::error_code& ec, std::size_t n) {
          if (ec == asio::error::operation_aborted) return;
          if (!ec) {
            node_ = node_sender_;
            forward(far_, master_, {near_buffer_.begin(), near_buffer_.begin() + static_cast<long>(n)});
          }
          receive_near();
        });
  }
  void receive_far() {
    far_.async_receive(asio::buffer(far_buffer_), [this](const boost::system::error_code& ec, std::size_t n) {
      if (ec == asio::error::operation_aborted) return;
      if (!ec && node_) forward(near_, *node_, {far_buffer_.begin(), far_buffer_.begin() + static_cast<long>(n)});
      receive_far();  // an ICMP "unreachable" (the master not up yet) surfaces as an error: keep going
    });
  }

  asio::io_context& io_;
  udp::socket near_, far_;
  udp::endpoint master_, node_sender_;
  std::optional<udp::endpoint> node_;
  Delays& delays_;
  const Settings& settings_;
  Counts& counts_;
  std::array<char, 65536> near_buffer_{}, far_buffer_{};
};

class TcpRelay {
 public:
  TcpRelay(asio::io_context& io, const tcp::endpoint& listen, const tcp::endpoint& master, Delays& delays,
           Counts& counts)
      : io_(io), acceptor_(io, listen), master_(master), delays_(delays), counts_(counts) {
    accept();
  }

 private:
  void accept() {
    acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
      if (ec == asio::error::operation_aborted) return;
      if (!ec) connect(std::make_shared<tcp::socket>(std::move(socket)));
      accept();
    });
  }
  void connect(std::shared_ptr<tcp::socket> node) {
    auto master = std::make_shared<tcp::socket>(io_);
    master->async_connect(master_, [this, node, master](const boost::system::error_code& ec) {
      if (ec) {  // the master not up (yet): the node sees its connection close and retries
        boost::system::error_code ignored;
        node->close(ignored);
        return;
      }
      node->set_option(tcp::no_delay(true));
      master->set_option(tcp::no_delay(true));
      std::make_shared<TcpPipe>(node, master, delays_, counts_)->start();
      std::make_shared<TcpPipe>(master, node, delays_, counts_)->start();
    });
  }

  asio::io_context& io_;
  tcp::acceptor acceptor_;
  tcp::endpoint master_;
  Delays& delays_;
  Counts& counts_;
};

bool split_address(const std::string& text, std::string& host, unsigned short& port) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos) return false;
  host = text.substr(0, colon);
  const long p = std::strtol(text.c_str() + colon + 1, nullptr, 10);
  if (p < 1 || p > 65535) return false;
  port = static_cast<unsigned short>(p);
  return true;
}

int usage(const std::string& why) {
  std::cerr << "zenith_delay_relay: " << why
            << "\nusage: zenith_delay_relay --listen HOST:PORT --to HOST:PORT [--delay-ms D] [--jitter-ms J] "
               "[--duplicate-percent P] [--reorder-percent P] [--reorder-extra-ms X] [--seed N]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  std::string listen, to;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    const bool numeric = end != value.c_str() && *end == '\0' && number >= 0 && number <= 100000;
    if (key == "--listen")
      listen = value;
    else if (key == "--to")
      to = value;
    else if (!numeric)
      return usage(key + " " + value + ": not a number in [0, 100000]");
    else if (key == "--delay-ms")
      s.delay_ms = number;
    else if (key == "--jitter-ms")
      s.jitter_ms = number;
    else if (key == "--duplicate-percent")
      s.duplicate_percent = number;
    else if (key == "--reorder-percent")
      s.reorder_percent = number;
    else if (key == "--reorder-extra-ms")
      s.reorder_extra_ms = number;
    else if (key == "--seed")
      s.seed = static_cast<unsigned>(number);
    else
      return usage("unknown option " + key);
  }
  if (argc % 2 == 0) return usage("an option without its value");
  if (!split_address(listen, s.listen_host, s.listen_port)) return usage("--listen HOST:PORT is required");
  if (!split_address(to, s.to_host, s.to_port)) return usage("--to HOST:PORT is required");
  try {
    asio::io_context io;
    Delays delays(s);
    Counts counts;
    const auto listen_address = asio::ip::make_address(s.listen_host);
    const auto master_address = asio::ip::make_address(s.to_host);
    TcpRelay tcp_relay(io, {listen_address, s.listen_port}, {master_address, s.to_port}, delays, counts);
    UdpRelay udp_relay(io, {listen_address, s.listen_port}, {master_address, s.to_port}, delays, s, counts);
    asio::signal_set signals(io, SIGINT, SIGTERM);
    signals.async_wait([&](const boost::system::error_code&, int) { io.stop(); });
    std::cerr << "zenith_delay_relay: " << listen << " -> " << to << ", " << s.delay_ms << " ms ± " << s.jitter_ms
              << " ms each way, " << s.duplicate_percent << " % duplicated, " << s.reorder_percent << " % held back "
              << s.reorder_extra_ms << " ms" << std::endl;
    io.run();
    std::cerr << "zenith_delay_relay: " << counts.tcp_chunks << " TCP chunks, " << counts.datagrams << " datagrams ("
              << counts.duplicated << " duplicated, " << counts.held_back << " held back)" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "zenith_delay_relay: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
