// The 3602's interpolated moves in motion (3602 manual ch. 3; A17, A37, A39, A46): lines and
// circles by every method to the exact end point on both axes, Move Complete on both, axis 1's
// status LSW bit 11, Hold / External / Resume along the path, and the stops that take both axes.
#include "tests/module/rig_interp_3602.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::status_msw;
namespace cmd = m2::cmd_msw;

class InterpMotion3602 : public RigInterp3602 {
 protected:
  // Both axes at a known position (absolute coordinates need valid positions).
  void home_both(std::int32_t x, std::int32_t y) {
    preset(kAxis1, x);
    preset(kAxis2, y);
  }
  // Runs the path to its end; both axes then sit exactly on (x, y) with MC on both.
  void expect_ends_at(std::int32_t x, std::int32_t y) {
    ASSERT_TRUE(wait_path_end());
    EXPECT_EQ(position(kAxis1), x);
    EXPECT_EQ(position(kAxis2), y);
    EXPECT_TRUE(status(kAxis1, kMoveComplete));  // 3602-MC-01: both axes
    EXPECT_TRUE(status(kAxis2, kMoveComplete));
    EXPECT_FALSE(ce(kAxis1));
    EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kInterpolatedRunning));
  }
  // Runs until the path is under way on both axes.
  bool wait_running() {
    return vm_.run_until_true([this] { return moving(kAxis1) && moving(kAxis2); }, 2 * kNsPerSec);
  }
  bool wait_stopped_moving() {
    return vm_.run_until_true([this] { return !moving(kAxis1) && !moving(kAxis2); },
                              10 * kNsPerSec);
  }
};

