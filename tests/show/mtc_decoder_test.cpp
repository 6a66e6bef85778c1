// MIDI timecode (show/timecode/mtc_decoder.h) from byte streams made as a
// show-control PC sends them: quarter frames at every rate, a full-frame
// locate, clock and note messages in between, a lost byte; and the chase
// following it to a fraction of a frame.
#include "show/timecode/mtc_decoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace zenith::show {
namespace {

/// One MIDI message and when it was sent.
struct Sent {
  std::vector<std::uint8_t> bytes;
  double at_s;
};

int rate_bits(TimecodeRate rate) {
  switch (rate) {
    case TimecodeRate::fps24: return 0;
    case TimecodeRate::fps25: return 1;
    case TimecodeRate::fps29_97_drop: return 2;
    case TimecodeRate::fps30: return 3;
  }
  return 3;
}

/// Quarter frames for `frames` frames (even) from `start`, sent from `t0_s`: eight messages a
/// label, four a frame, piece 0 as its frame begins.
std::vector<Sent> quarter_frames(const Timecode& start, TimecodeRate rate, int frames, double t0_s) {
  std::vector<Sent> out;
  const double frame_s = 1.0 / frames_per_second(rate);
  const std::int64_t first = frame_index(start, rate);
  for (int f = 0; f < frames; f += 2) {
    const Timecode tc = timecode_at(first + f, rate);
    const int nibbles[8] = {tc.frames & 15,  tc.frames >> 4,  tc.seconds & 15, tc.seconds >> 4,
                            tc.minutes & 15, tc.minutes >> 4, tc.hours & 15,   (tc.hours >> 4) | rate_bits(rate) << 1};
    for (int piece = 0; piece < 8; ++piece)
      out.push_back(
          {{0xF1, static_cast<std::uint8_t>(piece << 4 | nibbles[piece])}, t0_s + (f + piece / 4.0) * frame_s});
  }
  return out;
}

/// The same played backwards: from `start` down, piece 7 first; the label's
/// timecode at piece 7's sending, the frame below it at piece 3's.
std::vector<Sent> quarter_frames_backwards(const Timecode& start, TimecodeRate rate, int frames, double t0_s) {
  std::vector<Sent> out;
  const double frame_s = 1.0 / frames_per_second(rate);
  const std::int64_t first = frame_index(start, rate);
  for (int f = 0; f < frames; f += 2) {
    const Timecode tc = timecode_at(first - f, rate);
    const int nibbles[8] = {tc.frames & 15,  tc.frames >> 4,  tc.seconds & 15, tc.seconds >> 4,
                            tc.minutes & 15, tc.minutes >> 4, tc.hours & 15,   (tc.hours >> 4) | rate_bits(rate) << 1};
    for (int piece = 7; piece >= 0; --piece)
      out.push_back(
          {{0xF1, static_cast<std::uint8_t>(piece << 4 | nibbles[piece])}, t0_s + (f + (7 - piece) / 4.0) * frame_s});
  }
  return out;
}

Sent full_frame(const Timecode& tc, TimecodeRate rate, double at_s) {
  return {{0xF0, 0x7F, 0x7F, 0x01, 0x01, static_cast<std::uint8_t>(rate_bits(rate) << 5 | tc.hours),
           static_cast<std::uint8_t>(tc.minutes), static_cast<std::uint8_t>(tc.seconds),
           static_cast<std::uint8_t>(tc.frames), 0xF7},
          at_s};
}

std::vector<TimecodeEvent> decode_all(MtcDecoder& decoder, const std::vector<Sent>& stream) {
  std::vector<TimecodeEvent> out;
  for (const Sent& s : stream) {
    const std::vector<TimecodeEvent> events = decoder.decode(s.bytes, s.at_s);
    out.insert(out.end(), events.begin(), events.end());
  }
  return out;
}

TEST(Mtc, QuarterFramesGiveEveryFrameWhereItBeganAtEveryRate) {
  for (const TimecodeRate rate :
       {TimecodeRate::fps24, TimecodeRate::fps25, TimecodeRate::fps29_97_drop, TimecodeRate::fps30}) {
    // Across a minute's turn: drop-frame's skipped labels included.
    const Timecode start{1, 0, 59, labels_per_second(rate) - 4};
    MtcDecoder decoder;
    const std::vector<TimecodeEvent> events = decode_all(decoder, quarter_frames(start, rate, 40, 10.0));
    ASSERT_EQ(events.size(), 40u) << to_string(rate);
    const std::int64_t first = frame_index(start, rate);
    for (std::size_t i = 0; i < events.size(); ++i) {
      EXPECT_EQ(events[i].timecode, timecode_at(first + static_cast<std::int64_t>(i), rate)) << to_string(rate);
      EXPECT_EQ(events[i].rate, rate);
      EXPECT_NEAR(events[i].local_s, 10.0 + static_cast<double>(i) / frames_per_second(rate), 1e-9);
    }
    EXPECT_EQ(decoder.labels(), 20);
    EXPECT_EQ(decoder.restarts(), 0);
  }
}

TEST(Mtc, ClockNotesAndOtherSysExBetweenTheQuarterFramesAreSkipped) {
  std::vector<Sent> stream;
  for (const Sent& q : quarter_frames({2, 0, 0, 0}, TimecodeRate::fps25, 8, 0.0)) {
    stream.push_back({{0xF8}, q.at_s});                                // MIDI clock
    stream.push_back({{0x90, 0x3C, 0x64}, q.at_s});                    // a note on
    stream.push_back({{0xF0, 0x7E, 0x7F, 0x06, 0x01, 0xF7}, q.at_s});  // another SysEx
    stream.push_back({{q.bytes[0], 0xFE, q.bytes[1]}, q.at_s});        // active sensing inside the message
  }
  MtcDecoder decoder;
  const std::vector<TimecodeEvent> events = decode_all(decoder, stream);
  ASSERT_EQ(events.size(), 8u);
  EXPECT_EQ(events.back().timecode, (Timecode{2, 0, 0, 7}));
  EXPECT_EQ(decoder.restarts(), 0);
}

TEST(Mtc, ALostByteMakesNoWrongLabelAndAFullFrameLocates) {
  std::vector<Sent> stream = quarter_frames({1, 0, 0, 0}, TimecodeRate::fps30, 8, 0.0);
  stream.erase(stream.begin() + 10);  // piece 2 of the second label lost
  MtcDecoder decoder;
  std::vector<TimecodeEvent> events = decode_all(decoder, stream);
  ASSERT_EQ(events.size(), 6u) << "the label with a lost piece is not made";
  EXPECT_EQ(events[1].timecode, (Timecode{1, 0, 0, 1}));
  EXPECT_EQ(events[2].timecode, (Timecode{1, 0, 0, 4}));
  EXPECT_EQ(decoder.restarts(), 1);

  const std::vector<TimecodeEvent> located =
      decoder.decode(full_frame({0, 59, 30, 12}, TimecodeRate::fps30, 1.0).bytes, 1.0);
  ASSERT_EQ(located.size(), 1u);
  EXPECT_EQ(located[0].timecode, (Timecode{0, 59, 30, 12}));
  EXPECT_EQ(located[0].local_s, 1.0);
  // A full frame of a label the rate does not have is none.
  EXPECT_TRUE(decoder.decode(full_frame({0, 59, 30, 29}, TimecodeRate::fps25, 2.0).bytes, 2.0).empty());
}

TEST(Mtc, PlayedBackwardsEveryFrameIsReadWhereItWas) {
  for (const TimecodeRate rate :
       {TimecodeRate::fps24, TimecodeRate::fps25, TimecodeRate::fps29_97_drop, TimecodeRate::fps30}) {
    // Back across a minute's turn: drop-frame's skipped labels included.
    const Timecode start{1, 1, 0, 4};
    MtcDecoder decoder;
    const std::vector<TimecodeEvent> events = decode_all(decoder, quarter_frames_backwards(start, rate, 40, 10.0));
    ASSERT_EQ(events.size(), 40u) << to_string(rate);
    const std::int64_t first = frame_index(start, rate);
    for (std::size_t i = 0; i < events.size(); ++i) {
      EXPECT_EQ(events[i].timecode, timecode_at(first - static_cast<std::int64_t>(i), rate)) << to_string(rate);
      EXPECT_NEAR(events[i].local_s, 10.0 + static_cast<double>(i) / frames_per_second(rate), 1e-9);
    }
    EXPECT_EQ(decoder.restarts(), 0);
  }
}

TEST(Mtc, TheTransportTurningRoundBreaksNoLabelIntoAWrongOne) {
  // Forward from 01:00:00:00 for 10 frames, then backward from where it stopped.
  const TimecodeRate rate = TimecodeRate::fps25;
  std::vector<Sent> stream = quarter_frames({1, 0, 0, 0}, rate, 10, 0.0);
  for (const Sent& s : quarter_frames_backwards({1, 0, 0, 10}, rate, 10, 0.4)) stream.push_back(s);
  stream.erase(stream.begin() + 13);  // and a byte lost going forward: piece 5 of the second label
  MtcDecoder decoder;
  const std::vector<TimecodeEvent> events = decode_all(decoder, stream);
  std::vector<Timecode> labels;
  for (const TimecodeEvent& e : events) labels.push_back(e.timecode);
  const std::vector<Timecode> expected = {{1, 0, 0, 0}, {1, 0, 0, 1}, {1, 0, 0, 4}, {1, 0, 0, 5},  {1, 0, 0, 6},
                                          {1, 0, 0, 7}, {1, 0, 0, 8}, {1, 0, 0, 9}, {1, 0, 0, 10}, {1, 0, 0, 9},
                                          {1, 0, 0, 8}, {1, 0, 0, 7}, {1, 0, 0, 6}, {1, 0, 0, 5},  {1, 0, 0, 4},
                                          {1, 0, 0, 3}, {1, 0, 0, 2}, {1, 0, 0, 1}};
  EXPECT_EQ(labels, expected);
  EXPECT_EQ(decoder.restarts(), 1);
}

/// Feeds `stream` to a chase (show time 0 at 01:00:00:00) through the decoder, asked 30 times a second
/// for 170 frames; returns the worst distance of its show time from `expected(t)` while it should be
/// locked (0.3 to 5.9 s), where it must be locked at `speed`.
double worst_chase_error(const std::vector<Sent>& stream, const std::function<double(double)>& expected, double speed) {
  ChaseSettings settings;
  settings.offset_s = 3600.0;
  TimecodeChase chase(settings);
  MtcDecoder decoder;
  std::size_t next = 0;
  double worst = 0.0;
  for (int k = 0; k < 170; ++k) {
    const double t = k / 30.0;
    while (next < stream.size() && stream[next].at_s <= t) {
      const Sent& s = stream[next++];
      for (const TimecodeEvent& e : decoder.decode(s.bytes, s.at_s)) chase.receive(e);
    }
    const ChasePosition p = chase.position(t);
    if (t > 0.3 && t < 5.9) {
      EXPECT_EQ(p.state, ChaseState::locked) << t;
      EXPECT_NEAR(p.speed, speed, 1e-9) << t;
      worst = std::max(worst, std::abs(p.show_time_s - expected(t)));
    }
  }
  return worst;
}

/// The chase on MTC: a label a frame and three quarters late, yet the show at the timecode of its moment.
TEST(Mtc, TheChaseFollowsItToAFractionOfAFrame) {
  const std::vector<Sent> stream = quarter_frames({1, 0, 0, 0}, TimecodeRate::fps25, 150, 0.0);
  EXPECT_LT(worst_chase_error(
                stream, [](double t) { return t; }, 1.0),
            0.05 / 25.0);
}

/// Shuttling back: the chase follows MTC played backwards, its speed −1.
TEST(Mtc, TheChaseFollowsItBackwards) {
  const std::vector<Sent> stream = quarter_frames_backwards({1, 0, 6, 0}, TimecodeRate::fps25, 150, 0.0);
  EXPECT_LT(worst_chase_error(
                stream, [](double t) { return 6.0 - t; }, -1.0),
            0.05 / 25.0);
}

}  // namespace
}  // namespace zenith::show
