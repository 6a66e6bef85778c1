// The operator's JSON commands (cluster/operator/operator_command.h;
// docs/operator.md, "Commands"): every command, the errors naming the key and
// the range, and a property test of 100 000 mutated inputs.
#include "cluster/operator/operator_command.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "core/json_reader.h"

namespace zenith::cluster {
namespace {

namespace oc = operator_command;
using nlohmann::json;

OperatorCommand parse(const std::string& text) { return parse_operator_command_text(text); }

/// The message of the ConfigError parsing `text` throws ("" when it parses).
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(OperatorCommand, ReadsEveryCommand) {
  EXPECT_EQ(parse(R"({"command": "play"})"), OperatorCommand(oc::Play{}));
  EXPECT_EQ(parse(R"({"command": "pause"})"), OperatorCommand(oc::Pause{}));
  EXPECT_EQ(parse(R"({"command": "toggle"})"), OperatorCommand(oc::Toggle{}));
  EXPECT_EQ(parse(R"({"command": "status"})"), OperatorCommand(oc::Status{}));
  EXPECT_EQ(parse(R"({"command": "quit"})"), OperatorCommand(oc::Quit{}));
  EXPECT_EQ(parse(R"({"command": "seek", "seconds": 12.5})"), OperatorCommand(oc::Seek{12.5}));
  EXPECT_EQ(parse(R"({"command": "rate", "rate": -2})"), OperatorCommand(oc::Rate{-2.0}));
  EXPECT_EQ(parse(R"({"command": "loop", "loop": true})"), OperatorCommand(oc::Loop{true}));
  EXPECT_EQ(parse(R"({"command": "loop", "loop": "off"})"), OperatorCommand(oc::Loop{false}));
  EXPECT_EQ(parse(R"({"command": "exposure", "exposure": 25})"), OperatorCommand(oc::Exposure{25.0}));
  EXPECT_EQ(parse(R"({"command": "exposure", "exposure": null})"), OperatorCommand(oc::Exposure{std::nullopt}));
  const OperatorCommand set =
      parse(R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scattering/turbidity", "value": 3})");
  ASSERT_TRUE(std::holds_alternative<oc::Set>(set));
  EXPECT_EQ(std::get<oc::Set>(set).body, "Earth");
  EXPECT_EQ(std::get<oc::Set>(set).pointer.to_string(), "/aerosol/scattering/turbidity");
  EXPECT_EQ(std::get<oc::Set>(set).value, json(3));
  EXPECT_EQ(describe(set), "set Earth /aerosol/scattering/turbidity = 3");
  EXPECT_EQ(describe(parse(R"({"command": "seek", "seconds": 1.5})")), "seek 1.5");
  EXPECT_EQ(parse(R"({"command": "sun", "elevation_deg": -6, "azimuth_deg": 270})"),
            OperatorCommand(oc::Sun{-6.0, 270.0}));
  EXPECT_EQ(parse(R"({"command": "sun", "azimuth_deg": -90})"), OperatorCommand(oc::Sun{std::nullopt, -90.0}));
  EXPECT_EQ(describe(parse(R"({"command": "sun", "elevation_deg": 12.5})")), "sun elevation 12.5°");
  EXPECT_EQ(parse(R"({"command": "clear", "what": "sun"})"), OperatorCommand(oc::Clear{oc::Clear::What::sun, ""}));
  EXPECT_EQ(parse(R"({"command": "clear", "what": "exposure"})"),
            OperatorCommand(oc::Clear{oc::Clear::What::exposure, ""}));
  EXPECT_EQ(describe(parse(R"({"command": "clear", "what": "sun"})")), "clear sun");
  EXPECT_EQ(parse(R"({"command": "clear", "what": "atmosphere", "body": "Earth"})"),
            OperatorCommand(oc::Clear{oc::Clear::What::atmosphere, "Earth"}));
  EXPECT_EQ(describe(parse(R"({"command": "clear", "what": "atmosphere", "body": "Earth"})")),
            "clear atmosphere of Earth");
  EXPECT_EQ(parse(R"({"command": "preview", "preview": true})"), OperatorCommand(oc::Preview{true}));
  EXPECT_EQ(parse(R"({"command": "preview", "preview": "off"})"), OperatorCommand(oc::Preview{false}));
  EXPECT_EQ(describe(parse(R"({"command": "preview", "preview": "on"})")), "preview on");
  EXPECT_EQ(describe(parse(R"({"command": "set", "body": "Earth", "pointer": "/ozone", "value": null})")),
            "set Earth /ozone = null");
  EXPECT_EQ(parse(R"({"command": "timecode", "offset": "01:00:00:00"})"),
            OperatorCommand(oc::TimecodeOffset{"01:00:00:00"}));
  EXPECT_EQ(describe(parse(R"({"command": "timecode", "offset": "00:59:58;02"})")), "timecode offset 00:59:58;02");
}

TEST(OperatorCommand, ErrorsNameTheKeyTheValueAndTheRange) {
  EXPECT_EQ(error_of(R"({"command": "rate", "rate": 20})"), "command: /rate = 20: must be in [-16, 16]");
  EXPECT_EQ(error_of(R"({"command": "timecode", "offset": "25:00:00:00"})"),
            "command: /offset = \"25:00:00:00\": must be a timecode label hh:mm:ss:ff (or hh:mm:ss;ff), hours "
            "[0, 23], minutes and seconds [0, 59], frames [0, 29]");
  EXPECT_EQ(error_of(R"({"command": "seek", "seconds": -1})"), "command: /seconds = -1: must be in [0, 1e+09] s");
  EXPECT_EQ(error_of(R"({"command": "exposure", "exposure": 0})"), "command: /exposure = 0: must be in (0, 1e+06]");
  EXPECT_EQ(error_of(R"({"command": "exposure", "exposure": "bright"})"),
            "command: /exposure = \"bright\": must be a number in (0, 1e+06] or null");
  EXPECT_EQ(error_of(R"({"command": "seek"})"), "command: /seconds: missing required key");
  EXPECT_EQ(error_of(R"({"command": "pause", "seconds": 1})"),
            "command: /seconds: unknown key (check the spelling; see docs/atmosphere-config.md)");
  EXPECT_NE(error_of(R"({"command": "warp"})").find("command: /command = \"warp\": must be one of \"play\""),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"command": "loop", "loop": 1})"),
            "command: /loop = 1: must be true, false, \"on\" or \"off\"");
  EXPECT_NE(error_of(R"({"command": "set", "body": "Earth", "pointer": "aerosol", "value": 1})")
                .find("command: /pointer = \"aerosol\": must be a JSON pointer"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command": "set", "body": "Earth", "pointer": "", "value": 1})").find("not the whole set"),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"command": "set", "body": "Earth", "pointer": "/a"})"),
            "command: /value: missing required key");
  EXPECT_NE(error_of(R"({"command": "set", "body": "", "pointer": "/a", "value": 1})").find("must name a body"),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"command": "sun", "elevation_deg": 91})"),
            "command: /elevation_deg = 91: must be in [-90, 90] deg");
  EXPECT_EQ(error_of(R"({"command": "sun", "azimuth_deg": 400})"),
            "command: /azimuth_deg = 400: must be in [-360, 360] deg");
  EXPECT_NE(
      error_of(R"({"command": "sun"})").find("command: /elevation_deg: missing required key (a sun command gives"),
      std::string::npos);
  EXPECT_NE(
      error_of(R"({"command": "clear", "what": "moon"})").find("command: /what = \"moon\": must be one of \"sun\""),
      std::string::npos);
  EXPECT_EQ(error_of(R"({"command": "clear", "what": "atmosphere"})"), "command: /body: missing required key");
  EXPECT_EQ(error_of(R"({"command": "preview", "preview": 1})"),
            "command: /preview = 1: must be true, false, \"on\" or \"off\"");
  EXPECT_EQ(error_of(R"({"command": "clear", "what": "sun", "body": "Earth"})"),
            "command: /body: unknown key (check the spelling; see docs/atmosphere-config.md)");
  EXPECT_NE(error_of(R"(["pause"])").find("must be a JSON object"), std::string::npos);
  EXPECT_NE(error_of(R"({"command": "pause")").find("command: (top level): not valid JSON"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMaxOperatorCommandBytes + 1, ' ')).find("at most"), std::string::npos);
  std::string deep = R"({"command": "set", "body": "Earth", "pointer": "/a", "value": )";
  deep += std::string(40, '[') + std::string(40, ']') + "}";
  EXPECT_NE(error_of(deep).find("more than 16 levels deep"), std::string::npos);
}

