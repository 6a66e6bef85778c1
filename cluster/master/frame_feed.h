#pragma once
// Drives the master frame by frame from another thread (docs/shows.md,
// "Offline rendering", --cluster): instead of its own show clock, the master
// takes each frame's state from the feed, and the feeding thread waits until
// the frame is presented on every node. Thread-safe; the master's networking
// thread is the consumer, one other thread the producer.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>

#include "scene/frame_description.h"

namespace zenith::cluster {

class FrameFeed {
 public:
  // ---- the producer ----
  /// Queues a frame's state (frame numbers must increase).
  void push(scene::FrameDescription state);
  /// No more frames: the master says Goodbye once the queue is empty.
  void finish();
  /// Blocks until frame `frame` was presented (true), the master stopped or
  /// `timeout` passed (false).
  bool wait_presented(std::uint64_t frame, std::chrono::milliseconds timeout);
  /// Whether the master stopped (it will present nothing more).
  bool stopped() const;

  // ---- the master ----
  enum class Next { frame, wait, finished };
  /// The next state to render, if any: Next::frame fills `state`.
  Next pop(scene::FrameDescription& state);
  void presented(std::uint64_t frame);
  void master_stopped();
  /// finish() was called and every queued frame was taken.
  bool done() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<scene::FrameDescription> queue_;
  std::optional<std::uint64_t> last_presented_;
  bool finished_ = false, stopped_ = false;
};

}  // namespace zenith::cluster
