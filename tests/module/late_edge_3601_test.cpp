// The late-edge guard (issue 12) seen from the PLC, in virtual time: a pulse thread stalled for
// longer than [rt] late_limit_us in the middle of a move must not burst the missed steps out; the
// axis stops as on an Immediate Stop (Stopped, Position Invalid) and the count stays what was
// really written.
#include <algorithm>

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

TEST_F(LateEdge3601, StallWithinTheLimitCatchesUpAndCompletes) {
  command(cmd::kRelativeMove, {.target = 20'000, .speed = 20'000, .accel = 100, .decel = 100});
  vm_.run_for(300 * kNsPerMs);
  const std::size_t before = vm_.step_times(0).size();
  vm_.stall_pulse_thread(vm_.now(), 600 * kNsPerUs);  // below the 1 ms default
  ASSERT_TRUE(wait_idle(5 * kNsPerSec));
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_EQ(motor(), 20'000);
  EXPECT_EQ(vm_.stack().motion(0).late_fault().count, 0u);
  // The missed steps were caught up (allowed within the limit): some gaps right after the stall
  // are shorter than the 50 us period.
  EXPECT_LT(min_gap_from(before), 50 * kNsPerUs);
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
