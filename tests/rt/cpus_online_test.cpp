// The kernel's CPU lists and the check of [rt] cpu against the CPUs online.
#include "rt/cpus_online.hpp"

#include <gtest/gtest.h>

namespace stepmod::rt {
namespace {

TEST(CpusOnline, ParsesTheKernelsLists) {
  EXPECT_EQ(*parse_cpu_list("0-3\n"), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(*parse_cpu_list("0,2-3"), (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(*parse_cpu_list("0"), (std::vector<int>{0}));
  EXPECT_FALSE(parse_cpu_list(""));
  EXPECT_FALSE(parse_cpu_list("3-1"));
  EXPECT_FALSE(parse_cpu_list("0-x"));
}

TEST(CpusOnline, ACpuTheBoardHasNotIsAProblemNamingTheOnesThereAre) {
  const std::vector<int> two{0, 1};
  EXPECT_EQ(rt_cpu_problem(-1, two), "");
  EXPECT_EQ(rt_cpu_problem(1, two), "");
  const std::string p = rt_cpu_problem(5, two);
  EXPECT_NE(p.find("CPU 5 is not online"), std::string::npos) << p;
  EXPECT_NE(p.find("CPUs 0, 1"), std::string::npos) << p;
}

TEST(CpusOnline, ThisMachineHasCpuZeroOnline) {
  const auto online = cpus_online();
  ASSERT_TRUE(online);
  EXPECT_EQ(rt_cpu_problem(0, *online), "");
  EXPECT_FALSE(cpus_online("/nonexistent/online"));
}

}  // namespace
}  // namespace stepmod::rt
