#pragma once
// A folder of the test process's own for the files its tests write, removed
// with them when the process ends. ctest runs each test case as a process of
// its own, two at a time, so a folder shared by name between processes cannot
// be removed safely, and one left behind collects in the temporary folder run
// after run.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace zenith::testing {

/// `<temp>/zenith-tests-<pid>`, made on first use.
inline const std::filesystem::path& process_scratch_folder() {
  struct Folder {
    pid_t owner = ::getpid();
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("zenith-tests-" + std::to_string(owner));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      if (::getpid() != owner) return;  // a forked child that exits normally leaves its parent's files
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

}  // namespace zenith::testing
