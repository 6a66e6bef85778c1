#pragma once
// A change of one atmosphere's parameters at a frame of the default show,
// from the command line (`zenith master --switch-atmosphere`; docs/cluster.md,
// "Table versions"). The master's table schedule (table_schedule.h) prepares
// and switches it.
#include <cstdint>
#include <string>

namespace zenith::cluster {

/// From frame `frame` on, the master prepares the tables of `atmosphere` for
/// body `body` in the background, ships them, and switches every node to them
/// at one frame once all live nodes hold them.
struct AtmosphereSwitch {
  std::uint64_t frame = 0;  ///< start preparing when this frame starts
  std::string body;         ///< a body of the scene that has an atmosphere
  std::string atmosphere;   ///< a preset name or an atmosphere file (as `zenith render --atmosphere`)
};

}  // namespace zenith::cluster