TEST(OperatorCommand, ReadsFadesAndBlackouts) {
  EXPECT_EQ(parse(R"({"command": "fade", "seconds": 3})"), OperatorCommand(oc::Fade{1.0, 3.0, std::nullopt}));
  EXPECT_EQ(parse(R"({"command": "fade", "level": 0, "seconds": 0.5})"),
            OperatorCommand(oc::Fade{0.0, 0.5, std::nullopt}));
  EXPECT_EQ(parse(R"({"command": "fade", "level": 0.5, "seconds": 2, "colour": [1, 0.5, 0]})"),
            OperatorCommand(oc::Fade{0.5, 2.0, std::array<double, 3>{1.0, 0.5, 0.0}}));
  EXPECT_EQ(describe(parse(R"({"command": "fade", "level": 1, "seconds": 2, "colour": [1, 0, 0]})")),
            "fade to level 1.0 over 2.0 s toward [1.0, 0.0, 0.0]");
  EXPECT_EQ(parse(R"({"command": "blackout"})"), OperatorCommand(oc::Blackout{true}));
  EXPECT_EQ(parse(R"({"command": "blackout", "blackout": "off"})"), OperatorCommand(oc::Blackout{false}));
  EXPECT_EQ(describe(parse(R"({"command": "blackout", "blackout": false})")), "blackout off");
  // Ranges in the errors: duration ≥ 0 (at most an hour), level and colour components in [0, 1].
  EXPECT_EQ(error_of(R"({"command": "fade", "seconds": -1})"), "command: /seconds = -1: must be in [0, 3600] s");
  EXPECT_EQ(error_of(R"({"command": "fade", "level": 2, "seconds": 1})"), "command: /level = 2: must be in [0, 1]");
  EXPECT_EQ(error_of(R"({"command": "fade", "level": 1})"), "command: /seconds: missing required key");
  EXPECT_EQ(
      error_of(R"({"command": "fade", "seconds": 1, "colour": [1, 1.5, 0]})"),
      "command: /colour = [1,1.5,0]: must be [r, g, b], each a number in [0, 1] (display-linear; [0, 0, 0] black)");
  EXPECT_NE(error_of(R"({"command": "fade", "seconds": 1, "colour": "red"})").find("must be [r, g, b]"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"command": "fade", "seconds": 1, "color": [0, 0, 0]})").find("/color: unknown key"),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"command": "blackout", "blackout": 2})"),
            "command: /blackout = 2: must be true, false, \"on\" or \"off\"");
}

