#pragma once
// The master as the operator's desk sees it: the one door between the
// operator (cluster/operator/) and the master (cluster/master/). The desk
// keeps the operator's own state — exposure, sun, fade, dome preview — and
// asks the master, through this interface only, for what the master owns:
// where the frames are, the atmospheres' table versions, the status of its
// nodes and tables, and the end of the show. The master implements it
// (cluster/master/master_desk.h); a test may implement it with a stand-in.
// Networking thread only.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "cluster/operator/dome_preview.h"
#include "cluster/operator/operator_command.h"
#include "cluster/protocol/messages.h"
#include "scene/local_horizon.h"

namespace zenith::cluster {

/// The desk's own part of the status (docs/operator.md, "Status"): what the
/// operator has set, which the master's status shows beside its own.
struct DeskStatus {
  std::optional<double> exposure_override;
  std::optional<scene::SkyAngles> sun;           ///< the latest frame's sun in its camera's sky; nullopt before frame 0
  std::optional<scene::SkyAngles> sun_override;  ///< the operator's sun, nullopt: the show's
  const DomePreview* preview = nullptr;          ///< the dome preview; nullptr without the HTTP console
  bool preview_on = false;
};

class DeskMaster {
 public:
  virtual ~DeskMaster() = default;

  /// The latest frame started, nullptr before frame 0.
  virtual const FrameState* latest_frame() const = 0;
  /// The frame the master's barrier is at (the next to start before frame 0).
  virtual std::uint64_t barrier_frame() const = 0;
  /// An operator's `set` of an atmosphere parameter, or `clear` of a body's
  /// changes: the reply; throws std::invalid_argument (or ConfigError) when
  /// refused, and then nothing changed.
  virtual std::string set_atmosphere(const operator_command::Set& set) = 0;
  virtual std::string clear_atmosphere(const std::string& body) = 0;
  /// The status (docs/operator.md, "Status"): the master's, with the desk's part.
  virtual nlohmann::json status(const DeskStatus& desk) const = 0;
  /// Ends the show (the operator's `quit`).
  virtual void stop(const std::string& reason) = 0;
};

}  // namespace zenith::cluster
