#pragma once
// The operator's fade (docs/operator.md, "Fades"): every output of every node
// fades toward a colour (black, or any display-linear RGB) and back over a
// given time, or blacks out at once. A fade is a ramp over frames, started at
// the next frame to begin; each frame's level goes into its FrameState
// (scene::FadeState), so every node applies the same level at the same frame
// and a recording keeps it like any other state. No clock, no sockets: the
// master's frame rate converts the duration into frames once, so the ramp is
// the same however late a frame starts (tests/cluster/fade_control_test.cpp).
//
// The curve is smoothstep, s(u) = u²(3 − 2u) with u = (frame − start + 1) / n
// clamped to [0, 1] and n = round(seconds · fps) frames: the level moves from
// where it was, with zero slope at both ends (no visible kink when a fade
// starts or lands), and is half-way at u = ½. The first frame of a fade is
// already one step in; a fade of 0 s (n = 0) is at its target at its first
// frame: a blackout is black at the next frame on every node.
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include "scene/frame_description.h"

namespace zenith::cluster {

/// The longest fade an operator may ask for (s): an hour.
inline constexpr double kMaxFadeSeconds = 3600.0;

/// smoothstep: 0 at u ≤ 0, 1 at u ≥ 1, u²(3 − 2u) between (slope 0 at both ends).
double fade_curve(double u);

class FadeControl {
 public:
  /// `fps`: the master's frame rate (> 0), which turns seconds into frames.
  explicit FadeControl(double fps);

  /// A fade that starts at `frame` (the next frame to begin) from the fade
  /// shown at that frame toward `level` in [0, 1] over `seconds` in
  /// [0, kMaxFadeSeconds]. `colour` (each component in [0, 1]) replaces the
  /// colour at once when the picture is fully visible when it starts, else
  /// the colour moves with the level; unset, the colour stays. Throws
  /// std::invalid_argument (naming the value and its range) for values out of range.
  void start(std::uint64_t frame, double level, std::optional<glm::dvec3> colour, double seconds);

  /// The operator's fade at `frame`.
  scene::FadeState at(std::uint64_t frame) const;
  /// Whether the operator's fade decides `frame`: moving, or resting away from
  /// the picture. At rest on the picture it does not, and a frame keeps the
  /// fade it came with (a recording's, played back).
  bool active(std::uint64_t frame) const;
  /// Puts the operator's fade on `next` when active(next.frame).
  void apply(scene::FadeState& fade, std::uint64_t frame) const;

  /// The ramp's ends, its frames and its start (for the console's status).
  double target_level() const { return to_.level; }
  const glm::dvec3& target_colour() const { return to_.colour; }
  std::uint64_t frames() const { return frames_; }
  std::uint64_t start_frame() const { return start_; }
  /// Frames left until the target, counted from `frame` (0 at rest).
  std::uint64_t frames_left(std::uint64_t frame) const;
  double fps() const { return fps_; }

 private:
  double fps_;
  scene::FadeState from_, to_;
  std::uint64_t start_ = 0;   ///< the fade's first frame
  std::uint64_t frames_ = 0;  ///< n: frames to the target (0: at once)
};

}  // namespace zenith::cluster