TEST(OperatorCommand, ToJsonIsTheInverseOfParsing) {
  for (const char* text :
       {R"({"command": "play"})", R"({"command": "seek", "seconds": 3})", R"({"command": "rate", "rate": 0.5})",
        R"({"command": "loop", "loop": "on"})", R"({"command": "exposure", "exposure": null})",
        R"({"command": "exposure", "exposure": 1e6})", R"({"command": "sun", "elevation_deg": 5})",
        R"({"command": "sun", "elevation_deg": -5, "azimuth_deg": 90})", R"({"command": "clear", "what": "exposure"})",
        R"({"command": "clear", "what": "atmosphere", "body": "Earth"})", R"({"command": "preview", "preview": false})",
        R"({"command": "fade", "level": 0.25, "seconds": 1.5, "colour": [0, 0.5, 1]})",
        R"({"command": "fade", "seconds": 0})", R"({"command": "blackout", "blackout": "on"})",
        R"({"command": "timecode", "offset": "10:00:00:00"})",
        R"({"command": "set", "body": "Mars", "pointer": "/planet/ground_albedo", "value": {"680": 0.3}})"}) {
    const OperatorCommand command = parse(text);
    EXPECT_EQ(parse_operator_command(to_json(command)), command) << text;
  }
}

// ---- property test -----------------------------------------------------------

/// Valid commands to mutate.
const std::vector<std::string> kSeeds = {
    R"({"command": "play"})",
    R"({"command": "pause"})",
    R"({"command": "seek", "seconds": 12.5})",
    R"({"command": "rate", "rate": -2})",
    R"({"command": "loop", "loop": true})",
    R"({"command": "exposure", "exposure": 25})",
    R"({"command": "exposure", "exposure": null})",
    R"({"command": "set", "body": "Earth", "pointer": "/aerosol/scattering/turbidity", "value": 3})",
    R"({"command": "set", "body": "Earth", "pointer": "/ozone", "value": {"profile": "us_standard_1976"}})",
    R"({"command": "quit"})",
    R"({"command": "sun", "elevation_deg": 10, "azimuth_deg": 250})",
    R"({"command": "clear", "what": "sun"})",
    R"({"command": "clear", "what": "atmosphere", "body": "Earth"})",
    R"({"command": "preview", "preview": true})",
    R"({"command": "timecode", "offset": "01:00:00:00"})",
};

