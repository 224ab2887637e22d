// 3602 command mode through the module's words (3602 manual ch. 9): both axes moving at once
// with exact counts, targets in the binary split, the ranges, Move Complete, Axis Stopped, the
// general-purpose output.
#include "tests/module/rig_3602.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::status_msw;
namespace cmd = m2::cmd_msw;

class Commands3602 : public Rig3602 {
 protected:
  void SetUp() override {
    configure(kAxis1);
    configure(kAxis2);
  }
};

TEST_F(Commands3602, MC_01_BothAxesAtOnceExactCounts) {
  set_command(kAxis1, cmd::kRelativeMove, {.target = 50'800, .speed = 40'000, .accel = 50});
  set_command(kAxis2, cmd::kRelativeMove, {.target = -23'456, .speed = 20'000, .accel = 50});
  vm_.scans(3);
  EXPECT_TRUE(moving(kAxis1));
  EXPECT_TRUE(moving(kAxis2));
  // 50,800 travels as 16#0000 / 16#C670.
  EXPECT_EQ(word(kAxis1, m2::out_word::kTargetMsw), 0);
  EXPECT_EQ(word(kAxis1, m2::out_word::kTargetLsw), -14'736);
  ASSERT_TRUE(wait_idle(kAxis1));
  ASSERT_TRUE(wait_idle(kAxis2));
  EXPECT_EQ(motor(kAxis1), 50'800);
  EXPECT_EQ(motor(kAxis2), -23'456);
  EXPECT_EQ(position(kAxis1), 50'800);
  EXPECT_EQ(position(kAxis2), -23'456);
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
  EXPECT_TRUE(status(kAxis2, kMoveComplete));
}

TEST_F(Commands3602, NegativeAbsoluteTargetInTheBinarySplit) {
  command(kAxis1, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  command(kAxis2, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  set_command(kAxis2, cmd::kAbsoluteMove, {.target = -70'000, .speed = 50'000, .accel = 100});
  EXPECT_EQ(word(kAxis2, m2::out_word::kTargetMsw), -2);  // 16#FFFE:EE90
  EXPECT_EQ(word(kAxis2, m2::out_word::kTargetLsw), -4'464);
  vm_.scans(3);
  ASSERT_TRUE(wait_idle(kAxis2));
  EXPECT_EQ(motor(kAxis2), -70'000);
  EXPECT_EQ(position(kAxis2), -70'000);
  EXPECT_EQ(motor(kAxis1), 0);
}

TEST_F(Commands3602, CE_05_TargetRangeIsPlusMinus1073741823) {
  // Preset accepts the range's ends and reports them back.
  command(kAxis1, cmd::kPresetPosition,
          {.target = 1'073'741'823, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(position(kAxis1), 1'073'741'823);
  EXPECT_FALSE(status(kAxis1, kCommandError));
  command(kAxis1, cmd::kPresetPosition,
          {.target = -1'073'741'823, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(position(kAxis1), -1'073'741'823);
  EXPECT_FALSE(status(kAxis1, kCommandError));
  // One beyond: Command Error, nothing moves.
  command(kAxis1, cmd::kRelativeMove, {.target = 1'073'741'824});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
  command(kAxis1, cmd::kResetErrors, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(kAxis1, kCommandError));
  command(kAxis1, cmd::kRelativeMove, {.target = -1'073'741'824});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
}

TEST_F(Commands3602, CE_05_SpeedAboveOneMillionIsRefused) {
  command(kAxis1, cmd::kRelativeMove, {.target = 100, .speed = 1'000'001});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
}

TEST_F(Commands3602, MC_02_PresetPositionClearsMoveComplete) {
  command(kAxis1, cmd::kRelativeMove, {.target = 800});
  ASSERT_TRUE(wait_idle(kAxis1));
  ASSERT_TRUE(status(kAxis1, kMoveComplete));
  command(kAxis1, cmd::kPresetPosition, {.target = -5, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(position(kAxis1), -5);
  EXPECT_FALSE(status(kAxis1, kMoveComplete));
}

TEST_F(Commands3602, STP_01_AxisStoppedWheneverIdleInCommandMode) {
  EXPECT_TRUE(status(kAxis1, kStopped));
  set_command(kAxis1, cmd::kRelativeMove, {.target = 5'000});
  vm_.scans(3);
  EXPECT_FALSE(status(kAxis1, kStopped));
  EXPECT_TRUE(status(kAxis2, kStopped));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_TRUE(status(kAxis1, kStopped));
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
}

TEST_F(Commands3602, CE_02_MoreThanOneCommandBit) {
  command(kAxis2, cmd::kRelativeMove | cmd::kAbsoluteMove, {.target = 100});
  EXPECT_TRUE(status(kAxis2, kCommandError));
  EXPECT_FALSE(status(kAxis1, kCommandError));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis2), 0);
}

// 3602 manual table 9.4 / 3602-LSW-01: command LSW bit 7 is the general-purpose output, a level at
// any time in command mode, on its own axis' line, echoed in status LSW bit 13.
TEST_F(Commands3602, LSW_01_GeneralPurposeOutputFollowsLswBit7) {
  constexpr std::uint32_t kGpoLevel = 1u << static_cast<unsigned>(OutputLine::kGpo);
  word(kAxis2, m2::out_word::kLsw) = m2::cmd_lsw::kGpo;
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(kAxis2, m2::status_lsw::kGpo));
  EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kGpo));
  EXPECT_EQ(vm_.sim().output_levels(kAxis2) & kGpoLevel, kGpoLevel);
  EXPECT_EQ(vm_.sim().output_levels(kAxis1) & kGpoLevel, 0u);
  // Kept through a move whose LSW carries it.
  command(kAxis2, cmd::kRelativeMove, {.target = 300, .lsw = m2::cmd_lsw::kGpo});
  ASSERT_TRUE(wait_idle(kAxis2));
  EXPECT_EQ(motor(kAxis2), 300);
  EXPECT_TRUE(lsw_status(kAxis2, m2::status_lsw::kGpo));
  word(kAxis2, m2::out_word::kLsw) = 0;
  vm_.scans(2);
  EXPECT_FALSE(lsw_status(kAxis2, m2::status_lsw::kGpo));
  EXPECT_EQ(vm_.sim().output_levels(kAxis2) & kGpoLevel, 0u);
}

TEST_F(Commands3602, LSW_01_ProximityEchoIsCommandLswBit6) {
  word(kAxis1, m2::out_word::kLsw) = m2::cmd_lsw::kBackplaneProximity;
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kProximityEcho));
  EXPECT_FALSE(lsw_status(kAxis2, m2::status_lsw::kProximityEcho));
}

// 3602-IE-01 / PI-03 on one axis: axis 1's CW input configured as an E-stop stops axis 1 only;
// axis 2 runs on to its exact count.
TEST_F(Commands3602, IE_01_PI_03_CwInputAsEStopStopsItsAxisOnly) {
  const auto estop_cw =
      static_cast<std::uint16_t>((kLimitsConfigMsw & ~m2::cfg_msw::kCwFunction) |
                                 m2::cfg_msw::kFunctionEStop << m2::cfg_msw::kCwFunctionShift);
  configure(kAxis1, estop_cw);
  set_command(kAxis1, cmd::kRelativeMove, {.target = -60'000});
  set_command(kAxis2, cmd::kRelativeMove, {.target = 20'000});
  vm_.scans(3);
  word(kAxis1, m2::out_word::kMsw) = 0;
  word(kAxis2, m2::out_word::kMsw) = 0;
  vm_.run_for(300 * kNsPerMs);
  // Panel: axis 1's CW input line high (active high).
  vm_.sim().force(kAxis1, 1u << static_cast<unsigned>(InputLine::kCwLimit),
                  1u << static_cast<unsigned>(InputLine::kCwLimit), vm_.now());
  vm_.scans(3);
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_TRUE(status(kAxis1, kInputError));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kCwActive));
  EXPECT_GT(motor(kAxis1), -60'000);
  EXPECT_TRUE(moving(kAxis2));
  ASSERT_TRUE(wait_idle(kAxis2));
  EXPECT_EQ(motor(kAxis2), 20'000);
  EXPECT_FALSE(status(kAxis2, kInputError));
  EXPECT_TRUE(status(kAxis2, kMoveComplete));
}

// 3602-IP-03 "Profile overflows internal registers" (A32): IP + CE when the planned step count or
// the position at the end of a move does not fit a signed 32-bit register. Targets and presets
// stay inside +-1,073,741,823 (2^30 - 1), but relative moves take the position beyond that box.
// First the step count: two steps out of the box at the top, an absolute move to the bottom is
// 2^31 steps away, one more than a 32-bit count holds; one step less is accepted.
TEST_F(Commands3602, IP_03_AbsoluteMoveFromOutsideTheBoxOverflowsTheStepCount) {
  constexpr std::int32_t kMax = 1'073'741'823;
  command(kAxis1, cmd::kPresetPosition, {.target = kMax, .speed = 0, .accel = 0, .decel = 0});
  command(kAxis1, cmd::kRelativeMove, {.target = 2});
  ASSERT_TRUE(wait_idle(kAxis1));
  ASSERT_EQ(position(kAxis1), kMax + 2);
  command(kAxis1, cmd::kAbsoluteMove, {.target = -kMax, .speed = 1'000'000, .accel = 2000});
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  EXPECT_TRUE(status(kAxis1, kCommandError));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_FALSE(moving(kAxis1));
  EXPECT_EQ(motor(kAxis1), 2);
  EXPECT_EQ(position(kAxis1), kMax + 2);
  // 2^31 - 1 steps: planned, runs.
  command(kAxis1, cmd::kResetErrors, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  command(kAxis1, cmd::kAbsoluteMove, {.target = -kMax + 1, .speed = 1'000'000, .accel = 2000});
  EXPECT_FALSE(status(kAxis1, kInvalidProfile));
  EXPECT_FALSE(status(kAxis1, kCommandError));
  EXPECT_TRUE(moving(kAxis1));
  command(kAxis1, cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_LT(motor(kAxis1), 2);
}

// Then the position at the end: from the top of the preset range one move of the largest target
// ends at 2^31 - 2, which fits; moves that would end past 2^31 - 1 do not.
TEST_F(Commands3602, IP_03_MoveEndingPast32BitsOverflowsThePosition) {
  constexpr std::int32_t kMax = 1'073'741'823;
  const Move3602 fast{.target = kMax, .speed = 1'000'000, .accel = 2000, .decel = 2000};
  command(kAxis1, cmd::kPresetPosition, {.target = kMax, .speed = 0, .accel = 0, .decel = 0});
  command(kAxis1, cmd::kRelativeMove, fast);  // ends at 2^31 - 2: accepted
  EXPECT_TRUE(moving(kAxis1));
  EXPECT_FALSE(status(kAxis1, kInvalidProfile));
  EXPECT_FALSE(status(kAxis1, kCommandError));
  command(kAxis1, cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(kAxis1));

  // That move takes 2^30 steps (18 min at 1 MHz, too long for a test even in virtual time). The
  // rig's seam (VirtualMachine::set_step_count) puts the axis where it would have ended: preset
  // again at the top of the range, then the step count advanced by the move's 2^30 - 1 steps.
  command(kAxis1, cmd::kPresetPosition, {.target = kMax, .speed = 0, .accel = 0, .decel = 0});
  const std::int64_t steps = vm_.stack().feedback(kAxis1).steps.load();
  vm_.set_step_count(kAxis1, steps + kMax);
  vm_.scans(2);
  ASSERT_EQ(position(kAxis1), 2'147'483'646);
  ASSERT_FALSE(status(kAxis1, kPositionInvalid));
  const std::int64_t motor_at = motor(kAxis1);

  // One step more ends at 2^31 - 1: fits, runs.
  command(kAxis1, cmd::kRelativeMove, {.target = 1});
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_FALSE(status(kAxis1, kInvalidProfile));
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
  EXPECT_EQ(position(kAxis1), 2'147'483'647);
  EXPECT_EQ(motor(kAxis1), motor_at + 1);

  // And one more would end at 2^31: IP + CE, no step.
  command(kAxis1, cmd::kRelativeMove, {.target = 1});
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  EXPECT_TRUE(status(kAxis1, kCommandError));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(kAxis1), motor_at + 1);

  // Back to 0 from 2^31 - 1: 2^31 - 1 steps CCW, planned and started.
  command(kAxis1, cmd::kResetErrors, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  command(kAxis1, cmd::kAbsoluteMove, {.target = 0, .speed = 1'000'000, .accel = 2000});
  EXPECT_TRUE(moving(kAxis1));
  EXPECT_FALSE(status(kAxis1, kInvalidProfile));
  command(kAxis1, cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_LT(motor(kAxis1), motor_at);
  // Axis 2 was never touched by any of it.
  EXPECT_FALSE(status(kAxis2, kInvalidProfile));
}

}  // namespace
}  // namespace stepmod::testing
