// OSC for show-control desks (cluster/operator/osc_packet.h, osc_command.h,
// osc_receiver.h; docs/operator.md, "OSC"): the decoder against hand-made
// packets, a property test of 200 000 mutated packets, the addresses and the
// allowed senders.
#include <gtest/gtest.h>

#include <random>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/address.hpp>

#include "cluster/operator/osc_command.h"
#include "cluster/operator/osc_packet.h"
#include "cluster/operator/osc_receiver.h"
#include "core/json_reader.h"
#include "core/strings.h"
#include "tests/cluster/captured_log.h"

namespace zenith::cluster {
namespace {

namespace oc = operator_command;
using Bytes = std::vector<std::uint8_t>;

Bytes bytes(std::string_view text) { return Bytes(text.begin(), text.end()); }

TEST(OscPacket, DecodesAMessageByteForByte) {
  // "/zenith/seek" ",f" 12.5 — as a desk sends it.
  Bytes packet = bytes(std::string_view("/zenith/seek\0\0\0\0,f\0\0\x41\x48\0\0", 24));
  const std::vector<OscMessage> messages = decode_osc_packet(packet);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].address, "/zenith/seek");
  ASSERT_EQ(messages[0].arguments.size(), 1u);
  EXPECT_EQ(std::get<float>(messages[0].arguments[0]), 12.5f);
  EXPECT_EQ(encode_osc_message(messages[0]), packet);
}

TEST(OscPacket, EveryArgumentTypeAndNestedBundlesRoundTrip) {
  const OscMessage all{"/zenith/x",
                       {std::int32_t{-7}, std::int64_t{1} << 40, 1.5f, -2.25, true, false, std::string("pickering"),
                        OscBlob{{1, 2, 3}}, std::monostate{}, OscWord{'t', 99}, OscWord{'m', 0x90407f00}}};
  const OscMessage play{"/zenith/play", {}};
  const Bytes inner = encode_osc_bundle({encode_osc_message(play)});
  const Bytes packet = encode_osc_bundle({encode_osc_message(all), inner});
  const std::vector<OscMessage> messages = decode_osc_packet(packet);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0], all);
  EXPECT_EQ(messages[1], play);
  // A message without a type tag string (old senders) has no arguments.
  EXPECT_EQ(decode_osc_packet(bytes(std::string_view("/zenith/play\0\0\0\0", 16)))[0], play);
}

