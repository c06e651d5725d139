#include "util/memory_budget.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/input_error.h"

namespace nenrin {
namespace {

TEST(MemoryBudget, SizesParseInPowersOf1024) {
    EXPECT_EQ(parseByteSize("512"), 512u);
    EXPECT_EQ(parseByteSize("8G"), uint64_t(8) << 30);
    EXPECT_EQ(parseByteSize("8gib"), uint64_t(8) << 30);
    EXPECT_EQ(parseByteSize("1.5M"), uint64_t(3) << 19);
    EXPECT_EQ(parseByteSize("2T"), uint64_t(2) << 40);
    for (const char* bad : {"", "G", "-1G", "0", "nan", "inf", "8Q", "1e30T", "8 G x"})
        EXPECT_EQ(parseByteSize(bad), 0u) << bad;
}

TEST(MemoryBudget, TheDefaultLimitIsFourFifthsOfTheMachine) {
    setMemoryLimit(0);
    const uint64_t machine = availableMemoryBytes();
    EXPECT_GT(machine, uint64_t(1) << 26);
    EXPECT_EQ(memoryLimit(), machine / 5 * 4);
    EXPECT_NO_THROW(requireMemory(double(machine) * 0.5, "half the machine", "job"));
    try {
        requireMemory(double(machine) * 2, "twice the machine", "job");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("job: twice the machine needs about"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("80 % of this machine's"), std::string::npos);
    }
    setMemoryLimit(uint64_t(1) << 20);
    EXPECT_THROW(requireMemory(2 << 20, "two MiB", "job"), InputError);
    EXPECT_NO_THROW(requireMemory(1 << 20, "one MiB", "job"));
    EXPECT_THROW(requireMemory(std::nan(""), "NaN bytes", "job"), InputError);
    setMemoryLimit(0);
}

}  // namespace
}  // namespace nenrin
