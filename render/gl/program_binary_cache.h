#pragma once
// Linked programs kept on disk between runs (ARB_get_program_binary, core in
// GL 4.1): after a program links, glGetProgramBinary writes its binary to a
// file; the next run gives that file to glProgramBinary instead of compiling
// and linking. On NVIDIA a precompute is bound by compiling its programs
// (docs/gpu-precompute.md, "Speed": 0.3–1.5 s each, cold, on an H200), so a
// warm run skips nearly all of its time.
//
// A program's key is the SHA-256 of the driver (GL_VENDOR, GL_RENDERER,
// GL_VERSION, GL_SHADING_LANGUAGE_VERSION) and of every stage's final text (what
// glShaderSource gets: includes expanded, #defines injected), so a new driver
// or a changed shader never meets an old binary. A driver may still refuse a
// binary (an update that keeps its version string, a changed GPU): then the
// file is removed and the program compiled as if it were not there. A driver
// with no binary format (GL_NUM_PROGRAM_BINARY_FORMATS = 0) disables the cache.
//
// Files: <directory>/<key>.bin, written to a temporary name and renamed, so a
// reader sees a whole file or none; several processes may share a directory,
// and several threads one cache (each with a context of its own).
#include <filesystem>
#include <mutex>
#include <span>
#include <string>

namespace zenith::render::gl {

class ProgramBinaryCache {
 public:
  /// A cache in `directory` (created on the first store) for the current
  /// context's driver. Needs a current GL context.
  explicit ProgramBinaryCache(std::filesystem::path directory);

  /// Whether the driver offers a binary format (Mesa llvmpipe 22.3: yes, when
  /// its shader disk cache is on; NVIDIA: yes).
  bool enabled() const { return formats_ > 0; }
  const std::filesystem::path& directory() const { return directory_; }

  /// The key of a program made of these stages' final texts.
  std::string key(std::span<const std::string> stage_texts) const;
  /// A linked program from the binary stored under `key`, or 0 when there is
  /// none, it cannot be read or the driver refuses it (then the file is removed).
  /// start_load and finish_load at once.
  unsigned load(const std::string& key);
  /// The binary stored under `key` given to glProgramBinary, without asking
  /// whether the driver took it (a driver may load it on its compiler
  /// threads, GL_KHR_parallel_shader_compile); 0 when there is no usable file.
  unsigned start_load(const std::string& key);
  /// Whether the driver took the binary of `program` (from start_load(key)):
  /// false when it refused it; then the program is deleted and the file removed.
  bool finish_load(const std::string& key, unsigned program);
  /// Stores the binary of the linked `program` under `key`. A failure (a full
  /// disk, a read-only folder) is logged once and otherwise ignored.
  void store(const std::string& key, unsigned program);

  struct Statistics {
    int loaded = 0;   ///< programs made from a stored binary
    int refused = 0;  ///< stored binaries the driver refused (compiled instead)
    int stored = 0;   ///< binaries written
  };
  Statistics statistics() const {
    std::lock_guard lock(mutex_);
    return statistics_;
  }

 private:
  /// A refused binary: `program` (0: none) deleted, the file removed, counted.
  void refuse(const std::string& key, unsigned program);

  std::filesystem::path directory_;
  std::string driver_;
  int formats_ = 0;
  mutable std::mutex mutex_;  // guards warned_ and statistics_
  bool warned_ = false;
  Statistics statistics_;
};

}  // namespace zenith::render::gl
