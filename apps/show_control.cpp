// `zenith show control`: sends one playback command to a running master's
// control socket (`zenith master|cluster --control-port PORT`) and prints the
// reply (docs/shows.md, "Playback").
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <istream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>

#include "apps/commands.h"

namespace zenith::app {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

struct ControlArgs {
  int port = 0;
  std::vector<std::string> words;
  int timeout_ms = 5000;
};

/// The master's reply line; throws std::runtime_error when it cannot be reached or does not answer in time.
std::string send_command(const ControlArgs& a) {
  std::string line;
  for (const std::string& w : a.words) {
    if (!line.empty()) line += ' ';
    line += w;
  }
  asio::io_context io;
  tcp::socket socket(io);
  asio::streambuf reply;
  std::string outgoing = line + "\n";
  std::string error;
  const tcp::endpoint master(asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(a.port));
  socket.async_connect(master, [&](const boost::system::error_code& ec) {
    if (ec) {
      error = fmt::format("cannot reach a master's control socket at 127.0.0.1:{}: {}", a.port, ec.message());
      return;
    }
    asio::async_write(socket, asio::buffer(outgoing), [&](const boost::system::error_code& wec, std::size_t) {
      if (wec) {
        error = fmt::format("sending to 127.0.0.1:{}: {}", a.port, wec.message());
        return;
      }
      asio::async_read_until(socket, reply, '\n', [&](const boost::system::error_code& rec, std::size_t) {
        if (rec) error = fmt::format("no reply from 127.0.0.1:{}: {}", a.port, rec.message());
      });
    });
  });
  io.run_for(std::chrono::milliseconds(a.timeout_ms));
  if (!io.stopped())
    throw std::runtime_error(fmt::format("no reply from 127.0.0.1:{} within {} ms", a.port, a.timeout_ms));
  if (!error.empty()) throw std::runtime_error(error);
  std::istream in(&reply);
  std::string answer;
  std::getline(in, answer);
  return answer;
}

}  // namespace

void register_show_control(CLI::App& show) {
  auto a = std::make_shared<ControlArgs>();
  CLI::App* cmd = show.add_subcommand(
      "control",
      "Send a playback command to a running master (play, pause, toggle, seek S, rate R, loop on|off, status, quit)");
  cmd->add_option("--port", a->port, "The master's --control-port")->required()->check(CLI::Range(1, 65535));
  cmd->add_option("--timeout-ms", a->timeout_ms, "Give up after this long (default 5000)")
      ->check(CLI::Range(1, 600000));
  cmd->add_option("command", a->words, "The command and its argument, e.g. seek 12.5")->required();
  cmd->callback([a] {
    const std::string answer = send_command(*a);
    fmt::print("{}\n", answer);
    if (answer.starts_with("error") || answer.starts_with("no show")) std::exit(1);
  });
}

}  // namespace zenith::app
