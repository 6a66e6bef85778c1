#include "cluster/master/frame_feed.h"

#include <stdexcept>
#include <string>

namespace zenith::cluster {

void FrameFeed::push(scene::FrameDescription state) {
  {
    std::lock_guard lock(mutex_);
    const std::optional<std::uint64_t> previous =
        !queue_.empty() ? std::optional(queue_.back().frame) : last_presented_;
    if (previous && state.frame <= *previous)
      throw std::invalid_argument("FrameFeed: frame " + std::to_string(state.frame) + " after frame " +
                                  std::to_string(*previous) + ": frame numbers must increase");
    queue_.push_back(std::move(state));
  }
  changed_.notify_all();
}

void FrameFeed::finish() {
  {
    std::lock_guard lock(mutex_);
    finished_ = true;
  }
  changed_.notify_all();
}

bool FrameFeed::wait_presented(std::uint64_t frame, std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return stopped_ || (last_presented_ && *last_presented_ >= frame); });
  return last_presented_ && *last_presented_ >= frame;
}

bool FrameFeed::stopped() const {
  std::lock_guard lock(mutex_);
  return stopped_;
}

FrameFeed::Next FrameFeed::pop(scene::FrameDescription& state) {
  std::lock_guard lock(mutex_);
  if (!queue_.empty()) {
    state = std::move(queue_.front());
    queue_.pop_front();
    return Next::frame;
  }
  return finished_ ? Next::finished : Next::wait;
}

bool FrameFeed::done() const {
  std::lock_guard lock(mutex_);
  return finished_ && queue_.empty();
}

void FrameFeed::presented(std::uint64_t frame) {
  {
    std::lock_guard lock(mutex_);
    last_presented_ = frame;
  }
  changed_.notify_all();
}

void FrameFeed::master_stopped() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
}

}  // namespace zenith::cluster
