#pragma once
// Where the operator console listens (docs/operator.md): a web page and JSON
// API over HTTP, and OSC over UDP for show-control desks, both on the master's
// event loop (cluster/operator/operator_desk.h serves them).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cluster/protocol/handshake.h"

namespace zenith::cluster {

struct OperatorConsoleOptions {
  std::optional<std::uint16_t> http_port;  ///< serve the console on this port (0: any free port, logged)
  std::string http_host = "127.0.0.1";     ///< a numeric address; anything but loopback needs `token`
  /// When set, every /api request must carry it ("Authorization: Bearer TOKEN").
  std::optional<SharedSecret> token;
  /// With a token: host names (besides IP addresses and the loopback) the console may be reached by.
  std::vector<std::string> http_names;
  std::optional<std::uint16_t> osc_port;  ///< receive OSC on this UDP port (0: any free port, logged)
  std::string osc_host = "127.0.0.1";     ///< a numeric address; anything but loopback needs `osc_allow`
  std::vector<std::string> osc_allow;     ///< the only senders accepted (numeric addresses)
};

}  // namespace zenith::cluster
