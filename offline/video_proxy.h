#pragma once
// A review proxy of a rendered show (`zenith show render --video FILE`,
// docs/shows.md): the frames' display codes, in order, piped to ffmpeg as raw
// RGBA and encoded by it (H.264, yuv420p, scaled to at most
// kMaxProxyEdgePx on the longer side, even sizes). zenith has no encoder of its
// own; ffmpeg is a dependency installed by scripts/bootstrap. ffmpeg's messages
// go to FILE.log.
#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

namespace zenith::app::offline {

inline constexpr int kMaxProxyEdgePx = 2048;

/// The ffmpeg program on PATH, or nullopt.
std::optional<std::filesystem::path> find_ffmpeg();

class VideoProxy {
 public:
  /// Starts ffmpeg writing `path` from frames of width × height pixels of
  /// `bits` (8 or 16) bits a sample at `fps`. Throws std::runtime_error naming
  /// --video when ffmpeg is not installed or cannot be started.
  VideoProxy(const std::filesystem::path& path, int width, int height, int bits, double fps);
  /// Without finish(): stops ffmpeg (the file is incomplete).
  ~VideoProxy();
  VideoProxy(const VideoProxy&) = delete;
  VideoProxy& operator=(const VideoProxy&) = delete;

  /// The next frame: width · height · 4 samples, rows top first, native byte
  /// order. Throws std::runtime_error (with ffmpeg's log) when ffmpeg has stopped.
  void write(std::span<const std::byte> rgba);
  /// Ends the stream and waits for ffmpeg; throws when it failed (its log).
  void finish();
  std::uint64_t frames() const { return frames_; }

 private:
  std::string failure(const std::string& what) const;

  std::filesystem::path path_, log_;
  std::size_t frame_bytes_ = 0;
  int socket_ = -1;
  pid_t pid_ = -1;
  std::uint64_t frames_ = 0;
};

}  // namespace zenith::app::offline
