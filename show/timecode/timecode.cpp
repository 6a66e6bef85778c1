#include "show/timecode/timecode.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>

namespace zenith::show {

namespace {

// Drop-frame counts (SMPTE ST 12-1): a minute holds 1 798 frames but each
// tenth 1 800; ten minutes 17 982.
constexpr std::int64_t kDropFramesPerMinute = 1798;
constexpr std::int64_t kDropFramesPerTenMinutes = 17982;

std::int64_t positive_modulo(std::int64_t a, std::int64_t m) { return ((a % m) + m) % m; }

}  // namespace

double frames_per_second(TimecodeRate rate) {
  switch (rate) {
    case TimecodeRate::fps24: return 24.0;
    case TimecodeRate::fps25: return 25.0;
    case TimecodeRate::fps29_97_drop: return 30000.0 / 1001.0;
    case TimecodeRate::fps30: return 30.0;
  }
  return 30.0;
}

int labels_per_second(TimecodeRate rate) {
  switch (rate) {
    case TimecodeRate::fps24: return 24;
    case TimecodeRate::fps25: return 25;
    case TimecodeRate::fps29_97_drop:
    case TimecodeRate::fps30: return 30;
  }
  return 30;
}

std::int64_t frames_per_day(TimecodeRate rate) {
  if (rate == TimecodeRate::fps29_97_drop) return 24 * 6 * kDropFramesPerTenMinutes;
  return std::int64_t{24} * 3600 * labels_per_second(rate);
}

std::string_view to_string(TimecodeRate rate) {
  switch (rate) {
    case TimecodeRate::fps24: return "24";
    case TimecodeRate::fps25: return "25";
    case TimecodeRate::fps29_97_drop: return "29.97df";
    case TimecodeRate::fps30: return "30";
  }
  return "?";
}

std::optional<TimecodeRate> parse_timecode_rate(std::string_view text) {
  if (text == "24") return TimecodeRate::fps24;
  if (text == "25") return TimecodeRate::fps25;
  if (text == "29.97df" || text == "29.97") return TimecodeRate::fps29_97_drop;
  if (text == "30") return TimecodeRate::fps30;
  return std::nullopt;
}

std::optional<TimecodeRate> timecode_rate_of(double fps) {
  for (TimecodeRate r : {TimecodeRate::fps24, TimecodeRate::fps25, TimecodeRate::fps29_97_drop, TimecodeRate::fps30})
    if (std::abs(fps / frames_per_second(r) - 1.0) < 5e-4) return r;
  return std::nullopt;
}

bool valid_timecode(const Timecode& tc, TimecodeRate rate) {
  if (tc.hours < 0 || tc.hours > 23 || tc.minutes < 0 || tc.minutes > 59 || tc.seconds < 0 || tc.seconds > 59 ||
      tc.frames < 0 || tc.frames >= labels_per_second(rate))
    return false;
  return !(rate == TimecodeRate::fps29_97_drop && tc.seconds == 0 && tc.frames < 2 && tc.minutes % 10 != 0);
}

std::int64_t frame_index(const Timecode& tc, TimecodeRate rate) {
  if (!valid_timecode(tc, rate))
    throw std::invalid_argument(fmt::format(
        "timecode {:02}:{:02}:{:02}:{:02} is not a label at {} fps: hours [0, 23], minutes and seconds [0, 59], "
        "frames [0, {}){}",
        tc.hours, tc.minutes, tc.seconds, tc.frames, to_string(rate), labels_per_second(rate),
        rate == TimecodeRate::fps29_97_drop ? ", and no frames 0 and 1 at second 0 of a minute not divisible by 10"
                                            : ""));
  const std::int64_t minutes = std::int64_t{60} * tc.hours + tc.minutes;
  const std::int64_t labels = ((minutes * 60) + tc.seconds) * labels_per_second(rate) + tc.frames;
  if (rate != TimecodeRate::fps29_97_drop) return labels;
  return labels - 2 * (minutes - minutes / 10);  // two labels skipped a minute, but each tenth
}

Timecode timecode_at(std::int64_t index, TimecodeRate rate) {
  std::int64_t labels = positive_modulo(index, frames_per_day(rate));
  if (rate == TimecodeRate::fps29_97_drop) {
    // Put back the skipped labels: 18 per whole ten minutes, 2 per whole minute after the tenth's first.
    const std::int64_t tens = labels / kDropFramesPerTenMinutes, rest = labels % kDropFramesPerTenMinutes;
    labels += 18 * tens + (rest > 1 ? 2 * ((rest - 2) / kDropFramesPerMinute) : 0);
  }
  const std::int64_t per_second = labels_per_second(rate);
  Timecode tc;
  tc.frames = static_cast<int>(labels % per_second);
  tc.seconds = static_cast<int>((labels / per_second) % 60);
  tc.minutes = static_cast<int>((labels / (per_second * 60)) % 60);
  tc.hours = static_cast<int>((labels / (per_second * 3600)) % 24);
  return tc;
}

double timecode_seconds(const Timecode& tc, TimecodeRate rate) {
  return static_cast<double>(frame_index(tc, rate)) / frames_per_second(rate);
}

Timecode timecode_at_seconds(double seconds, TimecodeRate rate) {
  return timecode_at(static_cast<std::int64_t>(std::llround(seconds * frames_per_second(rate))), rate);
}

std::string format_timecode(const Timecode& tc, TimecodeRate rate) {
  return fmt::format("{:02}:{:02}:{:02}{}{:02}", tc.hours, tc.minutes, tc.seconds,
                     rate == TimecodeRate::fps29_97_drop ? ';' : ':', tc.frames);
}

Timecode parse_timecode(std::string_view text, TimecodeRate rate) {
  const auto fail = [&] {
    return std::invalid_argument(
        fmt::format("timecode '{}': expected hh:mm:ss:ff (or hh:mm:ss;ff) at {} fps, hours [0, 23], minutes and "
                    "seconds [0, 59], frames [0, {})",
                    text, to_string(rate), labels_per_second(rate)));
  };
  std::array<int, 4> fields{};
  std::size_t at = 0;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    if (f > 0) {
      if (at >= text.size() || (text[at] != ':' && text[at] != ';' && text[at] != '.')) throw fail();
      ++at;
    }
    const std::size_t start = at;
    int value = 0;
    while (at < text.size() && at - start < 2 && text[at] >= '0' && text[at] <= '9')
      value = value * 10 + (text[at++] - '0');
    if (at == start) throw fail();
    fields[f] = value;
  }
  if (at != text.size()) throw fail();
  const Timecode tc{fields[0], fields[1], fields[2], fields[3]};
  if (!valid_timecode(tc, rate)) {
    if (rate == TimecodeRate::fps29_97_drop && tc.seconds == 0 && tc.frames < 2 && tc.minutes % 10 != 0)
      throw std::invalid_argument(
          fmt::format("timecode '{}': drop-frame skips frames 0 and 1 at second 0 of a minute "
                      "not divisible by 10 (the next label is {:02}:{:02}:00;02)",
                      text, tc.hours, tc.minutes));
    throw fail();
  }
  return tc;
}

}  // namespace zenith::show
