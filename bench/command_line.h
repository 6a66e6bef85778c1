#pragma once
// The benchmarks' own small command lines (`--option value`, comma lists),
// read the same way by each: cluster_bench, cluster_soak, series_tail_bench.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace zenith::bench {

/// The arguments after the program's name, one option at a time:
///   for (CommandLine args(argc, argv); args.next();)
///     if (args.option() == "--frames") frames = std::stoi(args.value());
class CommandLine {
 public:
  CommandLine(int argc, char** argv) : argc_(argc), argv_(argv) {}
  /// Moves to the next option; false past the last argument.
  bool next() {
    if (++i_ >= argc_) return false;
    option_ = argv_[i_];
    return true;
  }
  const std::string& option() const { return option_; }
  /// The argument after the current option; throws std::invalid_argument
  /// "<option> needs a value" when there is none.
  std::string value() {
    if (i_ + 1 >= argc_) throw std::invalid_argument(option_ + " needs a value");
    return argv_[++i_];
  }

 private:
  int argc_;
  char** argv_;
  int i_ = 0;
  std::string option_;
};

/// A benchmark's main: `run(argc, argv)`'s status, or 1 after printing
/// "<program>: <what went wrong>" and where the options are listed.
template <typename Run>
int main_reporting_errors(const char* program, int argc, char** argv, Run run) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n(%s --help lists the options)\n", program, e.what(), program);
    return 1;
  }
}

/// The last branch of an option chain: for --help or -h prints `usage` and
/// exits with status 0; any other `option` throws std::invalid_argument
/// "unknown option '<option>'".
[[noreturn]] inline void help_or_unknown_option(const std::string& option, const char* usage) {
  if (option == "--help" || option == "-h") {
    std::fputs(usage, stdout);
    std::exit(0);
  }
  throw std::invalid_argument("unknown option '" + option + "'");
}

/// "a,b,,c" → {"a", "b", "c"}.
inline std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

/// "1,2,4" → {1, 2, 4} (std::stoi: throws on a non-number).
inline std::vector<int> split_int_list(const std::string& list) {
  std::vector<int> out;
  for (const std::string& item : split_list(list)) out.push_back(std::stoi(item));
  return out;
}

}  // namespace zenith::bench
