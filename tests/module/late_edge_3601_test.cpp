// The late-edge guard (issues 12, 18) seen from the PLC, in virtual time: a stalled pulse thread
// never bursts the missed steps out. A pause the motor bridges slips the move; one it cannot
// (above Vs: more than lag_limit_steps; at any speed: longer than late_limit_us) stops the axis
// as an Immediate Stop does (Stopped, Position Invalid), and the count stays what was written.
#include <algorithm>

#include "rt/slip.hpp"

#include "tests/module/plc_3601.hpp"

namespace stepmod::testing {
namespace {

using namespace m::status_msw;
namespace cmd = m::cmd_msw;

class LateEdge3601 : public Plc3601 {
 protected:
  void SetUp() override {
    configure();
    command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
    ASSERT_FALSE(status(kPositionInvalid));
  }
  // Shortest gap between consecutive steps from index `from` on.
  Nanos min_gap_from(std::size_t from) const {
    const auto& t = vm_.step_times(0);
    Nanos gap = kNever;
    for (std::size_t i = std::max<std::size_t>(from, 1); i < t.size(); ++i) {
      gap = std::min(gap, t[i] - t[i - 1]);
    }
    return gap;
  }
  static constexpr Nanos kNever = std::numeric_limits<Nanos>::max();
};

TEST_F(LateEdge3601, StallBeyondTheLimitStopsTheAxisWithPositionInvalid) {
  command(cmd::kRelativeMove, {.target = 50'000, .speed = 20'000, .accel = 100, .decel = 100});
  ASSERT_TRUE(moving());
  vm_.run_for(300 * kNsPerMs);  // cruising at 20,000 steps/s
  const std::size_t before = vm_.step_times(0).size();
  ASSERT_GT(before, 1000u);
  vm_.stall_pulse_thread(vm_.now(), 200 * kNsPerMs);
  ASSERT_TRUE(wait_idle(2 * kNsPerSec));
  EXPECT_TRUE(status(kStopped));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kMoveComplete));
  // No burst: not one step came after the stall (its first late edge was the cut).
  EXPECT_EQ(vm_.step_times(0).size(), before);
  EXPECT_EQ(motor(), static_cast<std::int64_t>(before));
  EXPECT_EQ(position(), motor());
  const auto f = vm_.stack().motion(0).late_fault();
  EXPECT_EQ(f.count, 1u);
  EXPECT_EQ(f.step, motor());
  EXPECT_GT(f.late_ns, 150 * kNsPerMs);
  // The motor rests afterwards, and a new command moves it again (the PLC re-homes or presets).
  vm_.run_for(200 * kNsPerMs);
  EXPECT_EQ(motor(), static_cast<std::int64_t>(before));
  command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(kPositionInvalid));
  command(cmd::kRelativeMove, {.target = 1'000});
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_EQ(position(), 1'000);
  EXPECT_EQ(vm_.stack().motion(0).late_fault().count, 1u);
}

// Issue 18 (the revised "Late edges"): a pause the motor can bridge slips the move, it is never
// caught up. (Before, a stall within the 1 ms limit was caught up in a burst of short gaps.)
TEST_F(LateEdge3601, ShortStallAboveVsSlipsTheMoveAndCompletesWithoutABurst) {
  command(cmd::kRelativeMove, {.target = 20'000, .speed = 20'000, .accel = 100, .decel = 100});
  vm_.run_for(300 * kNsPerMs);  // cruising: 50 us per step
  const std::size_t before = vm_.step_times(0).size();
  // 300 us = 6 steps of lag: within the default lag_limit_steps (8).
  vm_.stall_pulse_thread(vm_.now(), 300 * kNsPerUs);
  ASSERT_TRUE(wait_idle(5 * kNsPerSec));
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_EQ(motor(), 20'000);
  EXPECT_EQ(position(), 20'000);
  EXPECT_EQ(vm_.stack().motion(0).late_fault().count, 0u);
  // Never squeezed: no gap after the stall is shorter than the cruise period (less the write
  // allowance, rt::kSlipFreeNs).
  EXPECT_GE(min_gap_from(before), 50 * kNsPerUs - rt::kSlipFreeNs);
  // The rest of the move came later by the stall: Move Complete at the slipped end.
  EXPECT_GE(vm_.stack().motion(0).slip_ns(), 250 * kNsPerUs);
}

TEST_F(LateEdge3601, StallAboveVsBeyondTheLagLimitStopsTheAxis) {
  command(cmd::kRelativeMove, {.target = 20'000, .speed = 20'000, .accel = 100, .decel = 100});
  vm_.run_for(300 * kNsPerMs);
  const std::size_t before = vm_.step_times(0).size();
  vm_.stall_pulse_thread(vm_.now(), 600 * kNsPerUs);  // 12 steps at 20,000 steps/s: > 8
  ASSERT_TRUE(wait_idle(2 * kNsPerSec));
  EXPECT_TRUE(status(kStopped));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_EQ(vm_.step_times(0).size(), before);  // the step after the pause was the cut
  const auto f = vm_.stack().motion(0).late_fault();
  EXPECT_EQ(f.count, 1u);
  EXPECT_GE(f.lag, 9);
  EXPECT_EQ(f.interval_ns, 50 * kNsPerUs);
}

// At the starting speed a pause is harmless (the motor starts and stops there without a ramp):
// a 50 ms pause (the fair server's longest on a 6.12+ kernel) slips the move, never faults it.
TEST_F(LateEdge3601, LongStallAtTheStartingSpeedSlipsAndNeverFaultsOnLag) {
  // Vs = 1,000 steps/s (configure()); vp <= vs: the whole move runs at the starting speed.
  command(cmd::kRelativeMove, {.target = 500, .speed = 1'000, .accel = 100, .decel = 100});
  vm_.run_for(100 * kNsPerMs);
  const std::size_t before = vm_.step_times(0).size();
  vm_.stall_pulse_thread(vm_.now(), 50 * kNsPerMs);
  ASSERT_TRUE(wait_idle(5 * kNsPerSec));
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_EQ(motor(), 500);
  EXPECT_EQ(vm_.stack().motion(0).late_fault().count, 0u);
  EXPECT_GE(min_gap_from(before), kNsPerMs - rt::kSlipFreeNs);
  EXPECT_GE(vm_.stack().motion(0).slip_ns(), 49 * kNsPerMs);
}

TEST_F(LateEdge3601, StallAtTheStartingSpeedBeyondTheLateLimitStopsTheAxis) {
  command(cmd::kRelativeMove, {.target = 5'000, .speed = 1'000, .accel = 100, .decel = 100});
  vm_.run_for(100 * kNsPerMs);
  vm_.stall_pulse_thread(vm_.now(), 250 * kNsPerMs);  // > [rt] late_limit_us (200 ms)
  ASSERT_TRUE(wait_idle(2 * kNsPerSec));
  EXPECT_TRUE(status(kStopped));
  EXPECT_TRUE(status(kPositionInvalid));
  const auto f = vm_.stack().motion(0).late_fault();
  EXPECT_EQ(f.count, 1u);
  EXPECT_EQ(f.lag, 0);  // at Vs: not judged by lag
  EXPECT_GT(f.late_ns, 200 * kNsPerMs);
}

TEST_F(LateEdge3601, StallDuringHomingEndsTheHomingAsAnImmediateStop) {
  command(cmd::kFindHomeCw, {.target = 0, .speed = 20'000, .accel = 100, .decel = 100});
  ASSERT_TRUE(moving());
  vm_.run_for(100 * kNsPerMs);
  vm_.stall_pulse_thread(vm_.now(), 50 * kNsPerMs);
  ASSERT_TRUE(wait_idle(2 * kNsPerSec));
  EXPECT_TRUE(status(kStopped));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kAtHome));
  const std::int64_t at = motor();
  vm_.run_for(3 * kNsPerSec);  // no homing segment resumes after its pause
  EXPECT_EQ(motor(), at);
}

// The guard can cut a homing sequence at any moment: while it searches, decelerates, pauses 2 s,
// reverses or creeps. Whatever the moment, the sequence ends (the axis reports it is not moving)
// and nothing moves afterwards: either the cut ended it as an Immediate Stop (Stopped, Position
// Invalid), or the stall fell in a pause (no edge was due) and the homing completed.
TEST_F(LateEdge3601, StallAtAnyMomentOfHomingEndsTheSequence) {
  for (const Nanos at :
       {20 * kNsPerMs, 150 * kNsPerMs, 600 * kNsPerMs, 1'200 * kNsPerMs, 2'400 * kNsPerMs,
        2'700 * kNsPerMs, 3'500 * kNsPerMs, 4'600 * kNsPerMs, 5'200 * kNsPerMs, 6'000 * kNsPerMs}) {
    SCOPED_TRACE(::testing::Message() << "stall " << at / kNsPerMs << " ms into the homing");
    command(cmd::kResetErrors);
    command(cmd::kFindHomeCw, {.target = 0, .speed = 5'000, .accel = 20, .decel = 20});
    vm_.run_for(at);
    vm_.stall_pulse_thread(vm_.now(), 50 * kNsPerMs);
    // The end of a homing: At Home, Stopped or an error (the moving bits are also clear in its
    // 2-s pauses, so they do not tell).
    ASSERT_TRUE(port_.wait_inputs(
        [](const ImageWords& in) {
          const auto s = plc::m3601::decode_status(in);
          return s.has(kAtHome) || s.has(kStopped) || s.has(kHomeInvalid) || s.has(kInputError);
        },
        std::chrono::seconds(20)))
        << "status " << status_msw();
    EXPECT_TRUE((status(kStopped) && status(kPositionInvalid)) || status(kAtHome))
        << "status " << status_msw();
    const std::int64_t rest = motor();
    vm_.run_for(3 * kNsPerSec);
    EXPECT_EQ(motor(), rest);
    EXPECT_FALSE(moving());
  }
}

}  // namespace
}  // namespace stepmod::testing
