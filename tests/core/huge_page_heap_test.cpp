// The heap on transparent huge pages (core/huge_page_heap.h): the kernel's
// mode as its file says it, and the tunable added without overriding a choice.
#include "core/huge_page_heap.h"

#include <gtest/gtest.h>

namespace zenith::core {
namespace {

TEST(HugePageHeap, TheModeIsTheWordInBrackets) {
  EXPECT_EQ(transparent_huge_page_mode("always [madvise] never\n"), "madvise");
  EXPECT_EQ(transparent_huge_page_mode("[always] madvise never\n"), "always");
  EXPECT_EQ(transparent_huge_page_mode("always madvise [never]\n"), "never");
  EXPECT_EQ(transparent_huge_page_mode(""), "");  // no such file (a kernel without THP)
  EXPECT_EQ(transparent_huge_page_mode("] madvise ["), "");
}

TEST(HugePageHeap, TheTunableIsAddedUnlessTheUserChoseIt) {
  EXPECT_EQ(tunables_with_huge_page_heap(nullptr), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_with_huge_page_heap(""), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_with_huge_page_heap("glibc.malloc.check=3"), "glibc.malloc.check=3:glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_with_huge_page_heap("glibc.malloc.hugetlb=0"), std::nullopt);
  EXPECT_EQ(tunables_with_huge_page_heap("glibc.malloc.check=3:glibc.malloc.hugetlb=2"), std::nullopt);
}

}  // namespace
}  // namespace zenith::core