TEST_F(InterpMotion3602, MC_01_RelativeLineEndsExactlyOnBothAxes) {
  home_both(100, 200);
  path_command({.speed = 20'000, .accel = 50, .decel = 50, .end_x = 3'000, .end_y = -4'000});
  EXPECT_FALSE(ce(kAxis1));
  expect_ends_at(3'100, -3'800);
  EXPECT_EQ(motor(kAxis1), 3'000);
  EXPECT_EQ(motor(kAxis2), -4'000);
}

TEST_F(InterpMotion3602, AbsoluteLineEndsOnTheEndPoint) {
  home_both(-500, 1'000);
  path_command({.lsw = il::kLinear | il::kAbsoluteCoordinates | il::kSCurve,
                .speed = 15'000,
                .end_x = 2'500,
                .end_y = -1'000});
  expect_ends_at(2'500, -1'000);
}

TEST_F(InterpMotion3602, LineAlongOneAxisLeavesTheOtherStill) {
  path_command({.end_x = 0, .end_y = 2'345});
  ASSERT_TRUE(vm_.run_until_true([this] { return moving(kAxis2); }, kNsPerSec));
  EXPECT_FALSE(moving(kAxis1));            // no pulses on axis 1: no motion bits
  EXPECT_FALSE(status(kAxis1, kStopped));  // but the move is in progress on it
  expect_ends_at(0, 2'345);
  EXPECT_EQ(motor(kAxis1), 0);
}

// 3602-LSW-01: axis 1's LSW bit 11 while interpolating, axis 2's always 0; Axis Stopped = 0 on
// both while the path runs.
TEST_F(InterpMotion3602, LSW_01_Bit11WhileInterpolating) {
  path_command({.end_x = 4'000, .end_y = 3'000});
  ASSERT_TRUE(wait_running());
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kInterpolatedRunning));
  EXPECT_FALSE(lsw_status(kAxis2, m2::status_lsw::kInterpolatedRunning));
  EXPECT_FALSE(status(kAxis1, kStopped));
  EXPECT_FALSE(status(kAxis2, kStopped));
  EXPECT_TRUE(status(kAxis1, kMovingCw));
  EXPECT_TRUE(status(kAxis2, kMovingCw));
  EXPECT_FALSE(status(kAxis1, kMoveComplete));
  expect_ends_at(4'000, 3'000);
  EXPECT_TRUE(status(kAxis1, kStopped));
  EXPECT_TRUE(status(kAxis2, kStopped));
}

TEST_F(InterpMotion3602, CentreMethodFullCircleReturnsToTheStart) {
  home_both(0, 0);
  path_command({.lsw = il::kCcwCircular,
                .speed = 20'000,
                .end_x = 0,
                .end_y = 0,
                .point_x = 1'500,
                .point_y = 0});
  ASSERT_TRUE(wait_running());
  expect_ends_at(0, 0);
}

TEST_F(InterpMotion3602, CentreMethodQuarterCircleAbsolute) {
  home_both(1'000, 0);
  // Centre (0, 0), from (1000, 0) CCW to (0, 1000): axis 1 runs CCW, axis 2 CW.
  path_command({.lsw = il::kCcwCircular | il::kAbsoluteCoordinates,
                .speed = 5'000,
                .end_x = 0,
                .end_y = 1'000,
                .point_x = 0,
                .point_y = 0});
  ASSERT_TRUE(wait_running());
  EXPECT_TRUE(status(kAxis1, kMovingCcw));
  EXPECT_TRUE(status(kAxis2, kMovingCw));
  expect_ends_at(0, 1'000);
}

// 3602 manual ch. 3 "Rounding, accept" runs, to its end point.
TEST_F(InterpMotion3602, CentreMethodRoundingAcceptRuns) {
  home_both(-1'000, 1'531);
  path_command({.lsw = il::kCcwCircular | il::kAbsoluteCoordinates,
                .speed = 50'000,
                .accel = 100,
                .decel = 100,
                .end_x = 1'563,
                .end_y = 950});
  EXPECT_FALSE(ce(kAxis1));
  expect_ends_at(1'563, 950);
}

TEST_F(InterpMotion3602, RadiusMethodShortAndLongArcs) {
  path_command({.lsw = il::kRadiusMethod | il::kCwCircular,
                .speed = 20'000,
                .end_x = 2'000,
                .end_y = 0,
                .point_x = 2'000});
  expect_ends_at(2'000, 0);
  path_command({.lsw = il::kRadiusMethod | il::kCcwCircular,
                .speed = 20'000,
                .end_x = -2'000,
                .end_y = 1'000,
                .point_x = -1'200});
  expect_ends_at(0, 1'000);
}

TEST_F(InterpMotion3602, ViaPointArcThroughThePoint) {
  home_both(0, 0);
  path_command({.lsw = il::kViaPoint | il::kAbsoluteCoordinates,
                .speed = 20'000,
                .end_x = 2'000,
                .end_y = 0,
                .point_x = 1'000,
                .point_y = 1'000});
  // The arc passes over the top: axis 2 reaches about 1000 on the way.
  std::int64_t highest = 0;
  ASSERT_TRUE(vm_.run_until_true(
      [&] {
        highest = std::max(highest, motor(kAxis2));
        return path_idle();
      },
      10 * kNsPerSec));
  EXPECT_GE(highest, 999);
  EXPECT_LE(highest, 1'000);
  expect_ends_at(2'000, 0);
}

// 3602-HLD-01 (interpolated): Hold on axis 1 stops both along the path; Resume on axis 1
// (interpolation bits 0, the Resume block's speed: A39) continues to the exact end point.
TEST_F(InterpMotion3602, HLD_01_HoldOnAxis1ThenResumeEndsOnThePath) {
  home_both(0, 0);
  path_command({.lsw = il::kCwCircular,
                .speed = 10'000,
                .end_x = 0,
                .end_y = 0,
                .point_x = 2'000,
                .point_y = 0});
  vm_.run_for(400 * kNsPerMs);
  command(kAxis1, cmd::kHold);
  ASSERT_TRUE(wait_stopped_moving());
  vm_.scans(5);
  EXPECT_TRUE(status(kAxis1, kHoldState));
  EXPECT_FALSE(status(kAxis1, kMoveComplete));
  EXPECT_FALSE(status(kAxis2, kMoveComplete));
  EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kInterpolatedRunning));
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));
  const std::int64_t hx = motor(kAxis1), hy = motor(kAxis2);
  EXPECT_FALSE(hx == 0 && hy == 0);
  clear_words(kAxis2);
  command(kAxis1, cmd::kResume, {.target = 0, .speed = 15'000, .accel = 20, .decel = 20});
  EXPECT_FALSE(ce(kAxis1));
  EXPECT_FALSE(status(kAxis1, kHoldState));
  expect_ends_at(0, 0);
}

// The External input of either axis: a controlled stop of the path, Hold on axis 1.
TEST_F(InterpMotion3602, HLD_01_ExternalOnAxis2HoldsThePath) {
  home_both(0, 0);
  path_command({.end_x = 20'000, .end_y = 10'000});
  vm_.run_for(500 * kNsPerMs);
  force(kAxis2, InputLine::kExternal, true);
  ASSERT_TRUE(wait_stopped_moving());
  vm_.scans(5);
  EXPECT_TRUE(status(kAxis1, kHoldState));
  EXPECT_LT(motor(kAxis1), 20'000);
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));
  EXPECT_FALSE(status(kAxis2, kPositionInvalid));
  // Still on the line: y = x / 2 within a step.
  EXPECT_LE(std::llabs(2 * motor(kAxis2) - motor(kAxis1)), 2);
  force(kAxis2, InputLine::kExternal, false);
  clear_words(kAxis2);
  command(kAxis1, cmd::kResume, {.target = 0, .speed = 10'000});
  expect_ends_at(20'000, 10'000);
}

// A17 then Resume: the path held before its start runs from the start.
TEST_F(InterpMotion3602, HLD_01_HeldAtTheStartResumeRunsThePath) {
  force(kAxis1, InputLine::kExternal, true);
  path_command({.end_x = -1'500, .end_y = 2'500});
  ASSERT_TRUE(status(kAxis1, kHoldState));
  force(kAxis1, InputLine::kExternal, false);
  clear_words(kAxis2);
  command(kAxis1, cmd::kResume, {.target = 0, .speed = 10'000});
  expect_ends_at(-1'500, 2'500);
}

TEST_F(InterpMotion3602, CE_09_ResumeWithInterpolationBitsIsRefused) {
  path_command({.end_x = 20'000, .end_y = 10'000});
  vm_.run_for(300 * kNsPerMs);
  command(kAxis1, cmd::kHold);
  ASSERT_TRUE(wait_stopped_moving());
  vm_.scans(5);
  clear_words(kAxis2);
  command(kAxis1, cmd::kResume, {.target = 0, .speed = 10'000, .lsw = il::kLinear});
  EXPECT_TRUE(ce(kAxis1));  // 3602-CE-03
  vm_.scans(20);
  EXPECT_FALSE(moving(kAxis1));
  EXPECT_TRUE(status(kAxis1, kHoldState));
}

// 3602-PI-07: Immediate Stop on axis 1 stops both axes at once, both positions invalid.
TEST_F(InterpMotion3602, PI_07_ImmediateStopOnAxis1StopsBoth) {
  home_both(0, 0);
  path_command({.end_x = 20'000, .end_y = -20'000});
  ASSERT_TRUE(wait_running());
  vm_.run_for(200 * kNsPerMs);
  clear_words(kAxis2);
  command(kAxis1, cmd::kImmediateStop);
  ASSERT_TRUE(vm_.run_until_true([this] { return path_idle(); }, 20 * kNsPerMs));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_TRUE(status(kAxis2, kPositionInvalid));
  EXPECT_FALSE(status(kAxis1, kMoveComplete));
  EXPECT_FALSE(status(kAxis2, kMoveComplete));
  const std::int64_t x = motor(kAxis1), y = motor(kAxis2);
  EXPECT_LT(x, 20'000);
  vm_.scans(50);
  EXPECT_EQ(motor(kAxis1), x);
  EXPECT_EQ(motor(kAxis2), y);
}

// 3602-CE-I2: Immediate Stop on axis 2 does not stop the path; CE on axis 1.
TEST_F(InterpMotion3602, CE_I2_ImmediateStopOnAxis2DoesNotStopThePath) {
  home_both(0, 0);
  path_command({.end_x = 8'000, .end_y = 6'000});
  ASSERT_TRUE(wait_running());
  clear_words(kAxis2);
  command(kAxis2, cmd::kImmediateStop);
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_FALSE(ce(kAxis2));
  EXPECT_TRUE(moving(kAxis2));
  ASSERT_TRUE(wait_path_end());
  EXPECT_EQ(motor(kAxis1), 8'000);
  EXPECT_EQ(motor(kAxis2), 6'000);
  EXPECT_TRUE(status(kAxis2, kMoveComplete));
  EXPECT_FALSE(status(kAxis2, kPositionInvalid));
}

// A46: any other axis-2 command during the path is refused, CE on axis 1; once released it does
// not fire after the path.
TEST_F(InterpMotion3602, CE_I1_Axis2CommandDuringThePathIsRefusedOnAxis1) {
  path_command({.end_x = 8'000, .end_y = 6'000});
  ASSERT_TRUE(wait_running());
  clear_words(kAxis2);
  set_command(kAxis2, cmd::kRelativeMove, {.target = 500});
  vm_.scans(3);
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_FALSE(ce(kAxis2));
  ASSERT_TRUE(wait_path_end());
  vm_.scans(5);
  word(kAxis2, m2::out_word::kMsw) = 0;
  vm_.scans(5);
  EXPECT_EQ(motor(kAxis1), 8'000);
  EXPECT_EQ(motor(kAxis2), 6'000);
}

// 3602-PI-04 / IE-02: a limit on either axis during the path stops both at once; both positions
// invalid, Input Error on the axis whose limit tripped.
TEST_F(InterpMotion3602, PI_04_IE_02_LimitOnAxis2StopsBothAxes) {
  path_command({.end_x = 20'000, .end_y = 20'000});
  ASSERT_TRUE(wait_running());
  vm_.run_for(200 * kNsPerMs);
  force(kAxis2, InputLine::kCcwLimit, true);  // either limit stops a path (3602 manual ch. 2)
  ASSERT_TRUE(vm_.run_until_true([this] { return path_idle(); }, 20 * kNsPerMs));
  EXPECT_TRUE(status(kAxis2, kInputError));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_TRUE(status(kAxis2, kPositionInvalid));
  EXPECT_FALSE(status(kAxis1, kMoveComplete));
  EXPECT_LT(motor(kAxis1), 20'000);
  const std::int64_t x = motor(kAxis1);
  vm_.scans(50);
  EXPECT_EQ(motor(kAxis1), x);
}

TEST_F(InterpMotion3602, IE_02_CwLimitOnAxis1StopsBothAxes) {
  path_command({.end_x = 20'000, .end_y = 20'000});
  ASSERT_TRUE(wait_running());
  force(kAxis1, InputLine::kCwLimit, true);
  ASSERT_TRUE(vm_.run_until_true([this] { return path_idle(); }, 20 * kNsPerMs));
  EXPECT_TRUE(status(kAxis1, kInputError));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_TRUE(status(kAxis2, kPositionInvalid));
}

// 3602 manual ch. 2: an E-stop on either axis cuts the path on both (3602-IE-01, PI-03).
TEST_F(InterpMotion3602, IE_01_EStopOnAxis2StopsBothAxes) {
  configure(kAxis2, static_cast<std::uint16_t>(
                        (kLimitsConfigMsw & ~m2::cfg_msw::kCwFunction) |
                        (m2::cfg_msw::kFunctionEStop << m2::cfg_msw::kCwFunctionShift)));
  home_both(0, 0);
  path_command({.end_x = 20'000, .end_y = -20'000});
  ASSERT_TRUE(wait_running());
  force(kAxis2, InputLine::kCwLimit, true);  // axis 2 runs CCW: an E-stop stops it all the same
  ASSERT_TRUE(vm_.run_until_true([this] { return path_idle(); }, 20 * kNsPerMs));
  EXPECT_TRUE(status(kAxis2, kInputError));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_TRUE(status(kAxis2, kPositionInvalid));
  EXPECT_LT(motor(kAxis1), 20'000);
}

// A46: Hold given to axis 2 does not hold the path; CE on axis 1.
TEST_F(InterpMotion3602, CE_I1_HoldOnAxis2IsRefusedThePathRunsOn) {
  path_command({.end_x = 8'000, .end_y = 6'000});
  ASSERT_TRUE(wait_running());
  clear_words(kAxis2);
  command(kAxis2, cmd::kHold);
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_FALSE(ce(kAxis2));
  ASSERT_TRUE(wait_path_end());
  EXPECT_EQ(motor(kAxis1), 8'000);
  EXPECT_EQ(motor(kAxis2), 6'000);
  EXPECT_FALSE(status(kAxis1, kHoldState));
}

// A path held, then axis 2 moved on its own: the path cannot continue from where it stopped.
TEST_F(InterpMotion3602, CE_09_ResumeAfterAxis2MovedIsRefused) {
  path_command({.end_x = 20'000, .end_y = 10'000});
  vm_.run_for(300 * kNsPerMs);
  command(kAxis1, cmd::kHold);
  ASSERT_TRUE(wait_stopped_moving());
  vm_.scans(5);
  ASSERT_TRUE(status(kAxis1, kHoldState));
  clear_words(kAxis2);
  command(kAxis2, cmd::kRelativeMove, {.target = 100});
  ASSERT_TRUE(wait_idle(kAxis2));
  const std::int64_t x = motor(kAxis1);
  command(kAxis1, cmd::kResume, {.target = 0, .speed = 10'000});
  EXPECT_TRUE(ce(kAxis1));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), x);
}

// 3602-CE-01 on a path: configuration mode requested on axis 1 while the path runs -> CE, the
// path finishes on both axes, then axis 1 enters configuration mode and CE clears.
TEST_F(InterpMotion3602, CE_01_ConfigurationRequestDuringThePathFinishesIt) {
  path_command({.end_x = 6'000, .end_y = 3'000});
  ASSERT_TRUE(wait_running());
  write_config(kAxis1, kLimitsConfigMsw);  // axis 1's words only; axis 2's stay
  vm_.scans(3);
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_TRUE(moving(kAxis1));
  ASSERT_TRUE(vm_.run_until_true([this] { return status(kAxis1, kConfigMode); }, 10 * kNsPerSec));
  EXPECT_EQ(motor(kAxis1), 6'000);
  EXPECT_EQ(motor(kAxis2), 3'000);
  EXPECT_FALSE(ce(kAxis1));
  EXPECT_TRUE(status(kAxis2, kMoveComplete));
}

TEST_F(InterpMotion3602, CE_04_SecondInterpolatedMoveWhileRunning) {
  path_command({.end_x = 8'000, .end_y = 6'000});
  ASSERT_TRUE(wait_running());
  path_command({.end_x = 100, .end_y = 100});
  EXPECT_TRUE(ce(kAxis1));
  ASSERT_TRUE(wait_path_end());
  EXPECT_EQ(motor(kAxis1), 8'000);
  EXPECT_EQ(motor(kAxis2), 6'000);
}

}  // namespace
}  // namespace stepmod::testing
