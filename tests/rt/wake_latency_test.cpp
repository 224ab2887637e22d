#include "rt/wake_latency.hpp"

#include <gtest/gtest.h>

namespace stepmod::rt {
namespace {

TEST(WakeLatencyWindow, EmptyIsZero) {
  WakeLatencyWindow w;
  EXPECT_EQ(w.percentile(990), 0);
}

TEST(WakeLatencyWindow, HighPercentileCoversTheTailNotTheMean) {
  WakeLatencyWindow w;
  // A VM's wake-ups: most ~40 us late, 3 % up to 90 us.
  for (int i = 0; i < 1000; ++i) w.add((i % 100 < 97 ? 40 : 90) * kNsPerUs + 300);
  EXPECT_EQ(w.percentile(500), 41 * kNsPerUs);
  EXPECT_EQ(w.percentile(990), 91 * kNsPerUs);
}

TEST(WakeLatencyWindow, AFewStallsDoNotMoveIt) {
  WakeLatencyWindow w;
  for (int i = 0; i < 1024; ++i) w.add(i % 256 == 0 ? 50 * kNsPerMs : 10 * kNsPerUs);
  EXPECT_EQ(w.percentile(990), 11 * kNsPerUs);   // 4 stalls in 1024 are under 1 %
  EXPECT_EQ(w.percentile(999), 512 * kNsPerUs);  // the top bucket holds them
}

TEST(WakeLatencyWindow, OldSamplesLeaveTheWindow) {
  WakeLatencyWindow w;
  for (unsigned i = 0; i < WakeLatencyWindow::kWindow; ++i) w.add(80 * kNsPerUs);
  EXPECT_EQ(w.percentile(990), 81 * kNsPerUs);
  for (unsigned i = 0; i < WakeLatencyWindow::kWindow; ++i) w.add(5 * kNsPerUs);
  EXPECT_EQ(w.size(), WakeLatencyWindow::kWindow);
  EXPECT_EQ(w.percentile(990), 6 * kNsPerUs);
}

}  // namespace
}  // namespace stepmod::rt
