#pragma once
// Playback control (docs/shows.md, "Playback"): turns presented frames into
// show time under play, pause, seek, loop and rate. The master asks for the
// show time of each frame it starts; operators change the clock between
// frames (console or control socket), so every node always gets one
// consistent state per frame.
#include <cstdint>
#include <string>
#include <string_view>

namespace zenith::show {

class PlaybackClock {
 public:
  /// The fastest playback either way: rates are in [−kMaxRate, kMaxRate].
  static constexpr double kMaxRate = 16.0;

  /// `duration_s` ≥ 0, `fps` in (0, 1000]. Starts playing at time 0, rate 1.
  PlaybackClock(double duration_s, double fps, bool loop);

  /// Show time of the frame being started, then advances by rate / fps when
  /// playing (holds when paused). At the end: wraps to 0 when looping, holds at
  /// the end and reports finished() otherwise. Rates may be negative (reverse;
  /// the start is then the end).
  double next_frame_time_s();

  void play();
  void pause();
  /// Jumps to t, clamped to [0, duration]; the next frame shows t.
  void seek(double show_time_s);
  /// Rate in [−16, 16]; throws std::invalid_argument outside.
  void set_rate(double rate);
  void set_loop(bool loop);

  bool playing() const;
  bool looping() const;
  double rate() const;
  double time_s() const;  ///< show time of the next frame
  double duration_s() const;
  /// Not looping and the last frame at the end (or start, reversed) was handed out.
  bool finished() const;

  /// Applies one operator command and returns a one-line reply:
  ///   play | pause | toggle | seek SECONDS | rate FACTOR | loop on|off | status
  /// Throws std::invalid_argument with the usage for anything else ("quit" is
  /// handled by the caller).
  std::string apply_command(std::string_view line);
  /// "playing at 12.500 s of 60.000 s, rate 1, loop off".
  std::string status() const;

 private:
  double duration_s_, fps_, time_s_ = 0.0, rate_ = 1.0;
  bool loop_, playing_ = true, finished_ = false;
};

}  // namespace zenith::show
