#include "show/timecode/timecode_chase.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace zenith::show {

void validate(const ChaseSettings& s) {
  const auto check = [](bool ok, std::string_view field, std::string_view range, double value) {
    if (!ok) throw std::invalid_argument(fmt::format("timecode chase: {} = {} outside {}", field, value, range));
  };
  check(s.offset_s >= 0.0 && s.offset_s < 86400.0, "offset_s", "[0, 86400)", s.offset_s);
  check(s.freewheel_s >= 0.0 && s.freewheel_s <= 3600.0, "freewheel_s", "[0, 3600]", s.freewheel_s);
  check(s.lock_frames >= 2 && s.lock_frames <= 30, "lock_frames", "[2, 30]", s.lock_frames);
  check(s.jump_frames >= 0.5 && s.jump_frames <= 100.0, "jump_frames", "[0.5, 100]", s.jump_frames);
  check(s.dropout_frames >= 1.5 && s.dropout_frames <= 100.0, "dropout_frames", "[1.5, 100]", s.dropout_frames);
}

std::string_view to_string(ChaseState state) {
  switch (state) {
    case ChaseState::waiting: return "waiting for timecode";
    case ChaseState::locking: return "locking";
    case ChaseState::locked: return "locked";
    case ChaseState::freewheeling: return "freewheeling";
    case ChaseState::held: return "held (no timecode)";
    case ChaseState::stopped: return "stopped (no timecode)";
  }
  return "?";
}

TimecodeChase::TimecodeChase(const ChaseSettings& settings) : settings_(settings) { validate(settings_); }

void TimecodeChase::set_offset_s(double offset_s) {
  ChaseSettings s = settings_;
  s.offset_s = offset_s;
  validate(s);
  held_timecode_s_ += offset_s - settings_.offset_s;  // a held show keeps its show time
  settings_ = s;
}

void TimecodeChase::resume() {
  if (state_ == ChaseState::stopped) state_ = ChaseState::locking;
}

void TimecodeChase::continue_from(double show_time_s) {
  floor_s_ = show_time_s;
  if (ever_locked_) return;
  held_timecode_s_ = settings_.offset_s + show_time_s;
  ever_locked_ = true;
  if (state_ == ChaseState::waiting) state_ = ChaseState::held;
}

TimecodeChase::Line TimecodeChase::fit(const std::deque<Point>& points, double default_speed) {
  Line line;
  if (points.empty()) return line;
  for (const Point& p : points) {
    line.local_mean_s += p.local_s;
    line.timecode_mean_s += p.timecode_s;
  }
  const auto n = static_cast<double>(points.size());
  line.local_mean_s /= n;
  line.timecode_mean_s /= n;
  double tt = 0.0, ty = 0.0;
  for (const Point& p : points) {
    tt += (p.local_s - line.local_mean_s) * (p.local_s - line.local_mean_s);
    ty += (p.local_s - line.local_mean_s) * (p.timecode_s - line.timecode_mean_s);
  }
  line.speed = points.size() >= 2 && tt > 1e-12 ? ty / tt : default_speed;
  return line;
}

double TimecodeChase::unwrapped(double timecode_s, double near_s, TimecodeRate rate) {
  const double day_s = static_cast<double>(frames_per_day(rate)) / frames_per_second(rate);
  while (timecode_s - near_s > day_s / 2) timecode_s -= day_s;
  while (near_s - timecode_s > day_s / 2) timecode_s += day_s;
  return timecode_s;
}

