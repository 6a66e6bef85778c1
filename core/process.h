#pragma once
// Child processes: start a program with its output in a log file, wait for it
// with a deadline. Used by the local cluster launcher (apps/child_process.h),
// the cluster benchmark and the multi-process tests.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace zenith::core {

enum class LogMode { truncate, append };

/// Starts `program` with `args` (argv[1..]) and this process's environment;
/// with `log`, the child's standard output and error go to that file. Returns
/// the child's pid; throws std::runtime_error naming the program and the
/// reason when it cannot be started.
pid_t spawn_process(const std::filesystem::path& program, const std::vector<std::string>& args,
                    const std::optional<std::filesystem::path>& log = std::nullopt,
                    LogMode mode = LogMode::truncate);

/// waitpid with a deadline: the exit status (128 + signal when killed), −1 when
/// `pid` is no child of this process, nullopt when it is still running.
std::optional<int> wait_for_exit(pid_t pid, std::chrono::milliseconds timeout);

}  // namespace zenith::core
