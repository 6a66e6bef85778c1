#pragma once
// Whole-file reads: the config and warp-file loaders, the offline manifest,
// the benchmarks and the tests read files through these two.
#include <cstdint>
#include <filesystem>
#include <string>

namespace zenith::core {

/// The largest input file read whole (a config, a show or a recording, a
/// warp file): 128 MiB. A show of 100 000 keys per track, or a recording of
/// an hour at 30 fps, is a few tens of MiB; past this a file is refused by
/// its size before a byte is parsed (parsed JSON takes about ten times its
/// text: 10^7 keys once took 3.5 GB before the key limit could say no).
inline constexpr std::uintmax_t kMaxInputFileBytes = 128ull * 1024 * 1024;

/// Why `path` may not be read whole, or "": it must be a regular file (not a
/// FIFO, which would block, nor a device such as /dev/zero, which never
/// ends, nor a directory) of at most `max_bytes`. A path that does not exist
/// passes (opening it reports that).
std::string unreadable_reason(const std::filesystem::path& path, std::uintmax_t max_bytes = kMaxInputFileBytes);

/// The bytes of a file. Throws std::runtime_error "<path>: cannot open
/// (<reason>)" when it cannot be read, "<path>: is a directory" for a
/// directory, "<path>: is a FIFO (named pipe), not a regular file" and the
/// like for anything but a regular file, "<path>: N bytes, more than the
/// M-byte limit" past `max_bytes`, and "<path>: read error" when reading
/// fails midway.
std::string file_bytes(const std::filesystem::path& path, std::uintmax_t max_bytes = kMaxInputFileBytes);

/// The text of a file, or "" when it does not exist or cannot be read: for
/// logs that a test or a benchmark polls while a child process writes them.
std::string read_text(const std::filesystem::path& path);

}  // namespace zenith::core