/// Pieces a mutation inserts: JSON punctuation, keys, values at and beyond the ranges' edges.
const std::vector<std::string> kPieces = {"{",
                                          "}",
                                          "[",
                                          "]",
                                          ",",
                                          ":",
                                          "\"",
                                          "\\",
                                          "null",
                                          "true",
                                          "false",
                                          "-",
                                          "0",
                                          "1e999",
                                          "-1e-999",
                                          "16.0000001",
                                          "1e6",
                                          "1e309",
                                          "NaN",
                                          "\"command\"",
                                          "\"seconds\"",
                                          "\"rate\"",
                                          "\"value\"",
                                          "\"pointer\"",
                                          "\"/\"",
                                          "\"~\"",
                                          "\"/~2\"",
                                          "\"\\u0000\"",
                                          "\"\\ud800\"",
                                          "\xff",
                                          "\xc3\x28",
                                          "18446744073709551616",
                                          "-9223372036854775809",
                                          "[[[[[[[[[[[[[[[[[[",
                                          "\"set\"",
                                          "\"loop\"",
                                          "\"on\"",
                                          "\"elevation_deg\"",
                                          "\"azimuth_deg\"",
                                          "90.0000001",
                                          "-360",
                                          "\"what\"",
                                          "\"sun\""};

std::string mutate(std::string text, std::mt19937_64& rng) {
  const auto below = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  const std::size_t mutations = 1 + below(4);
  for (std::size_t m = 0; m < mutations; ++m) {
    const std::size_t at = text.empty() ? 0 : below(text.size() + 1);
    switch (below(6)) {
      case 0:  // flip a bit
        if (!text.empty()) text[below(text.size())] ^= static_cast<char>(1u << below(8));
        break;
      case 1:  // delete a span
        if (!text.empty()) text.erase(below(text.size()), 1 + below(8));
        break;
      case 2: text.insert(at, kPieces[below(kPieces.size())]); break;
      case 3: text.insert(at, 1, static_cast<char>(below(256))); break;
      case 4: text = text.substr(0, at); break;  // truncate
      case 5: {                                  // replace a number or string by a piece
        const std::size_t colon = text.find(':', at);
        if (colon != std::string::npos) {
          const std::size_t end = text.find_first_of(",}", colon);
          text.replace(colon + 1, end == std::string::npos ? std::string::npos : end - colon - 1,
                       kPieces[below(kPieces.size())]);
        }
        break;
      }
    }
  }
  return text;
}

TEST(OperatorCommandProperty, HundredThousandMutationsParseOrFailCleanlyAndRoundTrip) {
  std::mt19937_64 rng(20240716);
  std::size_t accepted = 0, refused = 0;
  for (int i = 0; i < 100000; ++i) {
    const std::string text = mutate(kSeeds[rng() % kSeeds.size()], rng);
    try {
      const OperatorCommand command = parse(text);
      ++accepted;
      // What parses is well-formed: it describes itself and reads back the same.
      EXPECT_FALSE(describe(command).empty());
      EXPECT_EQ(parse_operator_command(to_json(command)), command) << text;
      if (const auto* rate = std::get_if<oc::Rate>(&command)) {
        EXPECT_LE(std::abs(rate->rate), 16.0) << text;
      }
      if (const auto* exposure = std::get_if<oc::Exposure>(&command); exposure && exposure->exposure) {
        EXPECT_GT(*exposure->exposure, 0.0) << text;
      }
      if (const auto* set = std::get_if<oc::Set>(&command)) {
        EXPECT_FALSE(set->pointer.empty()) << text;
      }
    } catch (const ConfigError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind("command: ", 0), 0u) << "every error names the command: " << e.what();
    }
    // Anything else escaping fails the test (gtest reports the exception).
  }
  EXPECT_GT(accepted, 1000u) << "the mutations leave some commands valid";
  EXPECT_GT(refused, 50000u);
}

}  // namespace
}  // namespace zenith::cluster