TEST(OscPacket, ErrorsNameTheByteOffset) {
  const auto error_of = [](const Bytes& packet) {
    try {
      decode_osc_packet(packet);
    } catch (const OscError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of({}), "OSC packet, byte 0: empty");
  EXPECT_EQ(error_of(bytes("/zen")), "OSC packet, byte 0: a string without its terminating NUL");
  EXPECT_EQ(error_of(bytes(std::string_view("/a\0\0,f\0\0\0\0", 10))),
            "OSC packet, byte 0: an element of 10 bytes: OSC sizes are multiples of 4");
  EXPECT_EQ(error_of(bytes(std::string_view("/a\0\0,f\0\0", 8))),
            "OSC packet, byte 8: 4 bytes needed, the packet ends");
  EXPECT_EQ(error_of(bytes(std::string_view("/a\0\0,[\0\0", 8))),
            "OSC packet, byte 8: type tag '[' is not supported (i f s S b h d t T F N I c r m are)");
  EXPECT_EQ(error_of(bytes(std::string_view("/a b\0\0\0\0", 8))).find("address \"/a b\""), 20u);
  EXPECT_EQ(error_of(bytes(std::string_view("/ab\0,i\0\0\0\0\0\1\0\0\0\0", 16))),
            "OSC packet, byte 12: 4 bytes after the last argument");
  Bytes deep = encode_osc_message({"/zenith/play", {}});
  for (int i = 0; i < kMaxOscBundleDepth + 1; ++i) deep = encode_osc_bundle({deep});
  EXPECT_NE(error_of(deep).find("bundles nested more than 8 deep"), std::string::npos);
}

TEST(OscPacketProperty, TwoHundredThousandMutationsNeverCrashAndFailOnlyWithOscError) {
  std::mt19937_64 rng(20240717);
  const auto below = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  const std::vector<Bytes> seeds = {
      encode_osc_message({"/zenith/seek", {12.5f}}),
      encode_osc_message({"/zenith/atmosphere/Earth/aerosol/scattering/turbidity", {3.0f}}),
      encode_osc_message(
          {"/zenith/x", {std::int32_t{1}, std::int64_t{2}, 3.0, std::string("s"), OscBlob{{9, 9}}, true}}),
      encode_osc_bundle({encode_osc_message({"/zenith/pause", {}}), encode_osc_message({"/zenith/rate", {2.0f}})}),
  };
  std::size_t decoded = 0, refused = 0;
  for (int i = 0; i < 200000; ++i) {
    Bytes p = seeds[below(seeds.size())];
    const std::size_t mutations = 1 + below(4);
    for (std::size_t m = 0; m < mutations; ++m) {
      switch (below(5)) {
        case 0:
          if (!p.empty()) p[below(p.size())] ^= static_cast<std::uint8_t>(1u << below(8));
          break;
        case 1:
          if (!p.empty()) p.erase(p.begin() + static_cast<std::ptrdiff_t>(below(p.size())));
          break;
        case 2:
          p.insert(p.begin() + static_cast<std::ptrdiff_t>(below(p.size() + 1)), static_cast<std::uint8_t>(below(256)));
          break;
        case 3: p.resize(below(p.size() + 1)); break;
        case 4:  // a size or length field set to something large
          if (p.size() >= 4) {
            const std::size_t at = below(p.size() / 4) * 4;
            p[at] = static_cast<std::uint8_t>(below(256));
            p[at + 1] = 0xff;
          }
          break;
      }
    }
    try {
      const std::vector<OscMessage> messages = decode_osc_packet(p);
      ++decoded;
      EXPECT_LE(messages.size(), kMaxOscMessages);
      for (const OscMessage& m : messages) {
        EXPECT_EQ(m.address.front(), '/');
        for (const OscArgument& a : m.arguments) EXPECT_FALSE(describe(a).empty());
        try {
          osc_command(m);  // what decodes maps to a command or a clean refusal
        } catch (const ConfigError&) {
        } catch (const std::invalid_argument&) {
        }
      }
    } catch (const OscError&) {
      ++refused;
    }
  }
  EXPECT_GT(decoded, 1000u);
  EXPECT_GT(refused, 100000u);
}

TEST(OscCommand, AddressesBecomeTheApisCommandsWithItsRanges) {
  EXPECT_EQ(osc_command({"/zenith/play", {}}), OperatorCommand(oc::Play{}));
  EXPECT_EQ(osc_command({"/zenith/pause", {1.0f}}), OperatorCommand(oc::Pause{}));
  EXPECT_EQ(osc_command({"/zenith/seek", {12.5f}}), OperatorCommand(oc::Seek{12.5}));
  EXPECT_EQ(osc_command({"/zenith/rate", {std::int32_t{-2}}}), OperatorCommand(oc::Rate{-2.0}));
  EXPECT_EQ(osc_command({"/zenith/exposure", {40.0}}), OperatorCommand(oc::Exposure{40.0}));
  EXPECT_EQ(osc_command({"/zenith/exposure", {std::monostate{}}}), OperatorCommand(oc::Exposure{std::nullopt}));
  EXPECT_EQ(osc_command({"/zenith/loop", {std::int32_t{0}}}), OperatorCommand(oc::Loop{false}));
  EXPECT_EQ(osc_command({"/zenith/loop", {true}}), OperatorCommand(oc::Loop{true}));
  const OperatorCommand set = osc_command({"/zenith/atmosphere/Earth/aerosol/scattering/turbidity", {3.1f}});
  ASSERT_TRUE(std::holds_alternative<oc::Set>(set));
  EXPECT_EQ(std::get<oc::Set>(set).body, "Earth");
  EXPECT_EQ(std::get<oc::Set>(set).pointer.to_string(), "/aerosol/scattering/turbidity");
  EXPECT_EQ(std::get<oc::Set>(set).value, nlohmann::json(3.1)) << "a float reads as the decimal it was typed as";
  EXPECT_EQ(std::get<oc::Set>(osc_command({"/zenith/atmosphere/Earth/air_mass", {std::string("geometric")}})).value,
            nlohmann::json("geometric"));
  EXPECT_EQ(osc_command({"/zenith/sun/elevation", {-3.5f}}), OperatorCommand(oc::Sun{-3.5, std::nullopt}));
  EXPECT_EQ(osc_command({"/zenith/preview", {std::int32_t{1}}}), OperatorCommand(oc::Preview{true}));
  EXPECT_EQ(osc_command({"/zenith/preview", {false}}), OperatorCommand(oc::Preview{false}));
  EXPECT_EQ(osc_command({"/zenith/sun/azimuth", {std::int32_t{270}}}), OperatorCommand(oc::Sun{std::nullopt, 270.0}));
  EXPECT_EQ(osc_command({"/zenith/clear/sun", {1.0f}}), OperatorCommand(oc::Clear{oc::Clear::What::sun, ""}));
  EXPECT_EQ(osc_command({"/zenith/clear/exposure", {}}), OperatorCommand(oc::Clear{oc::Clear::What::exposure, ""}));
  EXPECT_EQ(osc_command({"/zenith/clear/atmosphere/Earth", {1.0f}}),
            OperatorCommand(oc::Clear{oc::Clear::What::atmosphere, "Earth"}));
  EXPECT_EQ(osc_command({"/zenith/fade", {1.0f, 3.0f}}), OperatorCommand(oc::Fade{1.0, 3.0, std::nullopt}));
  EXPECT_EQ(osc_command({"/zenith/fade", {std::int32_t{0}, 0.5f}}), OperatorCommand(oc::Fade{0.0, 0.5, std::nullopt}));
  EXPECT_EQ(osc_command({"/zenith/fade", {0.5f, 2.0f, 1.0f, 0.2f, 0.0f}}),
            OperatorCommand(oc::Fade{0.5, 2.0, std::array<double, 3>{1.0, 0.2, 0.0}}));
  EXPECT_EQ(osc_command({"/zenith/blackout", {}}), OperatorCommand(oc::Blackout{true}));
  EXPECT_EQ(osc_command({"/zenith/blackout", {std::int32_t{0}}}), OperatorCommand(oc::Blackout{false}));
  EXPECT_EQ(osc_command({"/zenith/blackout", {true}}), OperatorCommand(oc::Blackout{true}));
  EXPECT_EQ(osc_command({"/zenith/timecode/offset", {std::string("01:00:00:00")}}),
            OperatorCommand(oc::TimecodeOffset{"01:00:00:00"}));
  const auto error_of = [](const OscMessage& m) {
    try {
      osc_command(m);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of({"/zenith/rate", {20.0f}}), "command: /rate = 20.0: must be in [-16, 16]");
  EXPECT_EQ(error_of({"/zenith/fade", {1.0f, -2.0f}}), "command: /seconds = -2.0: must be in [0, 3600] s");
  EXPECT_NE(error_of({"/zenith/fade", {1.0f}}).find("OSC /zenith/fade: takes LEVEL SECONDS or LEVEL SECONDS R G B"),
            std::string::npos);
  EXPECT_NE(error_of({"/zenith/fade", {1.0f, 2.0f, 1.0f, 2.0f, 0.0f}}).find("each a number in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error_of({"/zenith/fade", {std::string("x"), 2.0f}}).find("argument 1 (level) must be a number"),
            std::string::npos);
  EXPECT_EQ(error_of({"/zenith/seek", {}}), "OSC /zenith/seek: takes one argument, got 0");
  EXPECT_NE(error_of({"/zenith/timecode/offset", {3600.0f}}).find("/offset: must be a string, got 3600.0"),
            std::string::npos);
  EXPECT_EQ(error_of({"/zenith/sun/elevation", {95.0f}}), "command: /elevation_deg = 95.0: must be in [-90, 90] deg");
  EXPECT_NE(error_of({"/zenith/quit", {}}).find("OSC /zenith/quit: unknown address"), std::string::npos);
  EXPECT_NE(error_of({"/other/play", {}}).find("not a zenith address"), std::string::npos);
  EXPECT_NE(error_of({"/zenith/atmosphere/Earth", {1.0f}}).find("expected /zenith/atmosphere/<body>/<parameter>"),
            std::string::npos);
  EXPECT_NE(error_of({"/zenith/exposure", {OscBlob{{1}}}}).find("cannot take blob of 1 bytes"), std::string::npos);
  EXPECT_NE(error_of({"/zenith/atmosphere/Earth/name", {std::string("\x01")}}).find("printable ASCII"),
            std::string::npos);
}

TEST(OscReceiverTest, AppliesMessagesFromAllowedSendersOnly) {
  boost::asio::io_context io;
  std::vector<std::string> applied;
  const auto handler = [&](const OperatorCommand& c, const std::string& source) {
    if (std::holds_alternative<oc::Pause>(c)) throw std::invalid_argument("no show");
    applied.push_back(describe(c) + " from " + source);
    return std::string("ok");
  };
  const auto localhost = boost::asio::ip::make_address("127.0.0.1");
  const auto desk = boost::asio::ip::make_address("10.0.0.5");
  OscReceiver loopback(io, {"127.0.0.1", 0, {}}, handler);
  const Bytes bundle =
      encode_osc_bundle({encode_osc_message({"/zenith/rate", {2.0f}}), encode_osc_message({"/zenith/pause", {}}),
                         encode_osc_message({"/zenith/nothing", {}}), encode_osc_message({"/zenith/play", {}})});
  EXPECT_EQ(loopback.handle(bundle, localhost), 2u)
      << "rate and play applied, pause refused, the unknown address refused";
  EXPECT_EQ(applied, (std::vector<std::string>{"rate 2.0 from osc 127.0.0.1", "play from osc 127.0.0.1"}));
  EXPECT_EQ(loopback.handle(bundle, desk), 0u) << "without --osc-allow only the loopback is heard";
  EXPECT_EQ(loopback.handle(bytes("garbage!"), localhost), 0u);

  OscReceiver open(io, {"0.0.0.0", 0, {}}, handler);
  EXPECT_THROW(open.start(), std::runtime_error) << "beyond loopback the desks must be named";
  OscReceiver allowing(io, {"127.0.0.1", 0, {"10.0.0.5"}}, handler);
  allowing.start();
  EXPECT_GT(allowing.port(), 0);
  applied.clear();
  EXPECT_EQ(allowing.handle(encode_osc_message({"/zenith/play", {}}), desk), 1u);
  EXPECT_EQ(allowing.handle(encode_osc_message({"/zenith/play", {}}), localhost), 0u) << "only the named senders";
  allowing.close();
}

// An OSC address with a newline or escape codes was once written
// raw into the log (forged log lines), and a flood logged a line per packet.
TEST(OscReceiverTest, LogsPeerBytesEscapedAndAFloodOfRefusalsOnceASecondWithItsCount) {
  boost::asio::io_context io;
  std::size_t commands = 0;
  OscReceiver receiver(io, {"127.0.0.1", 0, {}}, [&](const OperatorCommand&, const std::string&) {
    ++commands;
    return std::string("ok");
  });
  const auto localhost = boost::asio::ip::make_address("127.0.0.1");
  std::string text;
  {
    tests::CapturedLog log;
    EXPECT_EQ(receiver.handle(encode_osc_message({"/zenith/x\nmaster: quit \x1b[2J", {}}), localhost), 0u);
    text = log.text();
  }
  EXPECT_EQ(core::count_of(text, "\n"), 1u) << "one line, no forged second one:\n" << text;
  EXPECT_NE(text.find("/zenith/x\\x0amaster: quit \\x1b[2J"), std::string::npos) << text;
  {
    tests::CapturedLog log;
    for (int i = 0; i < 5000; ++i) receiver.handle(bytes("garbage!"), localhost);
    for (int i = 0; i < 5000; ++i) receiver.handle(encode_osc_message({"/zenith/nothing", {}}), localhost);
    text = log.text();
  }
  const std::size_t lines = core::count_of(text, "\n");
  EXPECT_GE(lines, 1u) << "the unknown address's first is logged (a bad packet was, just before)";
  EXPECT_LE(lines, 6u) << "10 000 refused packets within a few seconds: a line a second per kind\n" << text;
  EXPECT_EQ(commands, 0u);
}

}  // namespace
}  // namespace zenith::cluster
