#include "cluster/operator/operator_command.h"

#include <cmath>
#include <sstream>

#include "cluster/operator/fade_control.h"
#include "core/json_reader.h"
#include "core/strings.h"
#include "scene/scene.h"
#include "show/playback_clock.h"
#include "show/timecode/timecode.h"

namespace zenith::cluster {
namespace {

using config::brief;
using core::cat;
using nlohmann::json;
namespace oc = operator_command;

/// The name errors give as their "file".
constexpr const char* kSource = "command";
/// The furthest a seek may ask for (s); the master then checks the show's duration.
constexpr double kMaxSeekSeconds = 1e9;
/// The deepest nesting of arrays and objects a command may have (a `set` value
/// is at most a block of the atmosphere parameters, three or four levels).
constexpr int kMaxDepth = 16;
/// Body names: 1..64 bytes, as on the wire (AtmosphereTableRef).
constexpr std::size_t kMaxBodyBytes = 64;

const std::vector<std::string> kCommands = {"play",    "pause", "toggle",   "status",  "quit", "seek",
                                            "rate",    "loop",  "exposure", "set",     "sun",  "clear",
                                            "preview", "fade",  "blackout", "timecode"};
/// What `clear` ends.
const std::vector<std::string> kClearable = {"sun", "exposure", "atmosphere"};
/// The ranges of a sun given in the sky, as in scene files (docs/scenes.md).
constexpr double kMaxElevationDeg = 90.0;
constexpr double kMaxAzimuthDeg = 360.0;

/// Whether `value` nests arrays and objects deeper than `limit` levels.
bool deeper_than(const json& value, int limit) {
  if (!value.is_structured()) return false;
  if (limit == 0) return true;
  for (const json& child : value)
    if (deeper_than(child, limit - 1)) return true;
  return false;
}

/// `{"loop": true}`, or "on" / "off".
bool read_on_off(JsonReader& r, const std::string& key) {
  const json& v = r.raw(key);
  if (v.is_boolean()) return v.get<bool>();
  if (v.is_string() && v.get<std::string>() == "on") return true;
  if (v.is_string() && v.get<std::string>() == "off") return false;
  r.fail(key, cat("= ", brief(v), ": must be true, false, \"on\" or \"off\""));
}

/// An exposure in (0, kMaxExposure], or null for the show's own.
std::optional<double> read_exposure(JsonReader& r) {
  const json& v = r.raw("exposure");
  if (v.is_null()) return std::nullopt;
  std::ostringstream range;
  range << "(0, " << scene::kMaxExposure << "]";
  if (!v.is_number()) r.fail("exposure", cat("= ", brief(v), ": must be a number in ", range.str(), " or null"));
  const double x = v.get<double>();
  if (!(std::isfinite(x) && x > 0.0 && x <= scene::kMaxExposure))
    r.fail("exposure", cat("= ", brief(v), ": must be in ", range.str()));
  return x;
}

/// The JSON name of what `clear` ends.
const char* clear_target(oc::Clear::What what) {
  switch (what) {
    case oc::Clear::What::sun: return "sun";
    case oc::Clear::What::exposure: return "exposure";
    case oc::Clear::What::atmosphere: return "atmosphere";
  }
  return "sun";
}

/// A body name of a command: 1..kMaxBodyBytes bytes.
std::string read_body(JsonReader& r) {
  std::string body = r.string("body");
  if (body.empty() || body.size() > kMaxBodyBytes)
    r.fail("body", cat("= ", brief(json(body)), ": must name a body of the scene (1 to ", kMaxBodyBytes, " bytes)"));
  return body;
}

/// `sun`: an elevation, an azimuth, or both.
oc::Sun read_sun(JsonReader& r) {
  oc::Sun sun;
  if (r.has("elevation_deg")) sun.elevation_deg = r.number("elevation_deg", -kMaxElevationDeg, kMaxElevationDeg, "deg");
  if (r.has("azimuth_deg")) sun.azimuth_deg = r.number("azimuth_deg", -kMaxAzimuthDeg, kMaxAzimuthDeg, "deg");
  if (!sun.elevation_deg && !sun.azimuth_deg)
    r.fail("elevation_deg",
           "missing required key (a sun command gives \"elevation_deg\" in [-90, 90], \"azimuth_deg\" in "
           "[-360, 360], or both; the sun's own again: {\"command\": \"clear\", \"what\": \"sun\"})");
  return sun;
}

/// `clear`: what, and the body of an atmosphere.
oc::Clear read_clear(JsonReader& r) {
  oc::Clear clear;
  const std::string what = r.string("what", kClearable);
  clear.what = what == "sun"        ? oc::Clear::What::sun
               : what == "exposure" ? oc::Clear::What::exposure
                                    : oc::Clear::What::atmosphere;
  if (clear.what == oc::Clear::What::atmosphere) clear.body = read_body(r);
  return clear;
}

/// `set`: a body, a JSON pointer that is not the root, any value.
oc::Set read_set(JsonReader& r) {
  oc::Set set;
  set.body = read_body(r);
  const std::string text = r.string("pointer");
  try {
    set.pointer = json::json_pointer(text);
  } catch (const json::exception&) {
    r.fail("pointer", cat("= ", brief(json(text)),
                          ": must be a JSON pointer into the atmosphere's parameters, such as "
                          "\"/aerosol/scattering/turbidity\" (docs/atmosphere-config.md)"));
  }
  if (set.pointer.empty())
    r.fail("pointer", "= \"\": must name one parameter, such as \"/aerosol/scattering/turbidity\", not the whole set");
  set.value = r.raw("value");
  return set;
}

/// `fade`: a level (default 1), a duration, maybe a colour.
oc::Fade read_fade(JsonReader& r) {
  oc::Fade fade;
  fade.level = r.has("level") ? r.number("level", 0.0, scene::kMaxFadeLevel) : 1.0;
  fade.seconds = r.number("seconds", 0.0, kMaxFadeSeconds, "s");
  if (r.has("colour")) {
    const json& c = r.raw("colour");
    const auto bad = [&] {
      r.fail("colour",
             cat("= ", brief(c), ": must be [r, g, b], each a number in [0, 1] (display-linear; [0, 0, 0] black)"));
    };
    if (!c.is_array() || c.size() != 3) bad();
    std::array<double, 3> rgb{};
    for (std::size_t i = 0; i < 3; ++i) {
      if (!c[i].is_number()) bad();
      rgb[i] = c[i].get<double>();
      if (!(rgb[i] >= 0.0 && rgb[i] <= 1.0)) bad();
    }
    fade.colour = rgb;
  }
  return fade;
}

/// "1.5" for 1.5, as JSON writes numbers.
std::string number_text(double x) { return json(x).dump(); }

/// `timecode`: the offset's label, in the ranges of the rate with the most
/// labels a second (30); the master checks it against the show's own rate.
oc::TimecodeOffset read_timecode_offset(JsonReader& r) {
  const std::string label = r.string("offset");
  try {
    show::parse_timecode(label, show::TimecodeRate::fps30);
  } catch (const std::invalid_argument&) {
    r.fail("offset", cat("= ", brief(json(label)),
                         ": must be a timecode label hh:mm:ss:ff (or hh:mm:ss;ff), hours [0, 23], minutes and seconds "
                         "[0, 59], frames [0, 29]"));
  }
  return {label};
}

}  // namespace

OperatorCommand parse_operator_command(const json& request) {
  if (!request.is_object())
    throw ConfigError(kSource, "", cat("must be a JSON object such as {\"command\": \"pause\"}, got ", brief(request)));
  if (deeper_than(request, kMaxDepth))
    throw ConfigError(kSource, "", cat("nests arrays and objects more than ", kMaxDepth, " levels deep"));
  JsonReader r(request, kSource);
  const std::string name = r.string("command", kCommands);
  OperatorCommand command;
  if (name == "play")
    command = oc::Play{};
  else if (name == "pause")
    command = oc::Pause{};
  else if (name == "toggle")
    command = oc::Toggle{};
  else if (name == "status")
    command = oc::Status{};
  else if (name == "quit")
    command = oc::Quit{};
  else if (name == "seek")
    command = oc::Seek{r.number("seconds", 0.0, kMaxSeekSeconds, "s")};
  else if (name == "rate")
    command = oc::Rate{r.number("rate", -show::PlaybackClock::kMaxRate, show::PlaybackClock::kMaxRate)};
  else if (name == "loop")
    command = oc::Loop{read_on_off(r, "loop")};
  else if (name == "exposure")
    command = oc::Exposure{read_exposure(r)};
  else if (name == "sun")
    command = read_sun(r);
  else if (name == "clear")
    command = read_clear(r);
  else if (name == "preview")
    command = oc::Preview{read_on_off(r, "preview")};
  else if (name == "fade")
    command = read_fade(r);
  else if (name == "blackout")
    command = oc::Blackout{r.has("blackout") ? read_on_off(r, "blackout") : true};
  else if (name == "timecode")
    command = read_timecode_offset(r);
  else
    command = read_set(r);
  r.finish();
  return command;
}

OperatorCommand parse_operator_command_text(std::string_view text) {
  if (text.size() > kMaxOperatorCommandBytes)
    throw ConfigError(kSource, "",
                      cat("is ", text.size(), " bytes long: at most ", kMaxOperatorCommandBytes, " are read"));
  return parse_operator_command(parse_json(std::string(text), kSource));
}

json to_json(const OperatorCommand& command) {
  return std::visit(
      [](const auto& c) -> json {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, oc::Play>)
          return {{"command", "play"}};
        else if constexpr (std::is_same_v<T, oc::Pause>)
          return {{"command", "pause"}};
        else if constexpr (std::is_same_v<T, oc::Toggle>)
          return {{"command", "toggle"}};
        else if constexpr (std::is_same_v<T, oc::Status>)
          return {{"command", "status"}};
        else if constexpr (std::is_same_v<T, oc::Quit>)
          return {{"command", "quit"}};
        else if constexpr (std::is_same_v<T, oc::Seek>)
          return {{"command", "seek"}, {"seconds", c.seconds}};
        else if constexpr (std::is_same_v<T, oc::Rate>)
          return {{"command", "rate"}, {"rate", c.rate}};
        else if constexpr (std::is_same_v<T, oc::Loop>)
          return {{"command", "loop"}, {"loop", c.on}};
        else if constexpr (std::is_same_v<T, oc::Exposure>)
          return {{"command", "exposure"}, {"exposure", c.exposure ? json(*c.exposure) : json(nullptr)}};
        else if constexpr (std::is_same_v<T, oc::Set>)
          return {{"command", "set"}, {"body", c.body}, {"pointer", c.pointer.to_string()}, {"value", c.value}};
        else if constexpr (std::is_same_v<T, oc::Sun>) {
          json j = {{"command", "sun"}};
          if (c.elevation_deg) j["elevation_deg"] = *c.elevation_deg;
          if (c.azimuth_deg) j["azimuth_deg"] = *c.azimuth_deg;
          return j;
        } else if constexpr (std::is_same_v<T, oc::Clear>) {
          json j = {{"command", "clear"}, {"what", clear_target(c.what)}};
          if (c.what == oc::Clear::What::atmosphere) j["body"] = c.body;
          return j;
        } else if constexpr (std::is_same_v<T, oc::Fade>) {
          json j = {{"command", "fade"}, {"level", c.level}, {"seconds", c.seconds}};
          if (c.colour) j["colour"] = *c.colour;
          return j;
        } else if constexpr (std::is_same_v<T, oc::Blackout>)
          return {{"command", "blackout"}, {"blackout", c.on}};
        else if constexpr (std::is_same_v<T, oc::TimecodeOffset>)
          return {{"command", "timecode"}, {"offset", c.label}};
        else
          return {{"command", "preview"}, {"preview", c.on}};
      },
      command);
}

