#pragma once
// SMPTE timecode (SMPTE ST 12-1): a frame's label hours:minutes:seconds:frames
// at 24, 25, 29.97 drop-frame and 30 frames per second, and the real time it
// stands for. The house's show-control system or audio playback sends it (as
// LTC audio, show/timecode/ltc_codec.h, or MIDI timecode,
// show/timecode/mtc_decoder.h) and zenith's shows chase it
// (show/timecode/timecode_chase.h; docs/shows.md, "Chasing timecode").
//
// Drop-frame: 29.97 fps video counts 30 labels a second but runs 1000/1001 as
// fast as real seconds; it skips the labels :00 and :01 at the start of every
// minute but each tenth, 108 labels an hour, so the label keeps to the wall
// clock (00:10:00;00 is frame 17 982, 599.9994 s).
#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace zenith::show {

enum class TimecodeRate { fps24, fps25, fps29_97_drop, fps30 };

/// Frames per real second: 24, 25, 30000/1001, 30.
double frames_per_second(TimecodeRate rate);
/// Labels per timecode second: 24, 25, 30, 30.
int labels_per_second(TimecodeRate rate);
/// Frames in 24 hours of labels (drop-frame: 2 589 408).
std::int64_t frames_per_day(TimecodeRate rate);
/// "24", "25", "29.97df", "30".
std::string_view to_string(TimecodeRate rate);
/// The rate named "24", "25", "29.97df" (or "29.97"), "30"; nullopt for another text.
std::optional<TimecodeRate> parse_timecode_rate(std::string_view text);
/// The rate of `fps` frames per second within 0.05 % (30000/1001 is drop-frame); nullopt for another.
std::optional<TimecodeRate> timecode_rate_of(double fps);

struct Timecode {
  int hours = 0, minutes = 0, seconds = 0, frames = 0;
  auto operator<=>(const Timecode&) const = default;
};

/// Whether `tc` is a label of `rate`: hours [0, 23], minutes and seconds
/// [0, 59], frames [0, labels per second); drop-frame skips frames 0 and 1 at
/// second 0 of minutes not divisible by ten.
bool valid_timecode(const Timecode& tc, TimecodeRate rate);
/// The frame's number since 00:00:00:00 (the skipped labels not counted).
/// Throws std::invalid_argument naming the label and what is allowed for one
/// that is not valid_timecode.
std::int64_t frame_index(const Timecode& tc, TimecodeRate rate);
/// The label of frame `index` (taken modulo a day's frames).
Timecode timecode_at(std::int64_t index, TimecodeRate rate);
/// Real seconds since 00:00:00:00: frame_index / frames_per_second.
double timecode_seconds(const Timecode& tc, TimecodeRate rate);
/// The label of the frame nearest `seconds` since 00:00:00:00 (timecode_seconds' inverse).
Timecode timecode_at_seconds(double seconds, TimecodeRate rate);
/// "01:02:03:04", drop-frame "01:02:03;04" (the semicolon, as editors write it).
std::string format_timecode(const Timecode& tc, TimecodeRate rate);
/// Parses "hh:mm:ss:ff" (or "hh:mm:ss;ff", "hh:mm:ss.ff"). Throws
/// std::invalid_argument naming the text and the allowed form and ranges.
Timecode parse_timecode(std::string_view text, TimecodeRate rate);

}  // namespace zenith::show