void TimecodeChase::receive(const TimecodeEvent& e) {
  if (!valid_timecode(e.timecode, e.rate)) return;  // a damaged frame: the decoders' labels are checked again here
  if (e.rate != rate_ && (!points_.empty() || !candidate_.empty())) {
    // Another rate: nothing measured before holds.
    points_.clear();
    candidate_.clear();
    if (state_ == ChaseState::locked || state_ == ChaseState::freewheeling) state_ = ChaseState::locking;
  }
  rate_ = e.rate;
  last_ = e.timecode;
  last_local_s_ = e.local_s;
  const double tolerance_s = settings_.jump_frames * frame_s();
  const bool following = state_ == ChaseState::locked || state_ == ChaseState::freewheeling;
  double tc = timecode_seconds(e.timecode, e.rate);
  if (following) {
    const double predicted = line_.at(e.local_s);
    tc = unwrapped(tc, predicted, e.rate);
    if (std::abs(tc - predicted) <= tolerance_s) {  // on the line: follow it
      points_.push_back({e.local_s, tc});
      if (points_.size() > kChaseWindow) points_.pop_front();
      line_ = fit(points_, line_.speed);
      candidate_.clear();
      state_ = ChaseState::locked;
      return;
    }
  }
  // Off the line, or not following yet: frames in a row that agree with each other.
  if (!candidate_.empty()) {
    const Point& previous = candidate_.back();
    tc = unwrapped(tc, previous.timecode_s, e.rate);
    const double step_local = e.local_s - previous.local_s, step_tc = tc - previous.timecode_s;
    const double direction = step_tc < 0.0 ? -1.0 : 1.0;
    if (std::abs(step_tc - direction * step_local) > tolerance_s) candidate_.clear();
  }
  candidate_.push_back({e.local_s, tc});
  // A held show holds its frame until the timecode locks again; a stopped one waits for resume().
  if (!following && state_ != ChaseState::held && state_ != ChaseState::stopped) state_ = ChaseState::locking;
  if (state_ == ChaseState::stopped) {
    if (candidate_.size() > kChaseWindow) candidate_.pop_front();
    return;
  }
  if (static_cast<int>(candidate_.size()) < settings_.lock_frames) return;
  if (following) ++locates_;  // the timecode jumped while the show followed it
  const double direction = candidate_.back().timecode_s < candidate_.front().timecode_s ? -1.0 : 1.0;
  points_ = std::move(candidate_);
  candidate_.clear();
  line_ = fit(points_, direction);
  state_ = ChaseState::locked;
  ever_locked_ = true;
}

double TimecodeChase::show_time(double timecode_s, ChasePosition& p) const {
  const double s = timecode_s - settings_.offset_s;
  if (s < 0.0) {
    p.before_start = true;
    return 0.0;
  }
  return s;
}

ChasePosition TimecodeChase::position(double local_s, double now_s) {
  ChasePosition p;
  if (state_ == ChaseState::locked || state_ == ChaseState::freewheeling) {
    const double dropout_at = last_local_s_ + settings_.dropout_frames * frame_s();
    if (now_s > dropout_at + settings_.freewheel_s) {
      // Held where the freewheel ended, or where a frame sent ahead of its
      // moment already was: a held show never steps back.
      const double end = line_.at(dropout_at + settings_.freewheel_s);
      held_timecode_s_ = line_.speed >= 0.0 ? std::max(end, held_timecode_s_) : std::min(end, held_timecode_s_);
      state_ = settings_.after_dropout == ChaseSettings::AfterDropout::hold ? ChaseState::held : ChaseState::stopped;
    } else {
      state_ = now_s > dropout_at ? ChaseState::freewheeling : ChaseState::locked;
    }
  }
  p.state = state_;
  p.last = last_;
  p.rate = rate_;
  p.locates = locates_;
  p.offset_s = settings_.offset_s;
  switch (state_) {
    case ChaseState::locked:
    case ChaseState::freewheeling:
      p.speed = line_.speed;
      p.drift_ppm = (std::abs(line_.speed) - 1.0) * 1e6;
      held_timecode_s_ = line_.at(local_s);
      p.show_time_s = show_time(held_timecode_s_, p);
      break;
    case ChaseState::waiting: p.show_time_s = 0.0; break;
    case ChaseState::locking:
      if (!ever_locked_) {  // the show's start until the timecode first locks
        p.show_time_s = 0.0;
        break;
      }
      [[fallthrough]];
    case ChaseState::held:
    case ChaseState::stopped:
      p.speed = 0.0;
      p.show_time_s = show_time(held_timecode_s_, p);
      break;
  }
  if (floor_s_) {
    if (p.speed < 0.0 || p.show_time_s > *floor_s_)
      floor_s_.reset();  // the timecode has passed it (or runs backwards)
    else
      p.show_time_s = *floor_s_;
  }
  return p;
}

}  // namespace zenith::show
