// The ffmpeg review proxy (offline/video_proxy.h).
#include "offline/video_proxy.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace zenith::app::offline {

std::optional<std::filesystem::path> find_ffmpeg() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(folder) / "ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

VideoProxy::VideoProxy(const std::filesystem::path& path, int width, int height, int bits, double fps)
    : path_(path), log_(path.string() + ".log") {
  const std::optional<std::filesystem::path> ffmpeg = find_ffmpeg();
  if (!ffmpeg)
    throw std::runtime_error(fmt::format(
        "--video {}: ffmpeg is not installed (no ffmpeg on PATH); install it (scripts/bootstrap installs the Debian "
        "package ffmpeg) or drop --video",
        path.string()));
  if (bits != 8 && bits != 16) throw std::invalid_argument("--video: frames of 8 or 16 bits a sample");
  frame_bytes_ = std::size_t(width) * std::size_t(height) * 4 * std::size_t(bits / 8);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  const std::vector<std::string> args = {
      ffmpeg->string(),
      "-nostdin",
      "-hide_banner",
      "-loglevel",
      "warning",
      "-y",
      "-f",
      "rawvideo",
      "-pix_fmt",
      bits == 8 ? "rgba" : "rgba64le",
      "-video_size",
      fmt::format("{}x{}", width, height),
      "-framerate",
      fmt::format("{}", fps),
      "-i",
      "pipe:0",
      "-vf",
      fmt::format("scale=w='min({0},iw)':h='min({0},ih)':force_original_aspect_ratio=decrease:force_divisible_by=2",
                  kMaxProxyEdgePx),
      "-c:v",
      "libx264",
      "-preset",
      "veryfast",
      "-crf",
      "18",
      "-pix_fmt",
      "yuv420p",
      "-color_primaries",
      "bt709",
      "-color_trc",
      "iec61966-2-1",
      "-colorspace",
      "bt709",
      path.string()};
  // A socket rather than a pipe: a write to an ffmpeg that stopped fails with
  // EPIPE (MSG_NOSIGNAL) instead of killing this process with SIGPIPE.
  int sockets[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0)
    throw std::runtime_error(
        fmt::format("--video {}: cannot make a socket for ffmpeg: {}", path.string(), std::strerror(errno)));
  const int log = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) {
    ::close(sockets[0]);
    ::close(sockets[1]);
    throw std::runtime_error(
        fmt::format("--video {}: cannot create {}: {}", path.string(), log_.string(), std::strerror(errno)));
  }
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_ = ::fork();
  if (pid_ == 0) {
    ::dup2(sockets[1], STDIN_FILENO);
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  const int fork_errno = errno;
  ::close(sockets[1]);
  ::close(log);
  if (pid_ < 0) {
    ::close(sockets[0]);
    throw std::runtime_error(
        fmt::format("--video {}: cannot start ffmpeg: {}", path.string(), std::strerror(fork_errno)));
  }
  socket_ = sockets[0];
}

VideoProxy::~VideoProxy() {
  if (socket_ >= 0) ::close(socket_);
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

std::string VideoProxy::failure(const std::string& what) const {
  std::ifstream in(log_);
  std::stringstream text;
  text << in.rdbuf();
  std::string log = text.str();
  if (log.size() > 2000) log = "…" + log.substr(log.size() - 2000);
  return fmt::format("--video {}: {}{}", path_.string(), what, log.empty() ? "" : "; ffmpeg said:\n" + log);
}

void VideoProxy::write(std::span<const std::byte> rgba) {
  if (rgba.size() != frame_bytes_)
    throw std::invalid_argument(fmt::format("--video: a frame of {} bytes, expected {}", rgba.size(), frame_bytes_));
  if (socket_ < 0) throw std::runtime_error(failure("ffmpeg has stopped"));
  std::size_t done = 0;
  while (done < rgba.size()) {
    const ssize_t n = ::send(socket_, rgba.data() + done, rgba.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      ::close(socket_);
      socket_ = -1;
      throw std::runtime_error(failure(fmt::format("ffmpeg stopped reading frames ({})", std::strerror(error))));
    }
    done += static_cast<std::size_t>(n);
  }
  ++frames_;
}

void VideoProxy::finish() {
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
  int status = 0;
  if (pid_ > 0 && ::waitpid(pid_, &status, 0) == pid_) {
    pid_ = -1;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
      throw std::runtime_error(failure("ffmpeg could not be started"));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw std::runtime_error(failure(
          fmt::format("ffmpeg failed (status {})", WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status))));
  }
}

}  // namespace zenith::app::offline
