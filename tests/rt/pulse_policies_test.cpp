// The pulse loop's named policies (rt/adaptive_spin.hpp, rt/off_cpu_budget.hpp,
// rt/sleep_plan.hpp) on their own, with made-up clocks.
#include <gtest/gtest.h>

#include "rt/adaptive_spin.hpp"
#include "rt/off_cpu_budget.hpp"
#include "rt/sleep_plan.hpp"

namespace stepmod::rt {
namespace {

constexpr Nanos kUs = kNsPerUs;

TEST(AdaptiveSpin, StartsAtTheMaximumAndFollowsTheP99PlusMargin) {
  AdaptiveSpin spin(10 * kUs, 100 * kUs);
  EXPECT_TRUE(spin.adapts());
  EXPECT_EQ(spin.spin(), 100 * kUs);
  for (unsigned i = 1; i < AdaptiveSpin::kRecompute; ++i) EXPECT_FALSE(spin.add(30 * kUs));
  EXPECT_EQ(spin.spin(), 100 * kUs);  // not recomputed before kRecompute wake-ups
  EXPECT_TRUE(spin.add(30 * kUs));
  EXPECT_EQ(spin.p99(), 31 * kUs);
  EXPECT_EQ(spin.spin(), 31 * kUs + AdaptiveSpin::kMargin);
}

TEST(AdaptiveSpin, StaysWithinItsBounds) {
  AdaptiveSpin spin(10 * kUs, 50 * kUs);
  for (unsigned i = 0; i < AdaptiveSpin::kRecompute; ++i) spin.add(0);
  EXPECT_EQ(spin.spin(), 10 * kUs);
  for (unsigned i = 0; i < WakeLatencyWindow::kWindow; ++i) spin.add(400 * kUs);
  EXPECT_EQ(spin.spin(), 50 * kUs);
  EXPECT_FALSE(AdaptiveSpin(20 * kUs, 20 * kUs).adapts());
}

TEST(OffCpuBudget, DebtCapsTheSpinUntilPaidBack) {
  // 70 per mille off: 18.6 ms of CPU allowed per 20 ms window.
  OffCpuBudget budget(70, 10 * kUs, 100 * kUs, 0, 0);
  EXPECT_EQ(budget.spin_cap(), 100 * kUs);
  EXPECT_FALSE(budget.window_over(OffCpuBudget::kWindow - 1));
  ASSERT_TRUE(budget.window_over(OffCpuBudget::kWindow));
  budget.close_window(OffCpuBudget::kWindow, OffCpuBudget::kWindow);  // on the CPU all along
  EXPECT_EQ(budget.debt(), 1400 * kUs);
  EXPECT_EQ(budget.spin_cap(), 10 * kUs);
  // The next window: 18 ms of CPU, 0.6 ms under the share; not yet paid back.
  budget.close_window(2 * OffCpuBudget::kWindow, OffCpuBudget::kWindow + 18 * kNsPerMs);
  EXPECT_EQ(budget.debt(), 800 * kUs);
  EXPECT_EQ(budget.spin_cap(), 10 * kUs);
  // An idle window pays it back.
  budget.close_window(3 * OffCpuBudget::kWindow, OffCpuBudget::kWindow + 18 * kNsPerMs);
  EXPECT_LT(budget.debt(), 0);
  EXPECT_EQ(budget.spin_cap(), 100 * kUs);
}

TEST(OffCpuBudget, DebtIsBoundedAndZeroPermilleIsOff) {
  OffCpuBudget budget(70, 10 * kUs, 100 * kUs, 0, 0);
  Nanos t = 0;
  for (int i = 0; i < 1000; ++i) {
    t += OffCpuBudget::kWindow;
    budget.close_window(t, t);
  }
  EXPECT_EQ(budget.debt(), OffCpuBudget::kMaxDebt);
  const OffCpuBudget off(0, 10 * kUs, 100 * kUs, 0, 0);
  EXPECT_FALSE(off.window_over(1000 * OffCpuBudget::kWindow));
  EXPECT_EQ(off.spin_cap(), 100 * kUs);
}

TEST(DoorbellWindow, ARingKeepsThePollOnForAwakeNs) {
  DoorbellWindow bell(7, 20 * kNsPerMs);
  EXPECT_FALSE(bell.awake(0));
  bell.see(7, 1000);  // no ring since
  EXPECT_FALSE(bell.awake(1000));
  bell.see(8, 1000);
  EXPECT_EQ(bell.bell(), 8u);
  EXPECT_TRUE(bell.awake(1000 + 20 * kNsPerMs - 1));
  EXPECT_FALSE(bell.awake(1000 + 20 * kNsPerMs));
}

constexpr SleepLimits kLimits{50 * kUs, 10 * kNsPerMs};
constexpr DryRing kNotStarved{false, kNever};

TEST(PlanSleep, QuietSleepWithNothingExpected) {
  const SleepPlan p = plan_sleep(1000, kNever, 20 * kUs, false, kNotStarved, kLimits);
  EXPECT_EQ(p.wake, 1000 + 10 * kNsPerMs);
  EXPECT_FALSE(p.for_edge);
  EXPECT_FALSE(p.starved);
}

TEST(PlanSleep, PollsAfterARing) {
  const SleepPlan p = plan_sleep(1000, kNever, 20 * kUs, true, kNotStarved, kLimits);
  EXPECT_EQ(p.wake, 1000 + 50 * kUs);
}

TEST(PlanSleep, WakesTheSpinBeforeAnEdgeWithinTheSleep) {
  const Nanos edge = 1000 + 3 * kNsPerMs;
  const SleepPlan quiet = plan_sleep(1000, edge, 20 * kUs, false, kNotStarved, kLimits);
  EXPECT_EQ(quiet.wake, edge - 20 * kUs);
  EXPECT_TRUE(quiet.for_edge);
  const SleepPlan poll = plan_sleep(1000, edge, 20 * kUs, true, kNotStarved, kLimits);
  EXPECT_EQ(poll.wake, 1000 + 50 * kUs);  // the poll comes first
  EXPECT_FALSE(poll.for_edge);
}

TEST(PlanSleep, AStarvedRingPollsOnceThePlannersTimeHasCome) {
  // The planner named 2 ms: until then (less the spin) the quiet sleep ends there.
  const SleepPlan before = plan_sleep(1000, kNever, 20 * kUs, false, {true, 2 * kNsPerMs}, kLimits);
  EXPECT_EQ(before.wake, 2 * kNsPerMs - 20 * kUs);
  EXPECT_FALSE(before.starved);
  const SleepPlan after =
      plan_sleep(2 * kNsPerMs, kNever, 20 * kUs, false, {true, 2 * kNsPerMs}, kLimits);
  EXPECT_EQ(after.wake, 2 * kNsPerMs + 50 * kUs);
  EXPECT_TRUE(after.starved);
  // Starved with no time named: the quiet sleep.
  const SleepPlan unnamed = plan_sleep(1000, kNever, 20 * kUs, false, {true, kNever}, kLimits);
  EXPECT_EQ(unnamed.wake, 1000 + 10 * kNsPerMs);
  EXPECT_FALSE(unnamed.starved);
}

}  // namespace
}  // namespace stepmod::rt
