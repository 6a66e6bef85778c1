#pragma once
// The operator's desk (docs/shows.md, "Playback"; docs/operator.md): what an
// operator's command does, the operator's overrides of the show (exposure,
// sun, fade, dome preview on or off), and the status the console shows.
// Commands come as lines from the console and the control socket
// (OperatorInput), and as parsed commands from the HTTP console
// (OperatorHttpServer) and OSC (OscReceiver), which the desk starts on the
// master's io_context when asked to; every command changes the show between
// frames, so that every node gets one consistent state per frame. What the
// master owns — where the frames are, the atmospheres' table versions (a
// `set` goes to the master's table schedule), the nodes' status, the end of
// the show — the desk reaches through one door, DeskMaster
// (cluster/operator/desk_master.h). Without start_*() it opens nothing:
// tests/cluster/operator_desk_test.cpp drives it with a scene, a clock and
// the master's parts, no sockets. Networking thread only.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <nlohmann/json.hpp>

#include "cluster/link/cluster_config.h"
#include "cluster/operator/desk_master.h"
#include "cluster/operator/dome_preview.h"
#include "cluster/operator/fade_control.h"
#include "cluster/operator/operator_command.h"
#include "cluster/operator/operator_console_options.h"
#include "cluster/operator/operator_http_server.h"
#include "cluster/operator/operator_input.h"
#include "cluster/operator/osc_receiver.h"
#include "cluster/operator/sun_override.h"
#include "cluster/protocol/messages.h"
#include "scene/scene.h"
#include "show/playback_clock.h"
#include "show/show.h"

namespace zenith::cluster {

/// Invariant: the overrides change frames only through shape() (the next frame
/// on), and a refused command changes nothing.
class OperatorDesk {
 public:
  /// What the desk knows of the show from the start.
  struct Setup {
    const ClusterConfig& config;           ///< its viewports place the dome preview's thumbnails
    const show::Show* show = nullptr;      ///< nullptr: the default show
    show::PlaybackClock* clock = nullptr;  ///< a show's clock (nullptr with the default show)
    double fps = 30.0;
    bool feed = false;  ///< the frames come from an offline render's feed
    /// The chase of the house's timecode (the show's clock does not run):
    /// `play` resumes a stopped chase, `timecode offset hh:mm:ss:ff` moves the
    /// show's start against the timecode, `status` says where it is; pause,
    /// seek, rate and loop are refused (the timecode decides them). nullptr: none.
    show::TimecodeChase* chase = nullptr;
  };

  /// `master`: the door to the master (outlives the desk); `scene`: the
  /// master's (the local horizons of the operator's sun).
  OperatorDesk(DeskMaster& master, Setup setup, const scene::Scene& scene);

  // ---- commands ----
  /// One command line from the console or the control socket; the reply line.
  /// A line that starts with "{" is a JSON command (docs/operator.md).
  std::string on_line(std::string line);
  /// Applies one command from `source` ("control", "http 127.0.0.1", "osc
  /// 10.0.0.5") with a log line either way; returns the reply. Throws
  /// (std::invalid_argument, ConfigError) when the command is refused: then
  /// nothing was applied.
  std::string run(const OperatorCommand& command, const std::string& source);

  // ---- the frames ----
  /// The operator's exposure and sun put on the next frame of a show or the default show.
  void shape(FrameState& next) const;
  /// A standby taking over keeps the active master's exposure override.
  void set_exposure(std::optional<double> exposure) { exposure_ = exposure; }
  /// A standby taking over keeps the fade the nodes show (from the last FrameState it followed).
  void hold_fade(const scene::FadeState& fade, std::uint64_t first_frame);
  /// Whether the frame `frame` asks the nodes for thumbnails (the preview is on, every interval_frames()).
  bool wants_preview(std::uint64_t frame) const { return preview_on_ && frame % preview_interval_frames() == 0; }
  /// A node's thumbnail for the dome preview; ignored while the preview is off.
  /// Throws std::invalid_argument for a thumbnail that does not fit its outputs.
  void add_thumbnail(const std::string& node, const Thumbnail& thumbnail);
  /// Frames between two thumbnail requests: about two a second.
  std::uint64_t preview_interval_frames() const;

  // ---- status ----
  /// The console's status (GET /api/status; docs/operator.md, "Status").
  nlohmann::json status() const;
  /// The dome preview as PNG bytes (GET /api/preview), nullopt while off or empty.
  std::optional<std::string> preview_png() const;

  // ---- where commands come from (sockets, on `io`) ----
  /// The HTTP console and OSC: listening from before the tables are
  /// prepared, so a bad address or a missing token stops the master at once.
  void start_console(boost::asio::io_context& io, const OperatorConsoleOptions& console);
  /// Console lines on standard input, and the control socket on 127.0.0.1:`control_port`.
  void start_inputs(boost::asio::io_context& io, bool console, std::optional<std::uint16_t> control_port);
  /// Stops every listener (the master is stopping).
  void close();

 private:
  std::string apply_sun(const operator_command::Sun& sun);
  std::string apply_preview(const operator_command::Preview& on);
  std::string apply_clear(const operator_command::Clear& clear);
  std::string apply_fade(const operator_command::Fade& fade);
  std::string apply_blackout(const operator_command::Blackout& blackout);
  /// A playback command in the clock's words, to the chase or the clock of the show (one is playing).
  std::string apply_to_show(const std::string& line);
  /// A playback command (the clock's words: "play", "status", …) while the show chases timecode.
  std::string apply_to_chase(const std::string& line);
  /// The first frame a command changes: the next one to start.
  std::uint64_t next_frame() const;

  DeskMaster& master_;
  Setup setup_;
  std::optional<double> exposure_;  ///< the operator's exposure, replacing the show's (or scene's)
  SunOverride sun_;                 ///< the operator's sun, replacing the show's until cleared
  FadeControl fade_;                ///< the operator's fade and blackout, on every output
  /// The dome preview from the nodes' thumbnails (with the HTTP console); asked for only while on.
  std::optional<DomePreview> preview_;
  bool preview_on_ = false;
  std::optional<OperatorInput> input_;
  std::optional<OperatorHttpServer> http_;
  std::optional<OscReceiver> osc_;
};

}  // namespace zenith::cluster
