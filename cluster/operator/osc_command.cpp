#include "cluster/operator/osc_command.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "core/json_reader.h"
#include "core/strings.h"

namespace zenith::cluster {
namespace {

using core::cat;
using nlohmann::json;

constexpr std::string_view kPrefix = "/zenith/";
constexpr std::string_view kAtmosphere = "/zenith/atmosphere/";

[[noreturn]] void refuse(const OscMessage& m, const std::string& why) {
  throw std::invalid_argument(cat("OSC ", m.address, ": ", why));
}

/// A float as the decimal it was typed as: 7 significant digits (3.1f is 3.1, not 3.0999999).
double float_value(float f) {
  char text[32];
  std::snprintf(text, sizeof text, "%.7g", static_cast<double>(f));
  return std::strtod(text, nullptr);
}

/// Printable ASCII (strings become JSON, which must be valid UTF-8).
bool printable(const std::string& s) {
  for (const char c : s)
    if (c < 0x20 || c > 0x7e) return false;
  return true;
}

/// The single argument as a JSON value: numbers, booleans, printable strings, nil as null.
json value_of(const OscMessage& m) {
  if (m.arguments.size() != 1) refuse(m, cat("takes one argument, got ", m.arguments.size()));
  return std::visit(
      [&](const auto& v) -> json {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>)
          return nullptr;
        else if constexpr (std::is_same_v<T, std::int32_t> || std::is_same_v<T, std::int64_t> ||
                           std::is_same_v<T, bool> || std::is_same_v<T, double>)
          return v;
        else if constexpr (std::is_same_v<T, float>)
          return float_value(v);
        else if constexpr (std::is_same_v<T, std::string>) {
          if (!printable(v)) refuse(m, "a string argument must be printable ASCII");
          return v;
        } else {
          refuse(m, cat("cannot take ", describe(OscArgument(v)), " (a number, T, F, a string or N)"));
        }
      },
      m.arguments[0]);
}

/// Argument `i` as a number (int, float, double).
json number_at(const OscMessage& m, std::size_t i, const char* what) {
  return std::visit(
      [&](const auto& v) -> json {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::int32_t> || std::is_same_v<T, std::int64_t> || std::is_same_v<T, double>)
          return v;
        else if constexpr (std::is_same_v<T, float>)
          return float_value(v);
        else
          refuse(m, cat("argument ", i + 1, " (", what, ") must be a number, got ", describe(OscArgument(v))));
      },
      m.arguments[i]);
}

/// `/zenith/fade LEVEL SECONDS [R G B]`: to LEVEL (0 the picture, 1 the colour) over SECONDS, toward R G B.
json fade_request(const OscMessage& m) {
  const std::size_t n = m.arguments.size();
  if (n != 2 && n != 5)
    refuse(m, cat("takes LEVEL SECONDS or LEVEL SECONDS R G B (level 0 the picture, 1 only the colour; colour "
                  "display-linear, each in [0, 1]), got ",
                  n, " argument", n == 1 ? "" : "s"));
  json request = {{"command", "fade"}, {"level", number_at(m, 0, "level")}, {"seconds", number_at(m, 1, "seconds")}};
  if (n == 5) request["colour"] = {number_at(m, 2, "red"), number_at(m, 3, "green"), number_at(m, 4, "blue")};
  return request;
}

}  // namespace

OperatorCommand osc_command(const OscMessage& m) {
  if (!m.address.starts_with(kPrefix)) refuse(m, "not a zenith address (they start with /zenith/)");
  const std::string name = m.address.substr(kPrefix.size());
  json request;
  if (name == "play" || name == "pause" || name == "toggle") {
    request = {{"command", name}};
  } else if (name == "seek") {
    request = {{"command", "seek"}, {"seconds", value_of(m)}};
  } else if (name == "rate") {
    request = {{"command", "rate"}, {"rate", value_of(m)}};
  } else if (name == "exposure") {
    request = {{"command", "exposure"}, {"exposure", value_of(m)}};
  } else if (name == "loop") {
    json on = value_of(m);
    if (on.is_number_integer()) on = on.get<std::int64_t>() != 0;
    request = {{"command", "loop"}, {"loop", on}};
  } else if (name == "preview") {
    json on = value_of(m);
    if (on.is_number_integer()) on = on.get<std::int64_t>() != 0;
    request = {{"command", "preview"}, {"preview", on}};
  } else if (name == "fade") {
    request = fade_request(m);
  } else if (name == "blackout") {  // no argument: on; 1 / 0, T / F, "on" / "off"
    json on = m.arguments.empty() ? json(true) : value_of(m);
    if (on.is_number_integer()) on = on.get<std::int64_t>() != 0;
    request = {{"command", "blackout"}, {"blackout", on}};
  } else if (name == "timecode/offset") {  // a label such as "01:00:00:00"
    request = {{"command", "timecode"}, {"offset", value_of(m)}};
  } else if (name == "sun/elevation") {
    request = {{"command", "sun"}, {"elevation_deg", value_of(m)}};
  } else if (name == "sun/azimuth") {
    request = {{"command", "sun"}, {"azimuth_deg", value_of(m)}};
  } else if (name == "clear/sun" || name == "clear/exposure") {
    request = {{"command", "clear"}, {"what", name.substr(6)}};
  } else if (name.starts_with("clear/atmosphere/")) {
    request = {{"command", "clear"}, {"what", "atmosphere"}, {"body", name.substr(17)}};
  } else if (m.address.starts_with(kAtmosphere)) {
    const std::string rest = m.address.substr(kAtmosphere.size());  // "<body>/<pointer>"
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == rest.size())
      refuse(m,
             "expected /zenith/atmosphere/<body>/<parameter>, such as "
             "/zenith/atmosphere/Earth/aerosol/scattering/turbidity");
    request = {
        {"command", "set"}, {"body", rest.substr(0, slash)}, {"pointer", rest.substr(slash)}, {"value", value_of(m)}};
  } else {
    refuse(m,
           "unknown address (known: /zenith/play, /zenith/pause, /zenith/toggle, /zenith/seek, /zenith/rate, "
           "/zenith/exposure, /zenith/loop, /zenith/preview, /zenith/fade, /zenith/blackout, /zenith/timecode/offset, "
           "/zenith/sun/elevation, "
           "/zenith/sun/azimuth, /zenith/clear/sun, "
           "/zenith/clear/exposure, /zenith/clear/atmosphere/<body>, /zenith/atmosphere/<body>/<parameter>)");
  }
  return parse_operator_command(request);
}

}  // namespace zenith::cluster
