#pragma once
// The heap on transparent huge pages. A start is mostly first touches of
// fresh memory: table sets read from the cache, their copies per wavelength
// group, the driver's textures (llvmpipe zeroes every one it makes), the
// albedo array — hundreds of MiB, a page fault per 4 KiB page. The kernel
// backs memory with 2 MiB pages where the process asks for it
// (/sys/kernel/mm/transparent_hugepage/enabled = "madvise", Debian's default),
// and glibc's malloc asks for its own mappings with the tunable
// glibc.malloc.hugetlb=1 — read only when a program starts, from
// GLIBC_TUNABLES. So the zenith program, at its very start, sets it and
// executes itself again (the same process: pid, descriptors, signals kept).
// Measured on the project's 2-core VM, the three-worlds dome's warm start
// 2.2 → 1.0 s and frames no slower (docs/shows.md, "Where the start goes").
//
// A GLIBC_TUNABLES that names glibc.malloc.hugetlb is the user's choice and
// kept (glibc.malloc.hugetlb=0: the kernel's default pages).
#include <optional>
#include <string>
#include <string_view>

namespace zenith::core {

/// The mode of a transparent_hugepage/enabled file ("always [madvise] never"
/// → "madvise"): the word in brackets; empty when there is none.
std::string transparent_huge_page_mode(std::string_view enabled_file);

/// GLIBC_TUNABLES with glibc.malloc.hugetlb=1 added to `current` (null: unset),
/// or nullopt where `current` names glibc.malloc.hugetlb already.
std::optional<std::string> tunables_with_huge_page_heap(const char* current);

/// Where the kernel's mode is "madvise" and GLIBC_TUNABLES leaves the heap's
/// pages to glibc's default: sets the tunable and executes /proc/self/exe with
/// `argv` (does not return). Otherwise, or where the exec fails, returns and
/// the program goes on as it is.
void restart_with_huge_page_heap(char** argv);

}  // namespace zenith::core
