#pragma once
// The zenith command line: every command (apps/commands.h) under one CLI11
// app, logs to stderr, errors as exit codes. apps/main.cpp is the program;
// tests/cli/zenith_with_shader_faults.cpp runs the same command line with a
// test's shader faults installed.

namespace zenith::app {

/// Parses `argv` and runs its command: 0 done, 1 an error, 2 a config error,
/// CLI11's code for a command line it refuses (with its message printed).
int run_command_line(int argc, char** argv);

}  // namespace zenith::app
