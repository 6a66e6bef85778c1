#pragma once
// Child processes: start a program with its output in a log file, wait for it
// with a deadline, find a free loopback port for it. Used by the local cluster
// launcher (cluster/launcher/child_process.h), the cluster benchmark and soak and the
// multi-process tests.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
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
                    const std::optional<std::filesystem::path>& log = std::nullopt, LogMode mode = LogMode::truncate);

/// waitpid with a deadline: the exit status (128 + signal when killed), −1 when
/// `pid` is no child of this process, nullopt when it is still running.
std::optional<int> wait_for_exit(pid_t pid, std::chrono::milliseconds timeout);

/// Whether `pid` has ended: no such process, or a zombie (a process of
/// another parent, or reparented to PID 1, that nothing reaped yet). For
/// checks that a launcher's children did not outlive it.
bool process_gone(pid_t pid);

/// Whether a child server could listen on 127.0.0.1:`port` now (a bind with
/// SO_REUSEADDR, as the cluster's master makes).
bool loopback_port_free(int port);
/// A TCP connection to 127.0.0.1:`port` (blocking): its file descriptor, or
/// −1 when no socket can be made or nobody accepts. The caller closes it.
/// For clients that play a peer byte by byte (the cluster's hostile-client
/// tests, the soak's garbage connections).
int connect_loopback(int port);
/// What the peer of `fd` sends until it closes the connection or `timeout`
/// passes (0: only what is already there); `closed` says whether it closed
/// (read returned 0 or an error). For the hostile-client tests and the soak's
/// attacks, which check that the master hangs up on them.
std::string read_until_closed(int fd, std::chrono::milliseconds timeout, bool& closed);
/// Polls `done` every 50 ms until it is true (true) or `timeout` passes
/// (false; `done` is asked once more at the deadline): for tests and
/// benchmarks that wait on a child process's files and logs.
bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout);
/// For test and benchmark clusters that share the machine with other runs:
/// the first port from `first` on, wrapping within [20000, 50000), that is
/// free together with the `span` − 1 ports after it; `first` when none is.
int free_loopback_port(int first, int span = 1);

}  // namespace zenith::core
