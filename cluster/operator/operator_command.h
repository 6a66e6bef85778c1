#pragma once
// The operator's commands as data (docs/operator.md, "Commands"): what the web
// console, scripts (POST /api/command), OSC desks and JSON lines on the control
// socket ask the master to do. Parsing only: no clock, no show, no sockets.
// What a command does is the master's; this file says what is a well-formed
// command, with the same kind of error as the configuration files
// ("command: /rate = 20: must be in [-16, 16]").
//
// The JSON form, one object:
//   {"command": "play"} | "pause" | "toggle" | "status" | "quit"
//   {"command": "seek", "seconds": S}          S finite, ≥ 0 (the master checks ≤ the show's duration)
//   {"command": "rate", "rate": R}             R in [−16, 16] (the playback clock's range)
//   {"command": "loop", "loop": true|false}    also "on" / "off"
//   {"command": "exposure", "exposure": E}     E in (0, 1e6] as in scenes; null: the show's own again
//   {"command": "set", "body": B, "pointer": P, "value": V}
//       P a JSON pointer into body B's atmosphere parameters (docs/atmosphere-config.md),
//       V any JSON value (null removes the key); checked by the atmosphere loader when applied
//   {"command": "sun", "elevation_deg": E, "azimuth_deg": A}
//       E in [−90, 90], A in [−360, 360] as in scenes; either may be left out (it keeps its value)
//   {"command": "clear", "what": "sun" | "exposure" | "atmosphere", "body": B}
//       the operator's override ends: the show's (or scene's) own again; "body" with "atmosphere" only
//   {"command": "preview", "preview": true|false}   also "on" / "off": the dome preview from node thumbnails
//   {"command": "fade", "level": L, "seconds": S, "colour": [R, G, B]}
//       every output toward colour (display-linear, each in [0, 1]; default: the colour it has, black at first)
//       to level L in [0, 1] (default 1; 0: back to the picture) over S in [0, 3600] s
//       (cluster/operator/fade_control.h)
//   {"command": "blackout", "blackout": true|false}  also "on" / "off"; default true: black (or the picture) at the
//   next frame
//   {"command": "timecode", "offset": "hh:mm:ss:ff"}
//       a show chasing the house's timecode starts (show time 0) at that label from the next frame on;
//       hh [0, 23], mm and ss [0, 59], ff [0, 29] (the master checks the label against the show's rate)
// Unknown keys are errors.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include <nlohmann/json.hpp>

namespace zenith::cluster {

/// The longest command text accepted (bytes): a command is a few words, a
/// `set` value at most a small object of the atmosphere parameters.
inline constexpr std::size_t kMaxOperatorCommandBytes = 16 * 1024;

namespace operator_command {
struct Play {
  bool operator==(const Play&) const = default;
};
struct Pause {
  bool operator==(const Pause&) const = default;
};
struct Toggle {
  bool operator==(const Toggle&) const = default;
};
struct Status {
  bool operator==(const Status&) const = default;
};
struct Quit {
  bool operator==(const Quit&) const = default;
};
struct Seek {
  double seconds = 0.0;  ///< show time, finite, ≥ 0
  bool operator==(const Seek&) const = default;
};
struct Rate {
  double rate = 1.0;  ///< in [−16, 16]
  bool operator==(const Rate&) const = default;
};
struct Loop {
  bool on = false;
  bool operator==(const Loop&) const = default;
};
struct Exposure {
  std::optional<double> exposure;  ///< (0, 1e6]; nullopt: the show's (or scene's) exposure again
  bool operator==(const Exposure&) const = default;
};
struct Set {
  std::string body;                      ///< a body of the scene, 1..64 bytes
  nlohmann::json::json_pointer pointer;  ///< into the body's atmosphere parameters, not the root
  nlohmann::json value;                  ///< null removes the key
  bool operator==(const Set&) const = default;
};
/// The sun in the camera's local horizon (docs/scenes.md, "Frames and
/// conventions"); at least one of the two is given, the other keeps its value.
struct Sun {
  std::optional<double> elevation_deg;  ///< [−90, 90]
  std::optional<double> azimuth_deg;    ///< [−360, 360]
  bool operator==(const Sun&) const = default;
};
/// Ends one of the operator's overrides: the show's (or scene's) own again.
struct Clear {
  enum class What { sun, exposure, atmosphere };
  What what = What::sun;
  std::string body;  ///< What::atmosphere: a body of the scene, 1..64 bytes; empty otherwise
  bool operator==(const Clear&) const = default;
};
/// The dome preview from the nodes' thumbnails on or off (off costs nothing).
struct Preview {
  bool on = false;
  bool operator==(const Preview&) const = default;
};
/// Every output toward a colour (or back to the picture) over a time (docs/operator.md, "Fades").
struct Fade {
  double level = 1.0;                           ///< [0, 1]: 1 only the colour, 0 the picture
  double seconds = 0.0;                         ///< [0, kMaxFadeSeconds]
  std::optional<std::array<double, 3>> colour;  ///< display-linear RGB, each in [0, 1]; unset: keep the colour
  bool operator==(const Fade&) const = default;
};
/// Black at the next frame on every node (on), or the picture again (off).
struct Blackout {
  bool on = true;
  bool operator==(const Blackout&) const = default;
};
/// A chasing show's start on the house's timecode (docs/shows.md, "Chasing timecode").
struct TimecodeOffset {
  std::string label;  ///< "hh:mm:ss:ff" (or ";ff", ".ff"), fields in range for some rate
  bool operator==(const TimecodeOffset&) const = default;
};
}  // namespace operator_command

using OperatorCommand =
    std::variant<operator_command::Play, operator_command::Pause, operator_command::Toggle, operator_command::Status,
                 operator_command::Quit, operator_command::Seek, operator_command::Rate, operator_command::Loop,
                 operator_command::Exposure, operator_command::Set, operator_command::Sun, operator_command::Clear,
                 operator_command::Preview, operator_command::Fade, operator_command::Blackout,
                 operator_command::TimecodeOffset>;

/// Reads one command object. Throws zenith::ConfigError (file "command", the
/// key as a JSON pointer, the value and the allowed range) for anything else.
OperatorCommand parse_operator_command(const nlohmann::json& request);

/// Reads one command from JSON text (at most kMaxOperatorCommandBytes).
/// Throws zenith::ConfigError for syntax errors and everything
/// parse_operator_command refuses.
OperatorCommand parse_operator_command_text(std::string_view text);

/// The command as the JSON object parse_operator_command reads (its inverse).
nlohmann::json to_json(const OperatorCommand& command);

/// One line for logs and replies: "pause", "seek 12.5", "set Earth /aerosol/scattering/turbidity = 3".
std::string describe(const OperatorCommand& command);

}  // namespace zenith::cluster
