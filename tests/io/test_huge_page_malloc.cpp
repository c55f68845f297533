// io/HugePageMalloc.h: when the process asks glibc for huge pages, and that it keeps the user's say.
#include "io/HugePageMalloc.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace jawmesh {
namespace {

TEST(HugePageMalloc, ReadsTheKernelsActiveMode) {
    EXPECT_EQ(activeHugePageMode("always [madvise] never\n"), "madvise");
    EXPECT_EQ(activeHugePageMode("[always] madvise never\n"), "always");
    EXPECT_EQ(activeHugePageMode("always madvise [never]"), "never");
    EXPECT_EQ(activeHugePageMode(""), "");
    EXPECT_EQ(activeHugePageMode("always madvise never"), "");
}

TEST(HugePageMalloc, AsksOnlyWhereTheKernelWaitsToBeAsked) {
    EXPECT_EQ(tunablesForHugePages("madvise", nullptr), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(tunablesForHugePages("madvise", ""), "glibc.malloc.hugetlb=1");
    EXPECT_FALSE(tunablesForHugePages("always", nullptr));
    EXPECT_FALSE(tunablesForHugePages("never", nullptr));
    EXPECT_FALSE(tunablesForHugePages("", nullptr));
}

TEST(HugePageMalloc, KeepsTheUsersTunables) {
    // other tunables stay; a hugetlb setting of the user's (off included) is never overridden,
    // which is also what ends the re-execution after one step
    EXPECT_EQ(tunablesForHugePages("madvise", "glibc.malloc.arena_max=2"), "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
    EXPECT_FALSE(tunablesForHugePages("madvise", "glibc.malloc.hugetlb=0"));
    EXPECT_FALSE(tunablesForHugePages("madvise", "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1"));
    // a name that merely contains the tunable's is not it
    EXPECT_EQ(tunablesForHugePages("madvise", "xglibc.malloc.hugetlb=0"), "xglibc.malloc.hugetlb=0:glibc.malloc.hugetlb=1");
}

TEST(HugePageMalloc, ReportsWhatTheEnvironmentSays) {
    const char* saved = std::getenv("GLIBC_TUNABLES");
    const std::string keep = saved ? saved : "";
    setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 1);
    EXPECT_TRUE(mallocAdvisesHugePages());
    setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=0", 1);
    EXPECT_FALSE(mallocAdvisesHugePages());
    unsetenv("GLIBC_TUNABLES");
    EXPECT_FALSE(mallocAdvisesHugePages());
    if (saved) setenv("GLIBC_TUNABLES", keep.c_str(), 1);
}

}  // namespace
}  // namespace jawmesh
