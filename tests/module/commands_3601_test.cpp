// 3601 commands in virtual time: absolute/relative moves, hold/resume, immediate stop, preset,
// reset errors, manual moves; the 3601 checklist items they implement are named in the test names.
#include <cmath>

#include "tests/module/plc_3601.hpp"

namespace stepmod::testing {
namespace {

using namespace m::status_msw;
namespace cmd = m::cmd_msw;

class Commands3601 : public Plc3601 {
 protected:
  void SetUp() override {
    configure();
    command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
    ASSERT_FALSE(status(kPositionInvalid));
  }
  bool errors() const {
    return status(kCommandError) || status(kInvalidProfile) || status(kInputError) ||
           status(kHomeInvalid);
  }
};

TEST_F(Commands3601, MC_01_RelativeMoveOutputsExactStepsAndCompletes) {
  command(cmd::kRelativeMove, {.target = 20'000});
  EXPECT_TRUE(moving());
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 20'000);
  EXPECT_EQ(position(), 20'000);
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kStopped));  // 3601-STP-N1
  EXPECT_FALSE(errors());
  EXPECT_EQ(vm_.step_times(0).size(), 20'000u);
}

TEST_F(Commands3601, MC_01_AbsoluteMoveGoesToTargetInBothDirections) {
  command(cmd::kAbsoluteMove, {.target = 7'500});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), 7'500);
  command(cmd::kAbsoluteMove, {.target = -2'345});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), -2'345);
  EXPECT_EQ(motor(), -2'345);
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Commands3601, DIR_01_DirectionBitsFollowTheMove) {
  command(cmd::kRelativeMove, {.target = 5'000});
  EXPECT_TRUE(status(kMovingCw));
  EXPECT_FALSE(status(kMovingCcw));
  ASSERT_TRUE(wait_idle());
  command(cmd::kRelativeMove, {.target = -5'000});
  EXPECT_TRUE(status(kMovingCcw));
  EXPECT_FALSE(status(kMovingCw));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), 0);
}

TEST_F(Commands3601, ACC_01_AccelerationAndDecelerationBitsFollowThePhases) {
  command(cmd::kRelativeMove, {.target = 20'000});
  bool saw_accel = false, saw_cruise = false, saw_decel = false;
  while (moving()) {
    saw_accel |= status(kAccelerating);
    saw_decel |= status(kDecelerating);
    saw_cruise |= !status(kAccelerating) && !status(kDecelerating);
    EXPECT_FALSE(status(kAccelerating) && status(kDecelerating));
    vm_.scans(10);
  }
  EXPECT_TRUE(saw_accel);
  EXPECT_TRUE(saw_cruise);
  EXPECT_TRUE(saw_decel);
}

TEST_F(Commands3601, MC_03_NextMoveClearsMoveCompleteButPresetDoesNot) {
  command(cmd::kRelativeMove, {.target = 100});
  ASSERT_TRUE(wait_idle());
  ASSERT_TRUE(status(kMoveComplete));
  command(cmd::kPresetPosition, {.target = 50, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_EQ(position(), 50);
  command(cmd::kRelativeMove, {.target = 10'000});
  EXPECT_FALSE(status(kMoveComplete));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), 10'050);
}

TEST_F(Commands3601, HLD_01_HoldStopsControlledAndResumeEndsAtTarget) {
  command(cmd::kAbsoluteMove, {.target = 40'000});
  vm_.run_for(1500 * kNsPerMs);
  ASSERT_TRUE(moving());
  command(cmd::kHold);
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kHoldState));
  EXPECT_FALSE(status(kMoveComplete));
  EXPECT_FALSE(status(kStopped));
  EXPECT_FALSE(status(kPositionInvalid));
  const std::int64_t held_at = position();
  EXPECT_GT(held_at, 0);
  EXPECT_LT(held_at, 40'000);
  // The controlled stop ends at the starting speed: the last period is about 1/Vs = 1 ms.
  const auto& t = vm_.step_times(0);
  ASSERT_GE(t.size(), 2u);
  EXPECT_NEAR(static_cast<double>(t[t.size() - 1] - t[t.size() - 2]), 1e6, 0.1e6);

  command(cmd::kResume, {.speed = 5'000, .accel = 20, .decel = 20});
  EXPECT_FALSE(status(kHoldState));  // 3601-HLD-C1
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), 40'000);
  EXPECT_EQ(motor(), 40'000);
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(errors());
}

TEST_F(Commands3601, HLD_01_HoldAndResumeRepeatedly) {
  command(cmd::kRelativeMove, {.target = -30'000});
  for (int i = 0; i < 3; ++i) {
    vm_.run_for(700 * kNsPerMs);
    if (!moving()) break;
    command(cmd::kHold);
    ASSERT_TRUE(wait_idle());
    ASSERT_TRUE(status(kHoldState));
    command(cmd::kResume);
  }
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), -30'000);
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Commands3601, PI_02_ImmediateStopLeavesPositionInvalidAndStopped) {
  command(cmd::kRelativeMove, {.target = 50'000});
  vm_.run_for(500 * kNsPerMs);
  command(cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(100 * kNsPerMs));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kStopped));  // 3601-STP-03
  EXPECT_FALSE(status(kMoveComplete));
  const std::int64_t stopped_at = motor();
  vm_.run_for(200 * kNsPerMs);
  EXPECT_EQ(motor(), stopped_at);  // no deceleration tail
  EXPECT_EQ(position(), stopped_at);
}

TEST_F(Commands3601, PI_02_ImmediateStopAtRestChangesNothing) {
  command(cmd::kImmediateStop);  // A6
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_FALSE(status(kStopped));
  EXPECT_FALSE(errors());
}

TEST_F(Commands3601, PI_C1_PresetPositionValidates) {
  command(cmd::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  command(cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle());
  ASSERT_TRUE(status(kPositionInvalid));
  command(cmd::kPresetPosition, {.target = -1'234'567, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_EQ(position(), -1'234'567);
}

TEST_F(Commands3601, PI_07_PlcLeavingRunModeStopsAndInvalidates) {
  command(cmd::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  vm_.stack().personality().plc_stopped(vm_.now());
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kPositionInvalid));
}

TEST_F(Commands3601, CE_L1_CommandErrorBlocksEveryCommandButResetErrors) {
  command(cmd::kResume);  // not in hold: CE
  ASSERT_TRUE(status(kCommandError));
  command(cmd::kRelativeMove, {.target = 1000});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
  command(cmd::kResetErrors);  // 3601-CE-L2
  EXPECT_FALSE(status(kCommandError));
  command(cmd::kRelativeMove, {.target = 1000});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 1000);
}

TEST_F(Commands3601, CE_L1_ImmediateStopIgnoredWhileCommandError) {
  command(cmd::kRelativeMove, {.target = 30'000});
  command(cmd::kResume);  // CE while moving
  ASSERT_TRUE(status(kCommandError));
  command(cmd::kImmediateStop);
  EXPECT_TRUE(moving());
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), 30'000);
}

TEST_F(Commands3601, CE_01_ConfigurationRequestWhileMovingFinishesTheMoveFirst) {
  command(cmd::kRelativeMove, {.target = 10'000});
  word(0) = static_cast<std::int16_t>(cmd::kConfigMode);
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kConfigMode));
  ASSERT_TRUE(vm_.run_until_true([this] { return status(kConfigMode); }, 10 * kNsPerSec));
  EXPECT_EQ(motor(), 10'000);
  EXPECT_FALSE(status(kCommandError));
}

TEST_F(Commands3601, CE_02_MoreThanOneCommandBit) {
  raw_command(cmd::kRelativeMove | cmd::kAbsoluteMove);
  EXPECT_TRUE(status(kCommandError));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
}

TEST_F(Commands3601, CE_03_MoveWhileMovingIsRefusedAndTheMoveContinues) {
  command(cmd::kRelativeMove, {.target = 10'000});
  command(cmd::kRelativeMove, {.target = 500});
  EXPECT_TRUE(status(kCommandError));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 10'000);
}

TEST_F(Commands3601, CE_04_ParameterOutOfRange) {
  const Move bad[] = {
      {.target = 8'388'608},
      {.target = -8'388'609},
      {.target = 100, .speed = 1'000'001},
      {.target = 100, .accel = 0},
      {.target = 100, .accel = 2001},
      {.target = 100, .decel = 0},
      {.target = 100, .decel = -5},
  };
  for (const Move& p : bad) {
    command(cmd::kRelativeMove, p);
    EXPECT_TRUE(status(kCommandError)) << p.target << " " << p.speed << " " << p.accel;
    EXPECT_TRUE(status(kInvalidProfile));  // 3601-IP-02
    command(cmd::kResetErrors);
  }
  vm_.run_for(50 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
}

TEST_F(Commands3601, CE_04_SplitWordsOutOfRangeOrOfOppositeSigns) {
  const std::int16_t pairs[][2] = {{0, 1000}, {0, -1000}, {12, -345}, {-12, 345}};
  for (const auto& p : pairs) {
    set_words(cmd::kRelativeMove, 0, 0, 10'000, 10, 10);
    word(2) = p[0];
    word(3) = p[1];
    vm_.scans(3);
    word(0) = 0;
    vm_.scans(1);
    EXPECT_TRUE(status(kCommandError)) << p[0] << "," << p[1];
    EXPECT_TRUE(status(kInvalidProfile));
    command(cmd::kResetErrors);
  }
  // The speed LSW must be 0..999.
  set_words(cmd::kRelativeMove, 0, 100, 0, 10, 10);
  word(4) = 10;
  word(5) = -1;
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
}

TEST_F(Commands3601, CE_05_ProgrammedSpeedBelowStartingSpeed) {
  command(cmd::kRelativeMove, {.target = 100, .speed = 999});
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));  // 3601-IP-01
}

TEST_F(Commands3601, IP_01_ProgrammedSpeedBelowStartingSpeedOnAbsoluteMove) {
  command(cmd::kAbsoluteMove, {.target = 100, .speed = 500});
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_TRUE(status(kCommandError));
}

TEST_F(Commands3601, IP_02_AnyMoveParameterOutOfRange) {
  command(cmd::kAbsoluteMove, {.target = 100, .accel = 3000});
  EXPECT_TRUE(status(kInvalidProfile));
}

TEST_F(Commands3601, CE_06_AbsoluteMoveWithInvalidPosition) {
  configure();  // position invalid again
  command(cmd::kAbsoluteMove, {.target = 100});
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kInvalidProfile));
  command(cmd::kResetErrors);
  command(cmd::kRelativeMove, {.target = 100});  // relative moves need no valid position
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 100);
}

TEST_F(Commands3601, CE_07_HoldWhileIdle) {
  command(cmd::kHold);
  EXPECT_TRUE(status(kCommandError));
}

TEST_F(Commands3601, CE_07_HoldDuringManualMoveStopsItControlled) {
  set_words(cmd::kManualCw, 0, 0, 5'000, 10, 10);
  vm_.run_for(500 * kNsPerMs);
  ASSERT_TRUE(moving());
  word(0) = static_cast<std::int16_t>(cmd::kHold);  // the Hold bit replaces the manual bit
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(status(kPositionInvalid));  // controlled (A43)
}

TEST_F(Commands3601, CE_08_ResumeWhenNotInHold) {
  command(cmd::kResume);
  EXPECT_TRUE(status(kCommandError));
}

TEST_F(Commands3601, CE_09_PresetWithNonZeroSpeedAccelOrDecel) {
  command(cmd::kPresetPosition, {.target = 10, .speed = 1, .accel = 0, .decel = 0});
  EXPECT_TRUE(status(kCommandError));
  command(cmd::kResetErrors);
  command(cmd::kPresetPosition, {.target = 10, .speed = 0, .accel = 1, .decel = 0});
  EXPECT_TRUE(status(kCommandError));
  command(cmd::kResetErrors);
  command(cmd::kPresetPosition, {.target = 10, .speed = 0, .accel = 0, .decel = 1});
  EXPECT_TRUE(status(kCommandError));
  EXPECT_EQ(position(), 0);
}

TEST_F(Commands3601, CE_12_HoldTogetherWithAnotherCommandBit) {
  command(cmd::kRelativeMove, {.target = 20'000});
  raw_command(cmd::kHold | cmd::kResume);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kHoldState));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 20'000);
}

TEST_F(Commands3601, CE_14_EncoderMoveWithoutEncoder) {
  configure(m::cfg_msw::kHomeUsed | m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCcwLimitUsed |
            m::cfg_msw::kStepDirOutput);
  command(cmd::kRelativeMove, {.target = 100, .lsw = m::cmd_lsw::kEncoderMove});
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));  // 3601-IP-11
}

TEST_F(Commands3601, IP_11_EncoderMoveWithoutEncoder) {
  configure(m::cfg_msw::kHomeUsed | m::cfg_msw::kCwLimitUsed | m::cfg_msw::kStepDirOutput);
  command(cmd::kAbsoluteMove, {.target = 0, .lsw = m::cmd_lsw::kEncoderMove});
  EXPECT_TRUE(status(kInvalidProfile));
}

TEST_F(Commands3601, CE_15_ResetErrorsAndPresetNeedAZeroLsw) {
  command(cmd::kPresetPosition, {.target = 5, .speed = 0, .accel = 0, .decel = 0, .lsw = 1});
  EXPECT_TRUE(status(kCommandError));
  command(cmd::kResetErrors, {.speed = 0, .accel = 0, .decel = 0, .lsw = 1});
  EXPECT_TRUE(status(kCommandError));
  command(cmd::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(kCommandError));
}

TEST_F(Commands3601, A33_ReservedCommandBit14) {
  raw_command(cmd::kReserved14);
  EXPECT_TRUE(status(kCommandError));
}

TEST_F(Commands3601, STP_01_ManualMoveStopsControlledWhenReleased) {
  set_words(cmd::kManualCcw, 0, 0, 8'000, 20, 20);
  vm_.run_for(600 * kNsPerMs);
  EXPECT_TRUE(status(kMovingCcw));
  word(0) = 0;  // only the command word is cleared (A11)
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_FALSE(errors());
  EXPECT_LT(position(), 0);
  EXPECT_EQ(position(), motor());
}

TEST_F(Commands3601, STP_01_ConstantSpeedManualMoveRunsAtProgrammedSpeed) {
  set_words(cmd::kManualCw, 0, 0, 500, 10, 10);  // Vp 500 <= Vs 1000: no ramps
  vm_.run_for(2 * kNsPerSec);
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
  const auto& t = vm_.step_times(0);
  ASSERT_GT(t.size(), 10u);
  for (std::size_t i = 1; i < t.size(); ++i) {
    EXPECT_NEAR(static_cast<double>(t[i] - t[i - 1]), 2e6, 2e3) << "step " << i;
  }
  EXPECT_TRUE(status(kStopped));
}

TEST_F(Commands3601, STP_N1_OneShotManualMoveOutputsOnePulse) {
  set_words(cmd::kManualCw, 0, 0, 0, 10, 10);
  vm_.run_for(300 * kNsPerMs);
  EXPECT_EQ(motor(), 1);
  word(0) = 0;
  vm_.scans(5);
  EXPECT_FALSE(status(kStopped));
  EXPECT_EQ(motor(), 1);
}

TEST_F(Commands3601, CE_L2_ResetErrorsClearsCommandErrorAndTheOtherNonFatalErrors) {
  command(cmd::kRelativeMove, {.target = 100, .speed = 500});  // Vp < Vs: CE + IP
  ASSERT_TRUE(status(kCommandError));
  ASSERT_TRUE(status(kInvalidProfile));
  command(cmd::kResetErrors);
  EXPECT_FALSE(status(kCommandError));
  EXPECT_FALSE(status(kInvalidProfile));   // A7: IP too
  EXPECT_FALSE(status(kPositionInvalid));  // ... but never PI
}

TEST_F(Commands3601, CE_L3_CommandErrorDoesNotClearItself) {
  command(cmd::kRelativeMove, {.target = 3'000});
  command(cmd::kResume);  // CE-08 while the move runs
  ASSERT_TRUE(status(kCommandError));
  ASSERT_TRUE(wait_idle());
  vm_.scans(50);
  // Only CE-01 (configuration) and CE-23 (Hold during a blend) clear themselves.
  EXPECT_TRUE(status(kCommandError));
  EXPECT_EQ(position(), 3'000);
}

TEST_F(Commands3601, IP_03_TheLongestMoveFitsTheRegisters) {
  // A32: on the 3601 every value beyond the documented ranges is a range error (CE-04/IP-02),
  // so no accepted move can overflow: the longest one (-8,388,608 -> 8,388,607) is planned.
  command(cmd::kPresetPosition, {.target = -8'388'608, .speed = 0, .accel = 0, .decel = 0});
  command(cmd::kAbsoluteMove,
          {.target = 8'388'607, .speed = 1'000'000, .accel = 2000, .decel = 2000});
  EXPECT_TRUE(moving());
  EXPECT_FALSE(status(kInvalidProfile));
  EXPECT_FALSE(status(kCommandError));
  command(cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle());
}

TEST_F(Commands3601, MC_02_NoMoveCompleteAfterAnErrorOrAManualMove) {
  command(cmd::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  force(InputLine::kEStop, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(status(kMoveComplete));  // ended with an error
  release(InputLine::kEStop);
  set_words(cmd::kManualCw, 0, 0, 5'000, 10, 10);
  vm_.run_for(300 * kNsPerMs);
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(status(kMoveComplete));  // manual moves never set MC
  EXPECT_TRUE(status(kStopped));
}

TEST_F(Commands3601, STP_C1_StoppedClearsWhenTheNextMoveStarts) {
  command(cmd::kRelativeMove, {.target = 50'000});
  vm_.run_for(200 * kNsPerMs);
  command(cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle());
  ASSERT_TRUE(status(kStopped));
  command(cmd::kRelativeMove, {.target = 1'000});
  EXPECT_FALSE(status(kStopped));
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(status(kStopped));
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Commands3601, HLD_C1_HoldClearsWhenANewMoveStartsInsteadOfResume) {
  command(cmd::kRelativeMove, {.target = 30'000});
  vm_.run_for(800 * kNsPerMs);
  command(cmd::kHold);
  ASSERT_TRUE(wait_idle());
  ASSERT_TRUE(status(kHoldState));
  command(cmd::kRelativeMove, {.target = -500});  // a completely new move, no resume
  EXPECT_FALSE(status(kHoldState));
  ASSERT_TRUE(wait_idle());
  command(cmd::kResume);  // the held move is gone
  EXPECT_TRUE(status(kCommandError));
}

TEST_F(Commands3601, MOK_01_ModuleOkAlwaysSet) {
  EXPECT_TRUE(status(kModuleOk));
  command(cmd::kRelativeMove, {.target = 2000});
  EXPECT_TRUE(status(kModuleOk));
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kModuleOk));
}

}  // namespace
}  // namespace stepmod::testing
