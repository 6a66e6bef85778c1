// The ordered writing stage of the offline pipeline (offline/frame_writer_pool.h).
#include "offline/frame_writer_pool.h"

#include <stdexcept>
#include <system_error>
#include <utility>

#include "offline/offline_manifest.h"

namespace zenith::app::offline {
namespace {

std::filesystem::path staging_path(const std::filesystem::path& path) {
  std::filesystem::path staging = path;
  staging += ".partial";
  return staging;
}

void remove_quietly(const std::filesystem::path& path) noexcept {
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

}  // namespace

FrameWriterPool::FrameWriterPool(int threads) {
  if (threads < 0) throw std::invalid_argument("FrameWriterPool: threads must be ≥ 0");
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
}

FrameWriterPool::~FrameWriterPool() {
  {
    std::unique_lock lock(mutex_);
    progress_.wait(lock, [&] { return pending_.empty(); });
    stopping_ = true;
  }
  work_ready_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void FrameWriterPool::rethrow_error() {
  if (error_) std::rethrow_exception(error_);
}

void FrameWriterPool::submit(Frame frame) {
  std::unique_lock lock(mutex_);
  if (error_) {
    if (frame.released) frame.released();
    rethrow_error();
  }
  const std::uint64_t sequence = next_sequence_++;
  Pending& p = pending_[sequence];
  p.sha256.resize(frame.files.size());
  p.files_left = frame.files.size();
  p.frame = std::move(frame);
  for (std::size_t i = 0; i < p.frame.files.size(); ++i) tasks_.push_back({sequence, i});
  if (workers_.empty()) {  // the simple path: write here, in order
    while (!tasks_.empty()) {
      const Task task = tasks_.front();
      tasks_.pop_front();
      run_task(task, lock);
    }
    publish_ready();
    rethrow_error();
    return;
  }
  if (p.files_left == 0) publish_ready();
  lock.unlock();
  work_ready_.notify_all();
}

void FrameWriterPool::run_task(const Task& task, std::unique_lock<std::mutex>& lock) {
  Pending& p = pending_.at(task.sequence);                      // std::map: stays valid while unlocked
  const bool skip = p.failed || task.sequence > first_failed_;  // a frame after a failed one is not kept
  const File& file = p.frame.files[task.file];
  std::string hash;
  std::exception_ptr failure;
  if (!skip) {
    lock.unlock();
    try {
      const std::filesystem::path staging = staging_path(file.path);
      file.write(staging);
      hash = file_sha256(staging);
    } catch (...) {
      failure = std::current_exception();
    }
    lock.lock();
  }
  if (failure) {
    p.failed = true;
    if (task.sequence < first_failed_) {  // the error of the earliest failing frame is the one reported
      first_failed_ = task.sequence;
      error_ = failure;
    }
  }
  p.sha256[task.file] = std::move(hash);
  --p.files_left;
}

void FrameWriterPool::publish_ready() {
  while (!pending_.empty() && pending_.begin()->first == next_to_publish_ && pending_.begin()->second.files_left == 0) {
    Pending& p = pending_.begin()->second;
    const std::uint64_t sequence = pending_.begin()->first;
    if (sequence < first_failed_) {  // every earlier frame is published: this one is kept
      try {
        for (const File& f : p.frame.files) {
          std::error_code ec;
          std::filesystem::rename(staging_path(f.path), f.path, ec);
          if (ec)
            throw std::runtime_error(f.path.string() + ": cannot rename " + staging_path(f.path).string() +
                                     " into place: " + ec.message());
        }
        if (p.frame.published) p.frame.published();
        written_.push_back({p.frame.frame, std::move(p.sha256)});
      } catch (...) {
        p.failed = true;
        first_failed_ = sequence;
        error_ = std::current_exception();
      }
    }
    if (sequence >= first_failed_)  // this frame or an earlier one failed: nothing of it stays
      for (const File& f : p.frame.files) remove_quietly(staging_path(f.path));
    if (p.frame.released) p.frame.released();
    pending_.erase(pending_.begin());
    ++next_to_publish_;
  }
  progress_.notify_all();
}

void FrameWriterPool::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    work_ready_.wait(lock, [&] { return stopping_ || !tasks_.empty(); });
    if (tasks_.empty()) return;  // stopping, nothing left
    const Task task = tasks_.front();
    tasks_.pop_front();
    run_task(task, lock);
    publish_ready();
  }
}

std::vector<WrittenFrame> FrameWriterPool::take_written() {
  std::unique_lock lock(mutex_);
  return std::exchange(written_, {});
}

void FrameWriterPool::finish() {
  std::unique_lock lock(mutex_);
  progress_.wait(lock, [&] { return pending_.empty(); });
  rethrow_error();
}

}  // namespace zenith::app::offline
