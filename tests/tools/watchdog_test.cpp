// The systemd watchdog policy: pet once per interval, and only while the pulse thread loops.
#include <gtest/gtest.h>

#include "systemd/watchdog.hpp"

namespace stepmod::systemd {
namespace {

constexpr Nanos kS = 1'000'000'000;

TEST(WatchdogPolicy, OffNeverPets) {
  WatchdogPolicy p(0);
  EXPECT_FALSE(p.due(0, 0));
  EXPECT_FALSE(p.due(100 * kS, 5));
}

TEST(WatchdogPolicy, PetsOncePerIntervalWhileThePulseThreadLoops) {
  WatchdogPolicy p(2 * kS);
  EXPECT_TRUE(p.due(10 * kS, 1));    // first scan
  EXPECT_FALSE(p.due(11 * kS, 50));  // too early
  EXPECT_TRUE(p.due(12 * kS, 60));   // interval passed, pulse thread looped
  EXPECT_FALSE(p.due(12 * kS + 1, 61));
  EXPECT_TRUE(p.due(14 * kS + 5, 70));
}

TEST(WatchdogPolicy, AStuckPulseThreadStopsThePetting) {
  WatchdogPolicy p(2 * kS);
  EXPECT_TRUE(p.due(0, 7));
  // Scans go on, the pulse thread's loop counter does not move: no pet, ever.
  for (Nanos t = 2 * kS; t < 20 * kS; t += kS / 1000 * 100) EXPECT_FALSE(p.due(t, 7)) << t;
  // It loops again: petting resumes at once.
  EXPECT_TRUE(p.due(20 * kS, 8));
}

TEST(WatchdogPolicy, AStuckScanStopsThePettingByItself) {
  // The control thread is the caller: a scan that never comes is a pet that never happens. After
  // a gap the next scan pets (the service was not yet killed, so it is alive again).
  WatchdogPolicy p(2 * kS);
  EXPECT_TRUE(p.due(0, 1));
  EXPECT_TRUE(p.due(30 * kS, 2));
}

}  // namespace
}  // namespace stepmod::systemd
