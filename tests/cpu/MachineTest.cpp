// What a program admits against (core/Machine.h): the memory available now, Linux's
// MemAvailable, not the machine's total; a variable stands for it in tests.
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "microrelief/core/Machine.h"

using namespace microrelief;

TEST(Machine, MemAvailableIsReadFromMeminfo) {
    const char* const meminfo =
        "MemTotal:       24683748 kB\n"
        "MemFree:        12135612 kB\n"
        "MemAvailable:   20428684 kB\n"
        "Buffers:          102400 kB\n";
    EXPECT_EQ(memAvailableBytes(meminfo), std::size_t{20428684} * 1024);
    // No such line (a kernel before 3.14), or one that does not read: nothing said.
    EXPECT_EQ(memAvailableBytes("MemTotal:       24683748 kB\nMemFree: 1 kB\n"), 0u);
    EXPECT_EQ(memAvailableBytes("MemAvailable:   lots kB\n"), 0u);
    EXPECT_EQ(memAvailableBytes("MemAvailable:   12 MB\n"), 0u);
    EXPECT_EQ(memAvailableBytes("MemAvailable:   12 kB"), 12u * 1024);  // no newline at the end
}

TEST(Machine, TheMemoryAvailableIsNoMoreThanTheMachinesAndAVariableStandsForIt) {
    {
        const test::ScopedEnvironment none(kAvailableMemoryVariable, "");
        const std::size_t available = availableMemoryBytes(), physical = physicalMemoryBytes();
        EXPECT_GT(available, 0u);
        EXPECT_LE(available, physical);
    }
    {
        const test::ScopedEnvironment given(kAvailableMemoryVariable, "20480");
        EXPECT_EQ(availableMemoryBytes(), std::size_t{20} << 30);
    }
    // What is not a positive number of MiB is not taken.
    for (const char* bad : {"0", "-5", "12x", "1e3", " 12"}) {
        const test::ScopedEnvironment given(kAvailableMemoryVariable, bad);
        EXPECT_LE(availableMemoryBytes(), physicalMemoryBytes()) << bad;
        EXPECT_GT(availableMemoryBytes(), 0u) << bad;
    }
}
