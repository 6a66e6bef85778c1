// The chase (show/timecode/timecode_chase.h) on LTC made by libltc's encoder
// and read back by its decoder, as a show would get it from a WAV file: a
// clean signal at every rate, ±0.1 % speed drift, dropouts shorter and longer
// than the freewheel, a locate backwards, a damaged frame, timecode before the
// show's start. The show is asked where it is at 30 frames a second, as the
// master does; the truth is the timecode the encoder wrote at that instant.
#include "show/timecode/timecode_chase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "show/timecode/ltc_codec.h"

namespace zenith::show {
namespace {

constexpr double kSampleRate = 48000.0;
constexpr double kShowFps = 30.0;  // the master's frame rate

/// A piece of the audio: LTC from `start` for `seconds`, or silence.
struct Segment {
  std::optional<Timecode> start;  ///< nullopt: silence
  double seconds = 0.0;
  double speed = 1.0;
};

struct Signal {
  std::vector<float> samples;
  TimecodeRate rate;
  /// [first sample, end sample, timecode seconds at the first, speed] per LTC segment.
  struct Piece {
    std::int64_t first, end;
    double timecode_s, speed;
  };
  std::vector<Piece> pieces;
  /// The timecode the encoder wrote at local time t (nullopt in silence).
  std::optional<double> truth(double t) const {
    const auto sample = static_cast<std::int64_t>(t * kSampleRate);
    for (const Piece& p : pieces)
      if (sample >= p.first && sample < p.end)
        return p.timecode_s + p.speed * (t - static_cast<double>(p.first) / kSampleRate);
    return std::nullopt;
  }
};

Signal make_signal(TimecodeRate rate, const std::vector<Segment>& segments) {
  Signal s{{}, rate, {}};
  for (const Segment& g : segments) {
    const auto first = static_cast<std::int64_t>(s.samples.size());
    if (!g.start) {
      s.samples.resize(s.samples.size() + static_cast<std::size_t>(g.seconds * kSampleRate), 0.0f);
      continue;
    }
    LtcSignal ltc;
    ltc.start = *g.start;
    ltc.rate = rate;
    ltc.speed = g.speed;
    ltc.sample_rate_hz = kSampleRate;
    ltc.frames = static_cast<std::int64_t>(std::lround(g.seconds * frames_per_second(rate) * g.speed));
    const std::vector<float> samples = encode_ltc(ltc);
    s.samples.insert(s.samples.end(), samples.begin(), samples.end());
    s.pieces.push_back({first, static_cast<std::int64_t>(s.samples.size()), timecode_seconds(*g.start, rate), g.speed});
  }
  return s;
}

/// The chase asked at every show frame; each LTC frame given once it has ended (when a reader has it).
struct ChaseRun {
  std::vector<double> times;
  std::vector<ChasePosition> positions;
};
ChaseRun chase(const Signal& signal, TimecodeChase& chase,
               const std::vector<std::pair<double, TimecodeEvent>>& extra = {},
               const std::function<void(double, TimecodeChase&)>& at_frame = {}) {
  LtcDecoder decoder(kSampleRate, frames_per_second(signal.rate));
  std::vector<std::pair<double, TimecodeEvent>> events = extra;  // (known at, event)
  for (const LtcFrame& f : decoder.decode(signal.samples))
    events.push_back({static_cast<double>(f.last_sample) / kSampleRate,
                      {f.timecode, signal.rate, static_cast<double>(f.first_sample) / kSampleRate}});
  std::sort(events.begin(), events.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ChaseRun run;
  std::size_t next = 0;
  const double end_s = static_cast<double>(signal.samples.size()) / kSampleRate;
  for (int k = 0; k / kShowFps < end_s; ++k) {
    const double t = k / kShowFps;
    while (next < events.size() && events[next].first <= t) chase.receive(events[next++].second);
    if (at_frame) at_frame(t, chase);
    run.times.push_back(t);
    run.positions.push_back(chase.position(t));
  }
  return run;
}

/// The largest |show time − truth| over the frames in [from_s, to_s] that `keep` accepts.
double worst_error(const Signal& signal, const ChaseRun& run, double offset_s, double from_s, double to_s) {
  double worst = 0.0;
  for (std::size_t i = 0; i < run.times.size(); ++i) {
    const double t = run.times[i];
    const std::optional<double> truth = signal.truth(t);
    if (t < from_s || t > to_s || !truth) continue;
    worst = std::max(worst, std::abs(run.positions[i].show_time_s - (*truth - offset_s)));
  }
  return worst;
}

const ChasePosition& at(const ChaseRun& run, double t) {
  const auto i = static_cast<std::size_t>(std::lround(t * kShowFps));
  return run.positions.at(std::min(i, run.positions.size() - 1));
}

TEST(TimecodeChase, EveryRateIsFollowedToAFractionOfAFrame) {
  for (const TimecodeRate rate :
       {TimecodeRate::fps24, TimecodeRate::fps25, TimecodeRate::fps29_97_drop, TimecodeRate::fps30}) {
    const Signal signal = make_signal(rate, {{Timecode{1, 0, 0, 0}, 5.0}});
    ChaseSettings settings;
    settings.offset_s = timecode_seconds({1, 0, 0, 0}, rate);
    TimecodeChase c(settings);
    const ChaseRun run = chase(signal, c);
    EXPECT_EQ(at(run, 0.0).state, ChaseState::waiting);
    EXPECT_EQ(at(run, 0.3).state, ChaseState::locked) << to_string(rate);
    const double frame = 1.0 / frames_per_second(rate);
    const double worst = worst_error(signal, run, settings.offset_s, 0.3, 4.9);
    std::printf("%s fps: worst |show time - timecode| %.3f ms (a frame is %.1f ms)\n",
                std::string(to_string(rate)).c_str(), worst * 1e3, frame * 1e3);
    EXPECT_LT(worst, 0.05 * frame) << to_string(rate);
    EXPECT_NEAR(at(run, 4.0).drift_ppm, 0.0, 100.0);
    EXPECT_EQ(at(run, 4.9).locates, 0);
  }
}

TEST(TimecodeChase, ASoundtrackRunningFastOrSlowIsFollowedAndItsDriftMeasured) {
  for (const double speed : {1.001, 0.999}) {
    const Signal signal = make_signal(TimecodeRate::fps25, {{Timecode{0, 30, 0, 0}, 10.0, speed}});
    ChaseSettings settings;
    settings.offset_s = 1800.0;
    TimecodeChase c(settings);
    const ChaseRun run = chase(signal, c);
    EXPECT_NEAR(at(run, 9.0).drift_ppm, (speed - 1.0) * 1e6, 100.0);
    EXPECT_LT(worst_error(signal, run, 1800.0, 0.3, 9.9), 0.05 / 25.0) << speed;
  }
}

TEST(TimecodeChase, ADropoutIsFreewheeledThroughThenHeldAndTheShowLocksAgain) {
  const TimecodeRate rate = TimecodeRate::fps25;
  // 2 s of timecode, 1 s of silence, then the timecode where it would be.
  const Signal short_gap =
      make_signal(rate, {{Timecode{1, 0, 0, 0}, 2.0}, {std::nullopt, 1.0}, {Timecode{1, 0, 3, 0}, 2.0}});
  ChaseSettings settings;
  settings.offset_s = 3600.0;
  settings.freewheel_s = 2.0;
  TimecodeChase through(settings);
  const ChaseRun run = chase(short_gap, through);
  EXPECT_EQ(at(run, 2.5).state, ChaseState::freewheeling);
  EXPECT_NEAR(at(run, 2.5).show_time_s, 2.5, 0.01) << "it ran on at the timecode's speed";
  EXPECT_EQ(at(run, 4.0).state, ChaseState::locked);
  EXPECT_LT(worst_error(short_gap, run, 3600.0, 3.3, 4.9), 0.05 / 25.0);

  // 3 s of silence against a freewheel of 1 s: held at the freewheel's end, then locked again.
  const Signal long_gap =
      make_signal(rate, {{Timecode{1, 0, 0, 0}, 2.0}, {std::nullopt, 3.0}, {Timecode{1, 0, 5, 0}, 2.0}});
  settings.freewheel_s = 1.0;
  TimecodeChase held(settings);
  const ChaseRun hold = chase(long_gap, held);
  // Held where the line was at the freewheel's end: the last frame read (01:00:01:23, begun at 1.92 s:
  // the one after it ends on no edge), four frame periods to the dropout, then the freewheel's second.
  EXPECT_EQ(at(hold, 3.5).state, ChaseState::held);
  ASSERT_TRUE(at(hold, 3.5).last);
  EXPECT_EQ(*at(hold, 3.5).last, (Timecode{1, 0, 1, 23}));
  EXPECT_NEAR(at(hold, 3.5).show_time_s, 1.92 + 4.0 / 25.0 + 1.0, 0.002);
  EXPECT_EQ(at(hold, 4.9).show_time_s, at(hold, 3.5).show_time_s) << "a held show stays on its frame";
  EXPECT_EQ(at(hold, 6.0).state, ChaseState::locked);
  EXPECT_LT(worst_error(long_gap, hold, 3600.0, 5.3, 6.9), 0.05 / 25.0);
}

/// A master sends each frame a lookahead before its moment: asked for 0.3 s ahead, the chase stays
/// locked while the timecode runs, gives the timecode of the moment, and, held after the signal ends,
/// never steps back from a frame it already gave.
TEST(TimecodeChase, FramesAskedAheadOfTheirMomentStayLockedAndNeverStepBack) {
  const Signal signal = make_signal(TimecodeRate::fps25, {{Timecode{1, 0, 0, 0}, 3.0}, {std::nullopt, 3.0}});
  ChaseSettings settings;
  settings.offset_s = 3600.0;
  settings.freewheel_s = 0.5;
  TimecodeChase c(settings);
  LtcDecoder decoder(kSampleRate, 25.0);
  std::vector<LtcFrame> frames = decoder.decode(signal.samples);
  std::size_t next = 0;
  double shown = 0.0;
  for (int k = 0; k < 180; ++k) {
    const double now = k / kShowFps, moment = now + 0.3;
    while (next < frames.size() && static_cast<double>(frames[next].last_sample) / kSampleRate <= now) {
      const LtcFrame& f = frames[next++];
      c.receive({f.timecode, TimecodeRate::fps25, static_cast<double>(f.first_sample) / kSampleRate});
    }
    const ChasePosition p = c.position(moment, now);
    if (now > 0.3 && now < 2.9) {
      EXPECT_EQ(p.state, ChaseState::locked) << now;
      EXPECT_NEAR(p.show_time_s, moment, 0.05 / 25.0) << now;
    }
    if (now > 0.3) {
      EXPECT_GE(p.show_time_s, shown) << "at " << now << ", in state " << to_string(p.state);
    }
    shown = std::max(shown, p.show_time_s);
  }
  EXPECT_EQ(c.position(6.3, 6.0).state, ChaseState::held);
}

TEST(TimecodeChase, AStoppedShowWaitsForTheOperator) {
  const Signal signal =
      make_signal(TimecodeRate::fps30, {{Timecode{2, 0, 0, 0}, 1.0}, {std::nullopt, 2.0}, {Timecode{2, 0, 3, 0}, 3.0}});
  ChaseSettings settings;
  settings.offset_s = 7200.0;
  settings.freewheel_s = 0.5;
  settings.after_dropout = ChaseSettings::AfterDropout::stop;
  TimecodeChase c(settings);
  const ChaseRun run = chase(signal, c, {}, [](double t, TimecodeChase& chase) {
    if (std::abs(t - 4.5) < 1e-9) chase.resume();  // the operator, 1.5 s after the timecode came back
  });
  EXPECT_EQ(at(run, 2.0).state, ChaseState::stopped);
  EXPECT_EQ(at(run, 4.0).state, ChaseState::stopped) << "the timecode is back, the show waits";
  EXPECT_EQ(at(run, 4.8).state, ChaseState::locked);
  EXPECT_LT(worst_error(signal, run, 7200.0, 4.8, 5.9), 0.05 / 30.0);
}

/// A standby taking over from the active master's last frame: held there until its chase locks, and —
/// locked on timecode a little behind that frame, which was sent ahead of its moment — never below it
/// until the timecode passes it.
TEST(TimecodeChase, ATakeoverGoesOnFromTheLastFrameNeverBelowIt) {
  ChaseSettings settings;
  settings.offset_s = 3600.0;
  TimecodeChase unlocked(settings);
  unlocked.continue_from(5.0);
  EXPECT_EQ(unlocked.position(0.0).state, ChaseState::held);
  EXPECT_EQ(unlocked.position(0.0).show_time_s, 5.0) << "not the show's start";

  TimecodeChase locked(settings);
  for (int f = 0; f < 5; ++f) locked.receive({{1, 0, 4, f}, TimecodeRate::fps25, f / 25.0});  // 4 s at local 0
  locked.continue_from(4.3);
  EXPECT_EQ(locked.position(0.16).show_time_s, 4.3) << "the timecode (4.16 s) is behind the last frame";
  EXPECT_EQ(locked.position(0.2).state, ChaseState::locked);
  for (int f = 5; f < 15; ++f) locked.receive({{1, 0, 4, f}, TimecodeRate::fps25, f / 25.0});
  EXPECT_NEAR(locked.position(0.56).show_time_s, 4.56, 1e-9) << "past it: the timecode's own time";
}

TEST(TimecodeChase, ALocateIsFollowedADamagedFrameIsNot) {
  const TimecodeRate rate = TimecodeRate::fps25;
  // 3 s from 01:00:10:00, then the audio located back to 01:00:00:00.
  const Signal signal = make_signal(rate, {{Timecode{1, 0, 10, 0}, 3.0}, {Timecode{1, 0, 0, 0}, 3.0}});
  ChaseSettings settings;
  settings.offset_s = 3600.0;
  TimecodeChase c(settings);
  // One damaged frame in the first part: a label 7 s off, once.
  const ChaseRun run = chase(signal, c, {{1.501, {Timecode{1, 0, 4, 12}, rate, 1.50}}});
  EXPECT_EQ(at(run, 2.9).locates, 0) << "a single frame off the line is not a locate";
  EXPECT_LT(worst_error(signal, run, 3600.0, 0.3, 2.95), 0.05 / 25.0);
  EXPECT_EQ(at(run, 5.9).locates, 1);
  // After the jump the show follows within lock_frames frames and a frame's reading.
  EXPECT_LT(worst_error(signal, run, 3600.0, 3.0 + 5.0 / 25.0, 5.9), 0.05 / 25.0);
}

TEST(TimecodeChase, TimecodeBeforeTheShowsStartHoldsItAtItsStart) {
  const Signal signal = make_signal(TimecodeRate::fps25, {{Timecode{0, 59, 58, 0}, 4.0}});
  ChaseSettings settings;
  settings.offset_s = 3600.0;
  TimecodeChase c(settings);
  const ChaseRun run = chase(signal, c);
  EXPECT_TRUE(at(run, 1.0).before_start);
  EXPECT_EQ(at(run, 1.0).show_time_s, 0.0);
  EXPECT_FALSE(at(run, 3.0).before_start);
  EXPECT_NEAR(at(run, 3.0).show_time_s, 1.0, 0.002);
}

TEST(TimecodeChase, SettingsOutOfRangeAreNamed) {
  const auto message = [](ChaseSettings s) {
    try {
      TimecodeChase c(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  ChaseSettings s;
  s.offset_s = -1.0;
  EXPECT_NE(message(s).find("offset_s = -1 outside [0, 86400)"), std::string::npos);
  s = {};
  s.lock_frames = 1;
  EXPECT_NE(message(s).find("lock_frames"), std::string::npos);
  s = {};
  s.freewheel_s = 1e9;
  EXPECT_NE(message(s).find("freewheel_s"), std::string::npos);
  TimecodeChase c{ChaseSettings{}};
  EXPECT_THROW(c.set_offset_s(90000.0), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::show
