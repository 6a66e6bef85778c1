#pragma once
// The encoding and writing stage of the offline pipeline (docs/shows.md,
// "The pipeline"): a pool of worker threads encodes and writes each frame's
// files, several frames at once, and publishes whole frames strictly in
// order. A file is written as NAME.partial and hashed by its worker; when it
// and every earlier frame are complete, the frame's files are renamed into
// place, its `published` callback runs (e.g. the video proxy's next frame)
// and it joins the frames take_written() returns. So the folder only ever
// holds a prefix of the submitted frames under their final names, whatever
// the workers' order and wherever the process is killed.
//
// An error (an encoder's, a full disk, a folder that cannot be written) stops
// publication at the failing frame: its files and every later frame's are
// removed, the frames before it stay published, and the error (naming the
// file) is rethrown by the next submit() or finish(). No GL:
// the caller hands over pixels already read back.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace zenith::app::offline {

/// A frame published in order, with the SHA-256 (hex) of each of its files in the order they were given.
struct WrittenFrame {
  std::uint64_t frame = 0;
  std::vector<std::string> file_sha256;
};

class FrameWriterPool {
 public:
  /// Writes one file: everything at `staging` (NAME.partial), which the pool renames to NAME.
  using WriteFile = std::function<void(const std::filesystem::path& staging)>;
  struct File {
    std::filesystem::path path;  ///< its final name
    WriteFile write;
  };
  struct Frame {
    std::uint64_t frame = 0;
    std::vector<File> files;
    /// Runs once its files are in place, in frame order, before the next frame's (under the pool's lock: keep it
    /// short).
    std::function<void()> published;
    /// Runs once the frame is done with, published or discarded (e.g. frees the memory its files were written from).
    std::function<void()> released;
  };

  /// `threads` ≥ 1 workers; 0: every file is written inside submit(), on the caller's thread (the simple path).
  explicit FrameWriterPool(int threads);
  /// Waits for the queued work (without throwing) and stops the workers.
  ~FrameWriterPool();
  FrameWriterPool(const FrameWriterPool&) = delete;
  FrameWriterPool& operator=(const FrameWriterPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()); }
  /// Queues a frame; frames must come in increasing frame order. Throws the pool's first error.
  void submit(Frame frame);
  /// The frames published since the last call, in order (also after an error: those before it).
  std::vector<WrittenFrame> take_written();
  /// Waits until every submitted frame is published or discarded; throws the pool's first error.
  void finish();

 private:
  struct Pending {
    Frame frame;
    std::vector<std::string> sha256;
    std::size_t files_left = 0;
    bool failed = false;
  };
  struct Task {
    std::uint64_t sequence = 0;
    std::size_t file = 0;
  };

  void work();
  /// Writes and hashes one file of frame `sequence` (without the lock).
  void run_task(const Task& task, std::unique_lock<std::mutex>& lock);
  /// Publishes or discards the frames at the head of the order that are done (with the lock).
  void publish_ready();
  void rethrow_error();  // with the lock

  std::mutex mutex_;
  std::condition_variable work_ready_, progress_;
  std::map<std::uint64_t, Pending> pending_;  ///< by submission sequence
  std::deque<Task> tasks_;
  std::uint64_t next_sequence_ = 0, next_to_publish_ = 0;
  std::vector<WrittenFrame> written_;
  std::exception_ptr error_;                 ///< that of the earliest failing frame
  std::uint64_t first_failed_ = UINT64_MAX;  ///< its sequence
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace zenith::app::offline
