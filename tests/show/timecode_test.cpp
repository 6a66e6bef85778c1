// SMPTE timecode labels (show/timecode/timecode.h): drop-frame counting
// against SMPTE ST 12-1's published counts, every label of a day there and
// back, parsing and its errors.
#include "show/timecode/timecode.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace zenith::show {
namespace {

constexpr TimecodeRate kRates[] = {TimecodeRate::fps24, TimecodeRate::fps25, TimecodeRate::fps29_97_drop,
                                   TimecodeRate::fps30};

TEST(Timecode, DropFrameSkipsTwoLabelsAMinuteButEachTenth) {
  const TimecodeRate df = TimecodeRate::fps29_97_drop;
  // The published counts: 1 798 frames in a minute, 17 982 in ten, 107 892 in an hour.
  EXPECT_EQ(frame_index({0, 0, 59, 29}, df), 1799);
  EXPECT_EQ(frame_index({0, 1, 0, 2}, df), 1800);  // 00:01:00;00 and ;01 do not exist
  EXPECT_EQ(frame_index({0, 10, 0, 0}, df), 17982);
  EXPECT_EQ(frame_index({1, 0, 0, 0}, df), 107892);
  EXPECT_EQ(frames_per_day(df), 2589408);
  EXPECT_EQ(timecode_at(1800, df), (Timecode{0, 1, 0, 2}));
  EXPECT_EQ(timecode_at(17982, df), (Timecode{0, 10, 0, 0}));
  EXPECT_EQ(timecode_at(17981, df), (Timecode{0, 9, 59, 29}));
  // The label keeps to the wall clock: an hour of drop-frame is 3.6 ms short of 3600 s.
  EXPECT_NEAR(timecode_seconds({1, 0, 0, 0}, df), 3599.9964, 1e-9);
  EXPECT_EQ(timecode_at_seconds(3599.9964, df), (Timecode{1, 0, 0, 0}));
  EXPECT_EQ(timecode_at_seconds(3600.0, TimecodeRate::fps25), (Timecode{1, 0, 0, 0}));
  EXPECT_FALSE(valid_timecode({0, 1, 0, 1}, df));
  EXPECT_TRUE(valid_timecode({0, 10, 0, 1}, df));
  EXPECT_TRUE(valid_timecode({0, 1, 0, 1}, TimecodeRate::fps30));
}

TEST(Timecode, EveryLabelOfADayThereAndBack) {
  for (const TimecodeRate rate : kRates) {
    Timecode previous = timecode_at(-1, rate);  // the day's last label
    EXPECT_EQ(previous, (Timecode{23, 59, 59, labels_per_second(rate) - 1})) << to_string(rate);
    for (std::int64_t i = 0; i < frames_per_day(rate); ++i) {
      const Timecode tc = timecode_at(i, rate);
      ASSERT_TRUE(valid_timecode(tc, rate)) << to_string(rate) << " frame " << i;
      ASSERT_EQ(frame_index(tc, rate), i) << to_string(rate) << " " << format_timecode(tc, rate);
      if (i > 0) {
        ASSERT_GT(tc, previous) << "labels in order";
      }
      previous = tc;
    }
  }
}

TEST(Timecode, RatesByNameAndByFrequency) {
  for (const TimecodeRate rate : kRates) {
    EXPECT_EQ(parse_timecode_rate(to_string(rate)), rate);
    EXPECT_EQ(timecode_rate_of(frames_per_second(rate)), rate);
  }
  EXPECT_EQ(parse_timecode_rate("29.97"), TimecodeRate::fps29_97_drop);
  EXPECT_EQ(timecode_rate_of(29.97), TimecodeRate::fps29_97_drop);
  EXPECT_EQ(parse_timecode_rate("23.976"), std::nullopt);
  EXPECT_EQ(timecode_rate_of(50.0), std::nullopt);
}

TEST(Timecode, ParsedAndWrittenAsEditorsDo) {
  EXPECT_EQ(parse_timecode("01:02:03:04", TimecodeRate::fps25), (Timecode{1, 2, 3, 4}));
  EXPECT_EQ(parse_timecode("01:02:03;04", TimecodeRate::fps29_97_drop), (Timecode{1, 2, 3, 4}));
  EXPECT_EQ(format_timecode({1, 2, 3, 4}, TimecodeRate::fps25), "01:02:03:04");
  EXPECT_EQ(format_timecode({1, 2, 3, 4}, TimecodeRate::fps29_97_drop), "01:02:03;04");
  for (const char* bad : {"1:2:3", "01:02:03:25", "24:00:00:00", "01:60:00:00", "01:02:03:04:05", "aa:bb:cc:dd", ""}) {
    try {
      parse_timecode(bad, TimecodeRate::fps25);
      ADD_FAILURE() << bad << " parsed";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("frames [0, 25)"), std::string::npos) << e.what();
    }
  }
  try {
    parse_timecode("00:01:00;00", TimecodeRate::fps29_97_drop);
    ADD_FAILURE() << "a skipped drop-frame label parsed";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the next label is 00:01:00;02"), std::string::npos) << e.what();
  }
  EXPECT_THROW(frame_index({0, 0, 0, 30}, TimecodeRate::fps30), std::invalid_argument);
}

}  // namespace
}  // namespace zenith::show
