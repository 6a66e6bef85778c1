#pragma once
// When a standby master takes over (docs/cluster.md, "Standby master"), as
// pure logic: no sockets, no clock. The standby follows the active master once
// welcomed. When that connection is lost (closed, or the master silent past
// the silence limit) it checks at once whether the active master is gone by
// connecting again: if that attempt fails (refused, unreachable, or no Welcome
// within the attempt limit) it takes over; if the active master welcomes it,
// the loss was the standby's own (it stalled, or the network between the two
// dropped) and it follows again. Before its first Welcome it never takes
// over: with no show seen there is nothing to continue, and a master that is
// not up yet is no failure (its link gives up at the connect timeout).
#include <cstdint>

namespace zenith::cluster {

class TakeoverRule {
 public:
  enum class Phase {
    connecting,   ///< not yet welcomed by the active master
    following,    ///< welcomed: receiving every table version and frame
    checking,     ///< the connection was lost: one more attempt says whether the master is gone
    taking_over,  ///< the master is gone: this standby becomes the master
  };

  Phase phase() const { return phase_; }

  /// The active master welcomed the standby. Returns true when it was
  /// checking: the active master is alive after all, it follows again.
  bool welcomed();
  /// The welcomed connection was lost without a Goodbye: check (the link tries again at once).
  void lost();
  /// An attempt to reach the active master failed. Returns true when the
  /// standby takes over now (it was checking after a loss); connecting, it
  /// keeps trying.
  bool attempt_failed();

  /// Times the standby followed again after a loss that was its own.
  std::uint32_t false_alarms() const { return false_alarms_; }

 private:
  Phase phase_ = Phase::connecting;
  std::uint32_t false_alarms_ = 0;
};

}  // namespace zenith::cluster
