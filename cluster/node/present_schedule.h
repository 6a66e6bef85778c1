#pragma once
// When a render node renders and presents scheduled frames (docs/cluster.md,
// "The frame schedule"). The master sends each frame ahead of time with the
// moment to present it (FrameSchedule, in the node's clock once mapped by
// ClockSync); the node renders one frame at a time — the next one due — and
// presents it at its moment, whether or not any other node has, so no link
// and no node can hold another one up.
//
// One frame is "current" at a time: queued for rendering (or rendered) and
// waiting for its moment. At that moment it is presented and the next
// pending frame becomes current, so the render thread renders frame n + 1
// while frame n is on the screen, as under the barrier. A frame that arrives
// after its moment, or whose moment passes before it can become current (the
// node was cut off, or rendered too slowly), is dropped and counted as missed:
// the projector keeps the last frame, then shows the next one on time. Frames
// only go forward: a duplicate or a frame older than the last presented is
// ignored; one older than the current frame but still in time (its earlier
// copies were lost) goes first, and the current one is rendered again after it.
//
// A present is handed out `handoff` before its moment (present_handoff()):
// the render thread then sleeps until the moment itself, so the moment is met
// by one thread waking (present_timing.h), not by the networking thread's
// timer and then the render thread's queue.
//
// Pure bookkeeping: time is passed in (tests/cluster/present_schedule_test.cpp).
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>

#include "cluster/protocol/messages.h"

namespace zenith::cluster {

class PresentSchedule {
 public:
  using Clock = std::chrono::steady_clock;

  /// `handoff`: how long before its moment a present step is handed out.
  explicit PresentSchedule(Clock::duration handoff = Clock::duration::zero()) : handoff_(handoff) {}

  /// What became of a frame handed to on_frame().
  enum class Arrival {
    taken,      ///< pending (or current): it will be presented at its moment
    duplicate,  ///< already taken (another copy of it)
    stale,      ///< older than a frame already taken
    late,       ///< its moment has passed
  };
  /// What the node does next.
  struct Step {
    enum class Kind { render, present } kind = Kind::render;
    std::uint64_t frame = 0;
    FrameState state;  ///< render
    Clock::time_point present_at{};
  };

  Arrival on_frame(const FrameState& state, Clock::time_point present_at, Clock::time_point now);
  /// The next step at `now`, if any: present the current frame when its
  /// moment is at most the handoff away (the step carries the moment, which
  /// the render thread waits for), else make the next pending frame current
  /// (render it).
  /// Call until it returns nothing, then wait until wake_at().
  std::optional<Step> next(Clock::time_point now);
  /// When next() has something to do again (the current frame's moment less the handoff);
  /// nothing while there is no current frame (a new frame wakes the node).
  std::optional<Clock::time_point> wake_at() const;

  /// Frames presented, and frames missed: dropped because they came too late,
  /// or their moment passed before they could be rendered, or never came
  /// (a gap in the frame numbers presented).
  std::uint64_t presented() const { return presented_; }
  std::uint64_t missed() const { return missed_; }
  /// The last frame presented (nothing before the first).
  std::optional<std::uint64_t> last_presented() const { return last_presented_; }
  std::size_t pending() const { return pending_.size(); }

 private:
  struct Pending {
    FrameState state;
    Clock::time_point present_at;
  };
  Clock::duration handoff_;
  std::map<std::uint64_t, Pending> pending_;
  std::optional<Step> current_;  ///< rendered (or queued), waiting for its moment
  std::optional<std::uint64_t> last_presented_;
  std::uint64_t presented_ = 0, missed_ = 0;
};

/// How long before its moment a node hands a frame's present to its render
/// thread: long enough that the networking thread, woken by its timer on a busy
/// machine, is rarely later than the moment; short, because the render thread
/// waits for the moment and does nothing else meanwhile: 4 ms, at most half a
/// period (2.1 ms at 240 Hz).
PresentSchedule::Clock::duration present_handoff(double frame_rate_hz);

/// "taken", "duplicate", "stale", "late".
const char* to_string(PresentSchedule::Arrival arrival);

/// The render thread's rule for a frame it is about to render while a later
/// frame's render waits behind it (the machine was busy: the frame before took
/// longer than a period). Under the barrier (`later_moment` empty) the frame is
/// dropped: the master has moved on. On a schedule it is dropped only once the
/// later frame's moment `later_moment` has come: until then there is time to
/// show it, late, and the later one on time — a few milliseconds of one
/// projector behind the others instead of a frame missing from it.
bool drop_frame_behind(std::optional<PresentSchedule::Clock::time_point> later_moment,
                       PresentSchedule::Clock::time_point now);

}  // namespace zenith::cluster
