#pragma once
// Show time from the house's timecode (docs/shows.md, "Chasing timecode"):
// the frames of LTC or MTC as they arrive, each with its label and the local
// time it arrived, turned into the show time to present at any local time.
//
// While the timecode runs, show time = timecode time − the show's offset,
// from a least-squares line through the frames since the chase locked (at
// most kChaseWindow of them): the line's slope is the timecode's speed
// against the local clock (its drift, in ppm, reported), so the show follows
// a soundtrack that runs 0.1 % fast frame for frame, and the jitter of single
// frames averages out. A frame off the line by more than
// ChaseSettings::jump_frames is a locate (the audio jumped) once
// `lock_frames` frames in a row agree with it — a single damaged frame is
// ignored — and the show jumps with it. Without frames for `dropout_frames`
// frame periods the show freewheels on the line for `freewheel_s`, then holds
// its last frame or stops (the operator's choice); when timecode returns it
// locks again. Timecode before the show's start holds the show at its start.
// No clock of its own: the caller gives every time (tests run a day of
// timecode in microseconds).
#include <deque>
#include <optional>
#include <string_view>

#include "show/timecode/timecode.h"

namespace zenith::show {

struct ChaseSettings {
  /// The timecode's real seconds at show time 0 (a show that starts at
  /// 01:00:00:00 at 25 fps: 3600 s), in [0, 86400).
  double offset_s = 0.0;
  /// Through a dropout the show runs on at the timecode's speed this long,
  /// in [0, 3600] s; then it holds or stops.
  double freewheel_s = 2.0;
  enum class AfterDropout { hold, stop };
  AfterDropout after_dropout = AfterDropout::hold;
  /// Frames in a row that agree before the chase locks, or follows a locate, in [2, 30].
  int lock_frames = 3;
  /// A frame further than this from the line is a locate, not jitter, in [0.5, 100] frames.
  double jump_frames = 1.5;
  /// No frame for this many frame periods is a dropout, in [1.5, 100].
  double dropout_frames = 4.0;
};
/// Throws std::invalid_argument naming the field and its range.
void validate(const ChaseSettings& settings);

enum class ChaseState {
  waiting,       ///< no timecode yet
  locking,       ///< frames arriving, not yet lock_frames that agree
  locked,        ///< following the timecode
  freewheeling,  ///< the timecode stopped: running on at its speed
  held,          ///< freewheel over: the show holds its last frame until the timecode returns
  stopped,       ///< freewheel over, AfterDropout::stop: the show stops until resume()
};
std::string_view to_string(ChaseState state);

/// A timecode frame as received: its label and rate, and the local time its
/// frame began (LTC: the audio clock at its first bit; MTC: the receive time
/// of the quarter frame that completed it, less its two frames).
struct TimecodeEvent {
  Timecode timecode;
  TimecodeRate rate = TimecodeRate::fps25;
  double local_s = 0.0;
};

struct ChasePosition {
  ChaseState state = ChaseState::waiting;
  double show_time_s = 0.0;      ///< to present at the local time asked for
  double speed = 1.0;            ///< timecode seconds per local second (−1: played backwards)
  double drift_ppm = 0.0;        ///< (|speed| − 1) · 10⁶ while locked or freewheeling
  std::optional<Timecode> last;  ///< the last frame received, and its rate
  TimecodeRate rate = TimecodeRate::fps25;
  double offset_s = 0.0;      ///< the timecode's real seconds at show time 0 (ChaseSettings::offset_s)
  int locates = 0;            ///< jumps followed since the start
  bool before_start = false;  ///< the timecode is before the show's offset: held at 0
};

/// Frames the line is fitted through, at most: 64 (2.1 s at 30 fps).
inline constexpr std::size_t kChaseWindow = 64;

class TimecodeChase {
 public:
  /// Throws what validate(settings) throws.
  explicit TimecodeChase(const ChaseSettings& settings);

  /// A frame, in order of local time.
  void receive(const TimecodeEvent& event);
  /// Where the show is at `local_s` (not before the last frame received),
  /// asked at that time.
  ChasePosition position(double local_s) { return position(local_s, local_s); }
  /// Where the show will be at `moment_s`, asked at `now_s` ≤ moment_s: a
  /// master sends its frames ahead of their moment (the cluster's
  /// lookahead); whether the timecode has dropped out is judged at `now_s`.
  ChasePosition position(double moment_s, double now_s);

  const ChaseSettings& settings() const { return settings_; }
  /// The show's offset from the console: show time jumps with it (a held
  /// show keeps its frame). Throws std::invalid_argument outside [0, 86400).
  void set_offset_s(double offset_s);
  /// The operator starts a stopped chase again: it locks to the timecode as it arrives.
  void resume();
  /// The show goes on from `show_time_s` (a standby taking over from the
  /// active master's last frame): a chase that has never locked holds there
  /// until it does, instead of at its start; and while the timecode runs
  /// forward no position is below it until the timecode passes it (that
  /// frame was sent ahead of its moment: nodes may present it after the
  /// first ones asked for now).
  void continue_from(double show_time_s);

 private:
  struct Point {
    double local_s, timecode_s;
  };
  /// The line through `points`: timecode seconds at local time t.
  struct Line {
    double local_mean_s = 0.0, timecode_mean_s = 0.0, speed = 1.0;
    double at(double local_s) const { return timecode_mean_s + speed * (local_s - local_mean_s); }
  };
  static Line fit(const std::deque<Point>& points, double default_speed);
  /// The frame's timecode seconds, unwrapped across midnight towards `near_s`.
  static double unwrapped(double timecode_s, double near_s, TimecodeRate rate);
  double frame_s() const { return 1.0 / frames_per_second(rate_); }
  /// Show time from timecode seconds; notes a timecode before the start.
  double show_time(double timecode_s, ChasePosition& p) const;

  ChaseSettings settings_;
  ChaseState state_ = ChaseState::waiting;
  TimecodeRate rate_ = TimecodeRate::fps25;
  std::deque<Point> points_;     ///< the line's, since it locked or last located
  std::deque<Point> candidate_;  ///< frames in a row off the line: a locate once lock_frames agree
  Line line_;
  std::optional<Timecode> last_;
  double last_local_s_ = 0.0;
  double held_timecode_s_ = 0.0;  ///< where a held or stopped show stays
  int locates_ = 0;
  bool ever_locked_ = false;       ///< a frame to hold: the chase locked once, or continue_from
  std::optional<double> floor_s_;  ///< continue_from's show time, until the timecode passes it
};

}  // namespace zenith::show