std::string describe(const OperatorCommand& command) {
  return std::visit(
      [](const auto& c) -> std::string {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, oc::Play>)
          return "play";
        else if constexpr (std::is_same_v<T, oc::Pause>)
          return "pause";
        else if constexpr (std::is_same_v<T, oc::Toggle>)
          return "toggle";
        else if constexpr (std::is_same_v<T, oc::Status>)
          return "status";
        else if constexpr (std::is_same_v<T, oc::Quit>)
          return "quit";
        else if constexpr (std::is_same_v<T, oc::Seek>)
          return cat("seek ", number_text(c.seconds));
        else if constexpr (std::is_same_v<T, oc::Rate>)
          return cat("rate ", number_text(c.rate));
        else if constexpr (std::is_same_v<T, oc::Loop>)
          return cat("loop ", c.on ? "on" : "off");
        else if constexpr (std::is_same_v<T, oc::Exposure>)
          return c.exposure ? cat("exposure ", number_text(*c.exposure)) : std::string("exposure of the show");
        else if constexpr (std::is_same_v<T, oc::Set>)
          return cat("set ", c.body, " ", c.pointer.to_string(), " = ", brief(c.value));
        else if constexpr (std::is_same_v<T, oc::Sun>) {
          std::string text = "sun";
          if (c.elevation_deg) text += cat(" elevation ", number_text(*c.elevation_deg), "°");
          if (c.azimuth_deg) text += cat(" azimuth ", number_text(*c.azimuth_deg), "°");
          return text;
        } else if constexpr (std::is_same_v<T, oc::Clear>)
          return c.what == oc::Clear::What::atmosphere ? cat("clear atmosphere of ", c.body)
                                                       : cat("clear ", clear_target(c.what));
        else if constexpr (std::is_same_v<T, oc::Fade>) {
          std::string text = cat("fade to level ", number_text(c.level), " over ", number_text(c.seconds), " s");
          if (c.colour)
            text += cat(" toward [", number_text((*c.colour)[0]), ", ", number_text((*c.colour)[1]), ", ",
                        number_text((*c.colour)[2]), "]");
          return text;
        } else if constexpr (std::is_same_v<T, oc::Blackout>)
          return cat("blackout ", c.on ? "on" : "off");
        else if constexpr (std::is_same_v<T, oc::TimecodeOffset>)
          return cat("timecode offset ", c.label);
        else
          return cat("preview ", c.on ? "on" : "off");
      },
      command);
}

}  // namespace zenith::cluster
