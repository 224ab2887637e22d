// 3202 command mode per channel: the 3202 checklist's Command Error (3202-CE-01..24 but the blend
// message items), Invalid Profile for moves, Position Invalid, Input Error, Stopped, Move Complete,
// Hold (3202 manual Ch.4, Ch.6). The behaviour is the shared axis' with kRules3202; these tests fix
// the 3202's words and bits around it, one channel acting, the other watched.
#include "tests/module/plc_3202.hpp"

namespace stepmod::testing {
namespace {

namespace sb = m2::status_bit;
namespace cb = m2::cmd_bit;
using namespace m2::cfg_bit;

constexpr Move3202 kFast{.target = 0, .speed = 10'000, .accel = 100'000, .decel = 100'000};

class Commands3202 : public Plc3202 {
 protected:
  void SetUp() override {
    configure(0);
    configure(1);
  }
  // Preset the position so that absolute moves are allowed.
  void preset(unsigned ch, std::int32_t p) {
    command(ch, cb::kPresetPosition, {.target = p, .speed = 0, .accel = 0, .decel = 0});
  }
  void expect_refused(unsigned ch, bool profile) {
    vm_.run_for(50 * kNsPerMs);
    EXPECT_TRUE(status(ch, sb::kCommandError));
    EXPECT_EQ(status(ch, sb::kInvalidProfile), profile);
    EXPECT_FALSE(moving(ch));
    EXPECT_EQ(motor(ch), 0);
  }
};

TEST_F(Commands3202, CE_01_ConfigurationRequestedWhileMovingFinishesTheMoveFirst) {
  command(0, cb::kRelativeMove, {.target = 20'000});
  ASSERT_TRUE(moving(0));
  write_config(0, kFull3202);
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kCommandError));
  EXPECT_FALSE(status(0, sb::kConfigMode));
  ASSERT_TRUE(vm_.run_until_true([&] { return status(0, sb::kConfigMode); }, 10 * kNsPerSec));
  EXPECT_EQ(motor(0), 20'000);
  EXPECT_FALSE(status(0, sb::kCommandError));
  EXPECT_FALSE(status(1, sb::kCommandError));
}

TEST_F(Commands3202, CE_02_MoreThanOneCommandBit) {
  command(0, cb::kRelativeMove | cb::kAbsoluteMove, {.target = 100});
  expect_refused(0, false);
  EXPECT_FALSE(status(1, sb::kCommandError));
  // Bits 16, 17, 18 and 29 are no commands.
  command(1, cb::kRelativeMove,
          {.target = 100, .flags = cb::kSCurve | cb::kTrapezoidalS | cb::kBackplaneProximity});
  ASSERT_TRUE(wait_idle(1));
  EXPECT_FALSE(status(1, sb::kCommandError));
  EXPECT_EQ(motor(1), 100);
}

TEST_F(Commands3202, CE_03_IP_02_ParameterOutOfRange) {
  command(0, cb::kRelativeMove, {.target = 8'388'608});
  expect_refused(0, true);
  command(0, cb::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  command(0, cb::kRelativeMove, {.target = 100, .speed = 1'000'001});
  expect_refused(0, true);
  command(0, cb::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  command(0, cb::kRelativeMove, {.target = 100, .accel = 999});
  expect_refused(0, true);
  command(0, cb::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  command(0, cb::kRelativeMove, {.target = 100, .decel = 2'000'001});
  expect_refused(0, true);
  EXPECT_FALSE(status(1, sb::kCommandError | sb::kInvalidProfile));
}

// A31: the accel/decel DINTs are steps/s^2 with 1,000 ... 2,000,000 accepted.
TEST_F(Commands3202, A31_AccelerationInStepsPerSecondSquared) {
  command(0, cb::kRelativeMove, {.target = 5'000, .accel = 2'000'000, .decel = 1'000});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_FALSE(status(0, sb::kCommandError));
  EXPECT_EQ(motor(0), 5'000);
  // At 1,000 steps/s^2 from Vs 1,000 the first 100 ms after the start add ~100 steps/s: the
  // move from rest covers far less than at 100,000 steps/s^2.
  command(1, cb::kRelativeMove, {.target = 100'000, .speed = 10'000, .accel = 1'000});
  vm_.run_for(500 * kNsPerMs);
  EXPECT_LT(motor(1), 700);
  EXPECT_GT(motor(1), 400);
}

TEST_F(Commands3202, CE_04_IP_01_SpeedBelowStartingSpeed) {
  command(0, cb::kRelativeMove, {.target = 100, .speed = 999});
  expect_refused(0, true);
}

TEST_F(Commands3202, CE_05_IP_03_ReservedDintsNotZero) {
  for (unsigned w = 5; w < 8; ++w) {
    set_command(0, cb::kRelativeMove, {.target = 100});
    word(0, w) = 7;
    vm_.scans(3);
    put(0, {});
    vm_.scans(1);
    expect_refused(0, true);
    command(0, cb::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
    EXPECT_FALSE(status(0, sb::kCommandError));
  }
}

TEST_F(Commands3202, CE_06_AbsoluteMoveWithPositionInvalid) {
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  command(0, cb::kAbsoluteMove, {.target = 100});
  expect_refused(0, false);
}

TEST_F(Commands3202, IP_04_A32_TheLongestMoveFitsTheRegisters) {
  // A32: on the 3202 every value beyond the documented ranges is a range error (CE-03/IP-02), so
  // no accepted move overflows: the longest one (-8,388,608 -> 8,388,607) is planned.
  preset(0, -8'388'608);
  command(0, cb::kAbsoluteMove,
          {.target = 8'388'607, .speed = 1'000'000, .accel = 2'000'000, .decel = 2'000'000});
  EXPECT_TRUE(moving(0));
  EXPECT_FALSE(status(0, sb::kInvalidProfile | sb::kCommandError));
  command(0, cb::kImmediateStop);
  ASSERT_TRUE(wait_idle(0));
}

TEST_F(Commands3202, PI_01_AfterEveryConfiguration) {
  preset(0, 500);
  EXPECT_FALSE(status(0, sb::kPositionInvalid));
  EXPECT_EQ(position(0), 500);
  configure(0);
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  EXPECT_EQ(position(0), 0);
}

TEST_F(Commands3202, PI_C1_PresetPositionClearsItAndKeepsMoveComplete) {
  command(0, cb::kRelativeMove, {.target = 100});
  ASSERT_TRUE(wait_idle(0));
  ASSERT_TRUE(status(0, sb::kMoveComplete));
  preset(0, -1'234);
  EXPECT_FALSE(status(0, sb::kPositionInvalid));
  EXPECT_EQ(position(0), -1'234);
  EXPECT_TRUE(status(0, sb::kMoveComplete));  // the manuals differ: the 3202 does not clear MC
  command(0, cb::kAbsoluteMove, {.target = -1'000});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(motor(0), 100 + 234);
}

TEST_F(Commands3202, CE_07_HoldDuringAManualMoveStopsItWithCommandError) {
  preset(0, 0);
  set_command(0, cb::kManualCw, {.speed = 5'000});
  vm_.scans(200);
  ASSERT_TRUE(moving(0));
  word(0, 0) = static_cast<std::int32_t>(cb::kHold);  // the Hold bit replaces the manual bit
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kCommandError));
  // A43: a controlled stop, the position stays valid.
  ASSERT_TRUE(wait_idle(0));
  EXPECT_FALSE(status(0, sb::kPositionInvalid));
}

TEST_F(Commands3202, CE_07_HoldDuringHomingRaisesCommandErrorAndHomingCompletes) {
  command(0, cb::kFindHomeCw, {.speed = 5'000, .accel = 100'000, .decel = 100'000});
  vm_.run_for(200 * kNsPerMs);
  ASSERT_TRUE(moving(0));
  command(0, cb::kHold);
  EXPECT_TRUE(status(0, sb::kCommandError));
  ASSERT_TRUE(vm_.run_until_true([&] { return status(0, sb::kAtHome); }, 20 * kNsPerSec));
  EXPECT_EQ(motor(0), 5'000);
}

TEST_F(Commands3202, CE_07_HoldDuringTheDecelerationPhaseIsIgnored) {
  command(0, cb::kRelativeMove, {.target = 12'000});
  ASSERT_TRUE(vm_.run_until_true([&] { return status(0, sb::kDecelerating); }, 10 * kNsPerSec));
  command(0, cb::kHold);
  ASSERT_TRUE(wait_idle(0));
  EXPECT_FALSE(status(0, sb::kCommandError));
  EXPECT_FALSE(status(0, sb::kHoldState));
  EXPECT_TRUE(status(0, sb::kMoveComplete));
  EXPECT_EQ(motor(0), 12'000);
}

TEST_F(Commands3202, CE_08_ResumeWhenNotInHold) {
  command(0, cb::kResume);
  expect_refused(0, false);
}

TEST_F(Commands3202, CE_09_PresetWithNonZeroSpeedAccelOrDecel) {
  command(0, cb::kPresetPosition, {.target = 10, .speed = 1, .accel = 0, .decel = 0});
  expect_refused(0, false);
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  command(0, cb::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  command(0, cb::kPresetEncoder, {.target = 10, .speed = 0, .accel = 1, .decel = 0});
  expect_refused(0, false);
  EXPECT_EQ(encoder(0), 0);
}

TEST_F(Commands3202, CE_10_HomingWithSCurve) {
  command(0, cb::kFindHomeCw, {.flags = cb::kSCurve});
  expect_refused(0, false);
}

TEST_F(Commands3202, CE_11_PresetEncoderWithoutEncoder) {
  configure(0, kFull3202 & ~kQuadratureEncoder);
  command(0, cb::kPresetEncoder, {.target = 10, .speed = 0, .accel = 0, .decel = 0});
  expect_refused(0, false);
  command(1, cb::kPresetEncoder, {.target = 10, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(1, sb::kCommandError));
  EXPECT_EQ(encoder(1), 10);
}

TEST_F(Commands3202, CE_12_IP_07_ManualMoveWithNonZeroTarget) {
  // The 3202 has no registration move: the target must be 0.
  set_command(0, cb::kManualCw, {.target = 100});
  vm_.scans(50);
  expect_refused(0, true);
}

TEST_F(Commands3202, CE_13_IP_08_TargetWrittenDuringAManualMove) {
  set_command(0, cb::kManualCw, {.speed = 5'000});
  vm_.scans(100);
  ASSERT_TRUE(moving(0));
  word(0, m2::out_word::kTarget) = 50;
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kCommandError));
  EXPECT_TRUE(status(0, sb::kInvalidProfile));
}

TEST_F(Commands3202, CE_14_IP_06_ManualSpeedChangedToZero) {
  set_command(0, cb::kManualCw, {.speed = 5'000});
  vm_.scans(100);
  word(0, m2::out_word::kSpeed) = 0;
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kCommandError));
  EXPECT_TRUE(status(0, sb::kInvalidProfile));
}

TEST_F(Commands3202, CE_15_IP_05_SpeedChangeOfAConstantSpeedManualMove) {
  set_command(0, cb::kManualCw, {.speed = 1'000});  // Vp <= Vs: constant speed
  vm_.scans(100);
  ASSERT_TRUE(moving(0));
  word(0, m2::out_word::kSpeed) = 800;
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kCommandError));
  EXPECT_TRUE(status(0, sb::kInvalidProfile));
  ASSERT_TRUE(wait_idle(0, kNsPerSec));
}

TEST_F(Commands3202, CE_16_IP_09_PI_07_InvalidChangeDuringAManualMoveStopsIt) {
  set_command(0, cb::kManualCw, {.speed = 5'000});
  vm_.scans(300);
  ASSERT_TRUE(moving(0));
  word(0, m2::out_word::kSpeed) = 6'000;
  word(0, m2::out_word::kAccel) = 5;  // examined because the speed changed
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kCommandError));
  EXPECT_TRUE(status(0, sb::kInvalidProfile));
  ASSERT_TRUE(wait_idle(0, kNsPerSec));
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
}

TEST_F(Commands3202, CE_17_RunBlendBeforeAProfileWasSent) {
  command(0, cb::kRunBlendCw, {.speed = 0, .accel = 0, .decel = 0});
  expect_refused(0, false);
}

TEST_F(Commands3202, CE_18_RunBlendWithNonZeroWords) {
  command(0, cb::kRunBlendCcw, {.target = 5, .speed = 0, .accel = 0, .decel = 0});
  expect_refused(0, false);
}

TEST_F(Commands3202, CE_21_HoldWithAnotherCommandBitIsIgnored) {
  command(0, cb::kRelativeMove, {.target = 20'000});
  ASSERT_TRUE(moving(0));
  set_command(0, cb::kHold | cb::kResume, {.target = 20'000});
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kCommandError));
  put(0, {});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(motor(0), 20'000);
  EXPECT_FALSE(status(0, sb::kHoldState));
}

TEST_F(Commands3202, CE_22_HI_03_FindHomeTowardAnUnconfiguredLimit) {
  configure(0, kFull3202 & ~kCwLimitUsed);
  command(0, cb::kFindHomeCw, kFast);
  expect_refused(0, false);
  EXPECT_TRUE(status(0, sb::kHomeInvalid));
}

TEST_F(Commands3202, CE_23_IP_10_EncoderMoveWithoutEncoder) {
  configure(0, kFull3202 & ~kQuadratureEncoder);
  command(0, cb::kRelativeMove, {.target = 100, .flags = cb::kEncoderMove});
  expect_refused(0, true);
}

TEST_F(Commands3202, CE_24_ReservedCommandBits) {
  for (unsigned b : {14u, 15u, 19u, 22u, 28u, 30u}) {
    command(0, cb::kRelativeMove | (1u << b), {.target = 100});
    word(0, 0) = 0;
    expect_refused(0, false);
    command(0, cb::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
    EXPECT_FALSE(status(0, sb::kCommandError)) << "bit " << b;
  }
}

// 3202-CE-L1 (as 3601): while CE is set even Immediate Stop is ignored; Reset Errors acts on its
// own channel only.
TEST_F(Commands3202, CE_L1_CommandErrorBlocksImmediateStopAndResetIsPerChannel) {
  command(0, cb::kRelativeMove, {.target = 20'000});
  command(1, cb::kResume);
  EXPECT_TRUE(status(1, sb::kCommandError));
  command(0, cb::kResume);
  EXPECT_TRUE(status(0, sb::kCommandError));
  command(0, cb::kImmediateStop);
  EXPECT_TRUE(moving(0));
  command(0, cb::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(0, sb::kCommandError));
  EXPECT_TRUE(status(1, sb::kCommandError));
  command(0, cb::kImmediateStop);
  EXPECT_FALSE(moving(0));
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
}

TEST_F(Commands3202, HI_01_HomeWithTargetNotZero) {
  command(0, cb::kFindHomeCw, {.target = 1, .speed = 10'000, .accel = 100'000, .decel = 100'000});
  expect_refused(0, false);
  EXPECT_TRUE(status(0, sb::kHomeInvalid));
}

TEST_F(Commands3202, HI_02_HomeWithSpeedBelowStartingSpeed) {
  command(0, cb::kFindHomeCcw, {.speed = 500, .accel = 100'000, .decel = 100'000});
  expect_refused(0, true);
  EXPECT_TRUE(status(0, sb::kHomeInvalid));
}

TEST_F(Commands3202, HI_04_HomeWithReservedDintsNotZero) {
  set_command(0, cb::kFindHomeCw, kFast);
  word(0, 7) = 1;
  vm_.scans(3);
  put(0, {});
  expect_refused(0, true);
  EXPECT_TRUE(status(0, sb::kHomeInvalid));
}

TEST_F(Commands3202, AH_01_HomingCompletesAndZeroesTheRegisters) {
  command(1, cb::kPresetEncoder, {.target = 77, .speed = 0, .accel = 0, .decel = 0});
  command(1, cb::kFindHomeCw, kFast);
  ASSERT_TRUE(vm_.run_until_true([&] { return status(1, sb::kAtHome); }, 20 * kNsPerSec));
  EXPECT_EQ(position(1), 0);
  EXPECT_EQ(encoder(1), 0);
  EXPECT_EQ(capture(1), 0);
  EXPECT_FALSE(status(1, sb::kPositionInvalid));
  EXPECT_FALSE(status(1, sb::kStopped));  // 3202-STP-N1: not after homing
  EXPECT_GE(motor(1), 5'000);
  EXPECT_LE(motor(1), 5'100);
  EXPECT_EQ(motor(0), 0);
}

TEST_F(Commands3202, PI_02_STP_03_ImmediateStopWhileMoving) {
  command(0, cb::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  command(0, cb::kImmediateStop);
  const auto at = motor(0);
  vm_.run_for(200 * kNsPerMs);
  EXPECT_LE(motor(0), at + 1);
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  EXPECT_TRUE(status(0, sb::kStopped));
  EXPECT_FALSE(status(0, sb::kMoveComplete));
}

TEST_F(Commands3202, PI_03_IE_01_STP_02_EStopWhileMoving) {
  command(0, cb::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  force(0, InputLine::kEStop, true);
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kInputError));
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  EXPECT_TRUE(status(0, sb::kStopped));
  EXPECT_TRUE(status(0, 1u << (sb::kInputShift + 3)));  // E-stop active, bit 19
  EXPECT_FALSE(moving(0));
  EXPECT_FALSE(status(1, sb::kInputError));
}

TEST_F(Commands3202, PI_04_IE_02_STP_04_LimitDuringAMove) {
  command(0, cb::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  force(0, InputLine::kCwLimit, true);
  vm_.scans(3);
  EXPECT_TRUE(status(0, sb::kInputError));
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  EXPECT_TRUE(status(0, sb::kStopped));
  EXPECT_TRUE(status(0, 1u << (sb::kInputShift + 4)));  // CW limit active, bit 20
  EXPECT_FALSE(moving(0));
}

TEST_F(Commands3202, IE_03_ManualMoveTowardAnActiveLimit) {
  force(0, InputLine::kCcwLimit, true);
  vm_.scans(2);
  set_command(0, cb::kManualCcw, {.speed = 5'000});
  vm_.scans(50);
  EXPECT_TRUE(status(0, sb::kInputError));
  EXPECT_EQ(motor(0), 0);
}

TEST_F(Commands3202, IE_N1_InputErrorDoesNotBlockMoves) {
  force(0, InputLine::kEStop, true);
  vm_.scans(2);
  release(0, InputLine::kEStop);
  vm_.scans(2);
  command(0, cb::kRelativeMove, {.target = 100});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(motor(0), 100);
  EXPECT_FALSE(status(0, sb::kCommandError));
}

TEST_F(Commands3202, STP_01_ManualMoveEndsWithStopped) {
  set_command(0, cb::kManualCw, {.speed = 5'000});
  vm_.scans(100);
  put(0, {});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_TRUE(status(0, sb::kStopped));
  EXPECT_GT(motor(0), 0);
}

TEST_F(Commands3202, STP_N1_MC_01_MoveCompleteWithoutStopped) {
  command(0, cb::kRelativeMove, {.target = 1'000});
  EXPECT_FALSE(status(0, sb::kMoveComplete));
  ASSERT_TRUE(wait_idle(0));
  EXPECT_TRUE(status(0, sb::kMoveComplete));
  EXPECT_FALSE(status(0, sb::kStopped));
  EXPECT_EQ(position(0), 1'000);
  // Cleared when the next move starts; an encoder move completes it too.
  command(0, cb::kRelativeMove, {.target = 1'000, .flags = cb::kEncoderMove});
  EXPECT_FALSE(status(0, sb::kMoveComplete));
  ASSERT_TRUE(wait_idle(0));
  EXPECT_TRUE(status(0, sb::kMoveComplete));
  // The deceleration starts on the count: an encoder move overshoots by its ramp (3202 manual ch. 4
  // "Encoder Move").
  EXPECT_GE(encoder(0), 2'000);
  EXPECT_EQ(encoder(0), motor(0));
}

TEST_F(Commands3202, HLD_01_HoldAndResume) {
  command(0, cb::kRelativeMove, {.target = 30'000});
  vm_.run_for(500 * kNsPerMs);
  command(0, cb::kHold);
  ASSERT_TRUE(wait_idle(0));
  EXPECT_TRUE(status(0, sb::kHoldState));
  EXPECT_FALSE(status(0, sb::kStopped));
  EXPECT_LT(motor(0), 30'000);
  command(0, cb::kResume, {.speed = 20'000, .accel = 100'000, .decel = 100'000});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(motor(0), 30'000);
  EXPECT_TRUE(status(0, sb::kMoveComplete));
  EXPECT_FALSE(status(0, sb::kHoldState));
}

TEST_F(Commands3202, HLD_01_EncoderMoveIgnoresHoldAndStopsOnExternalWithoutHold) {
  command(0, cb::kRelativeMove, {.target = 30'000, .flags = cb::kEncoderMove});
  vm_.run_for(300 * kNsPerMs);
  command(0, cb::kHold);  // Ch.4 "Hold Move" note 4: ignored
  EXPECT_FALSE(status(0, sb::kCommandError));
  EXPECT_TRUE(moving(0));
  force(0, InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle(0, 5 * kNsPerSec));
  EXPECT_LT(motor(0), 30'000);
  EXPECT_FALSE(status(0, sb::kHoldState));
  EXPECT_FALSE(status(0, sb::kMoveComplete));
}

TEST_F(Commands3202, PI_08_PlcLeavesRunModeWhileMoving) {
  command(0, cb::kRelativeMove, {.target = 50'000});
  command(1, cb::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  vm_.stack().personality().plc_stopped(vm_.now());
  vm_.scans(3);
  for (unsigned ch = 0; ch < 2; ++ch) {
    EXPECT_FALSE(moving(ch));
    EXPECT_TRUE(status(ch, sb::kPositionInvalid));
  }
}

// Capture (3202 manual ch. 3 bit 0): the encoder count at the capture edge with the encoder
// configured.
TEST_F(Commands3202, CaptureTakesTheEncoderCount) {
  command(0, cb::kRelativeMove, {.target = 3'000});
  ASSERT_TRUE(wait_idle(0));
  force(0, InputLine::kCapture, true);
  vm_.scans(2);
  EXPECT_EQ(capture(0), 3'000);
  EXPECT_TRUE(status(0, 1u << sb::kInputShift));
  EXPECT_EQ(capture(1), 0);
}

// Bit 29 echoed in status bit 29, whatever the configuration (A44).
TEST_F(Commands3202, ProximityBitEchoed) {
  word(1, 0) = static_cast<std::int32_t>(cb::kBackplaneProximity);
  vm_.scans(2);
  EXPECT_TRUE(status(1, sb::kProximityEcho));
  EXPECT_FALSE(status(0, sb::kProximityEcho));
}

// The registers are native DINTs (3202 manual ch. 5, 6).
TEST_F(Commands3202, NegativePositionIsANativeDint) {
  command(0, cb::kRelativeMove, {.target = -2'500});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(position(0), -2'500);
  EXPECT_EQ(motor(0), -2'500);
}

TEST_F(Commands3202, BothChannelsMoveAtOnceWithExactCounts) {
  command(0, cb::kRelativeMove, {.target = 12'345});
  command(1, cb::kRelativeMove, {.target = -6'789, .speed = 20'000});
  EXPECT_TRUE(moving(0));
  EXPECT_TRUE(moving(1));
  ASSERT_TRUE(wait_idle(0));
  ASSERT_TRUE(wait_idle(1));
  EXPECT_EQ(motor(0), 12'345);
  EXPECT_EQ(motor(1), -6'789);
  EXPECT_EQ(vm_.step_times(0).size(), 12'345u);
  EXPECT_EQ(vm_.step_times(1).size(), 6'789u);
}

}  // namespace
}  // namespace stepmod::testing
