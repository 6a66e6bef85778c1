#include "core/huge_page_heap.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

namespace zenith::core {

namespace {

constexpr std::string_view kTunable = "glibc.malloc.hugetlb";

}  // namespace

std::string transparent_huge_page_mode(std::string_view enabled_file) {
  const std::size_t open = enabled_file.find('['), close = enabled_file.find(']');
  if (open == std::string_view::npos || close == std::string_view::npos || close < open) return {};
  return std::string(enabled_file.substr(open + 1, close - open - 1));
}

std::optional<std::string> tunables_with_huge_page_heap(const char* current) {
  const std::string setting = std::string(kTunable) + "=1";
  if (current == nullptr || *current == '\0') return setting;
  const std::string_view tunables(current);
  if (tunables.find(kTunable) != std::string_view::npos) return std::nullopt;
  return std::string(tunables) + ":" + setting;  // tunables are separated by colons
}

void restart_with_huge_page_heap(char** argv) {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string enabled((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  // "always" backs the heap with huge pages already; "never" would not for any asking.
  if (transparent_huge_page_mode(enabled) != "madvise") return;
  const std::optional<std::string> tunables = tunables_with_huge_page_heap(std::getenv("GLIBC_TUNABLES"));
  if (!tunables || ::setenv("GLIBC_TUNABLES", tunables->c_str(), 1) != 0) return;
  ::execv("/proc/self/exe", argv);  // returns only where it failed: go on with the heap as it is
}

}  // namespace zenith::core
