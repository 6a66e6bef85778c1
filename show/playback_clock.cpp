#include "show/playback_clock.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/strings.h"

namespace zenith::show {
namespace {

using core::cat;

constexpr double kMaxRate = PlaybackClock::kMaxRate;
constexpr const char* kUsage =
    "commands: play | pause | toggle | seek SECONDS | rate FACTOR (-16..16) | loop on|off | status | quit";

/// Words separated by spaces or tabs.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r' || line[i] == '\n')) ++i;
    const std::size_t start = i;
    while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\r' || line[i] == '\n')) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

[[noreturn]] void usage(std::string_view line, const std::string& why) {
  throw std::invalid_argument(cat("\"", line, "\": ", why, "; ", kUsage));
}

double parse_number(std::string_view line, std::string_view text) {
  double x = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(x))
    usage(line, cat("\"", text, "\" is not a number"));
  return x;
}

}  // namespace

PlaybackClock::PlaybackClock(double duration_s, double fps, bool loop)
    : duration_s_(duration_s), fps_(fps), loop_(loop) {
  if (!(std::isfinite(duration_s) && duration_s >= 0.0))
    throw std::invalid_argument(cat("PlaybackClock: duration ", duration_s, " s must be finite and >= 0"));
  if (!(fps > 0.0 && fps <= 1000.0))
    throw std::invalid_argument(cat("PlaybackClock: fps ", fps, " must be in (0, 1000]"));
}

double PlaybackClock::next_frame_time_s() {
  const double t = time_s_;
  if (!playing_ || rate_ == 0.0 || finished_) return t;
  const double end = rate_ > 0.0 ? duration_s_ : 0.0;
  if (t == end) {
    // This frame is the last of a pass: start over, or stay and report it.
    if (loop_)
      time_s_ = rate_ > 0.0 ? 0.0 : duration_s_;
    else
      finished_ = true;
    return t;
  }
  // Advance; the end itself is always shown (never stepped over).
  time_s_ = std::clamp(t + rate_ / fps_, 0.0, duration_s_);
  return t;
}

void PlaybackClock::play() {
  if (finished_) {  // play again from the start
    time_s_ = rate_ >= 0.0 ? 0.0 : duration_s_;
    finished_ = false;
  }
  playing_ = true;
}

void PlaybackClock::pause() { playing_ = false; }

void PlaybackClock::seek(double show_time_s) {
  if (std::isnan(show_time_s)) throw std::invalid_argument("PlaybackClock::seek: time is NaN");
  time_s_ = std::clamp(show_time_s, 0.0, duration_s_);
  finished_ = false;
}

void PlaybackClock::set_rate(double rate) {
  if (!(rate >= -kMaxRate && rate <= kMaxRate))
    throw std::invalid_argument(cat("PlaybackClock: rate ", rate, " must be in [-16, 16]"));
  if ((rate > 0.0) != (rate_ > 0.0)) finished_ = false;  // a new direction has its own end
  rate_ = rate;
}

void PlaybackClock::set_loop(bool loop) {
  loop_ = loop;
  if (loop) finished_ = false;
}

bool PlaybackClock::playing() const { return playing_; }
bool PlaybackClock::looping() const { return loop_; }
double PlaybackClock::rate() const { return rate_; }
double PlaybackClock::time_s() const { return time_s_; }
double PlaybackClock::duration_s() const { return duration_s_; }
bool PlaybackClock::finished() const { return finished_; }

std::string PlaybackClock::status() const {
  char text[160];
  std::snprintf(text, sizeof text, "%s at %.3f s of %.3f s, rate %g, loop %s",
                finished_  ? "finished"
                : playing_ ? "playing"
                           : "paused",
                time_s_, duration_s_, rate_, loop_ ? "on" : "off");
  return text;
}

std::string PlaybackClock::apply_command(std::string_view line) {
  const std::vector<std::string_view> w = words(line);
  if (w.empty()) usage(line, "empty command");
  const std::string_view command = w[0];
  const std::size_t arguments = w.size() - 1;
  auto expect = [&](std::size_t n) {
    if (arguments != n) usage(line, cat("\"", command, "\" takes ", n == 0 ? "no argument" : "one argument"));
  };
  if (command == "play") {
    expect(0);
    play();
  } else if (command == "pause") {
    expect(0);
    pause();
  } else if (command == "toggle") {
    expect(0);
    if (playing_ && !finished_)
      pause();
    else
      play();
  } else if (command == "seek") {
    expect(1);
    seek(parse_number(line, w[1]));
  } else if (command == "rate") {
    expect(1);
    const double rate = parse_number(line, w[1]);
    if (!(rate >= -kMaxRate && rate <= kMaxRate)) usage(line, cat("rate ", rate, " is outside [-16, 16]"));
    set_rate(rate);
  } else if (command == "loop") {
    expect(1);
    if (w[1] == "on")
      set_loop(true);
    else if (w[1] == "off")
      set_loop(false);
    else
      usage(line, "loop takes \"on\" or \"off\"");
  } else if (command == "status") {
    expect(0);
  } else {
    usage(line, cat("unknown command \"", command, "\""));
  }
  return status();
}

}  // namespace zenith::show
