#include "cluster/master/node_session.h"

#include <spdlog/spdlog.h>

#include "core/strings.h"

namespace zenith::cluster {

using core::cat;

std::string NodeSession::who() const {
  if (role == PeerRole::standby) return cat("the standby (", connection->peer(), ")");
  // The name comes from the peer's Hello: escaped, so it cannot forge a log line.
  return name.empty() ? cat("connection from ", connection->peer())
                      : cat("node '", core::escaped(name, 64), "' (", connection->peer(), ")");
}

void NodeSession::refuse(RejectReason reason, const std::string& text, bool log) {
  if (log) spdlog::warn("master: refused {}: {}", who(), core::escaped(text, 1024));
  connection->send(Reject{reason, text.substr(0, kMaxReasonBytes)});
  connection->close_after_flush(cat("refused: ", text));
}

void NodeSession::close_for_protocol_violation(const std::string& what) {
  spdlog::warn("master: closing {}: {}", who(), what);
  connection->send(Goodbye{cat("protocol error: ", what).substr(0, kMaxReasonBytes)});
  connection->close_after_flush(cat("protocol error: ", what));
}

}  // namespace zenith::cluster
