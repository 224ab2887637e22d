// 3602 command mode through the module's words, motion commands and their errors (the 3602
// checklist's CE, IP, PI, IE, HLD items; manual ch. 2, 9): moves, hold/resume, immediate stop, jog,
// registration and the minimum registration distance, blend programming and run.
#include <array>
#include <vector>

#include "tests/module/rig_3602.hpp"
#include "tests/support/checklist_rows.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::status_msw;
namespace cmd = m2::cmd_msw;
namespace lsw = m2::cmd_lsw;

class Motion3602 : public Rig3602 {
 protected:
  void SetUp() override {
    configure(kAxis1);
    configure(kAxis2);
  }
  void reset_errors(unsigned a) {
    command(a, cmd::kResetErrors, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  }
  // A relative move of `target` commanded (its bit released after 3 scans) and 300 ms under way.
  void start_relative_move(unsigned a, std::int32_t target) {
    set_command(a, cmd::kRelativeMove, {.target = target});
    vm_.scans(3);
    word(a, m2::out_word::kMsw) = 0;
    vm_.run_for(300 * kNsPerMs);
  }
  void force(unsigned a, InputLine l, bool level) {
    const std::uint32_t bit = 1u << static_cast<unsigned>(l);
    if (level) {
      levels_[a] |= bit;
    } else {
      levels_[a] &= ~bit;
    }
    mask_[a] |= bit;
    vm_.sim().force(a, mask_[a], levels_[a], vm_.now());
    vm_.scans(2);
  }
  // Blend programming (3602 manual table 9.2, Ch.9 "Programming Blend Move Profiles"): each block
  // with LSW bits 4 and 5, wait for the acknowledge (status LSW bit 9), drop bit 5, wait for it to
  // clear.
  bool program_blend(unsigned a, const std::vector<std::array<std::int16_t, 6>>& blocks) {
    clear_words(a);
    for (const auto& b : blocks) {
      for (unsigned i = 0; i < 6; ++i) word(a, 2 + i) = b[i];
      word(a, m2::out_word::kLsw) = lsw::kProgramBlend | lsw::kBlendTransmit;
      if (!vm_.run_until_true([&] { return lsw_status(a, m2::status_lsw::kBlendAcknowledge); },
                              kNsPerSec)) {
        return false;
      }
      word(a, m2::out_word::kLsw) = lsw::kProgramBlend;
      if (!vm_.run_until_true([&] { return !lsw_status(a, m2::status_lsw::kBlendAcknowledge); },
                              kNsPerSec)) {
        return false;
      }
    }
    clear_words(a);
    vm_.scans(3);
    return true;
  }
  static std::array<std::int16_t, 6> segment(std::int32_t length, std::int32_t speed,
                                             std::int16_t rate) {
    const auto l = words::encode_3602(length);
    const auto s = words::encode_3602(speed);
    return {l.msw, l.lsw, s.msw, s.lsw, rate, 0};
  }
  std::uint32_t mask_[2] = {0, 0};
  std::uint32_t levels_[2] = {0, 0};
};

TEST_F(Motion3602, CE_01_ConfigurationRequestDuringMotionFinishesTheMove) {
  set_command(kAxis1, cmd::kRelativeMove, {.target = 8'000});
  vm_.scans(3);
  ASSERT_TRUE(moving(kAxis1));
  write_config(kAxis1, kLimitsConfigMsw);
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_TRUE(moving(kAxis1));
  ASSERT_TRUE(vm_.run_until_true([this] { return status(kAxis1, kConfigMode); }, 10 * kNsPerSec));
  EXPECT_EQ(motor(kAxis1), 8'000);
  EXPECT_FALSE(status(kAxis1, kCommandError));
}

TEST_F(Motion3602, CE_04_MoveWhileMovingIsRefusedAndTheMoveRunsOn) {
  set_command(kAxis1, cmd::kRelativeMove, {.target = 6'000});
  vm_.scans(3);
  word(kAxis1, m2::out_word::kMsw) = 0;
  vm_.scans(1);
  command(kAxis1, cmd::kAbsoluteMove, {.target = 100});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), 6'000);
}

TEST_F(Motion3602, CE_07_AbsoluteMoveWithPositionInvalid) {
  ASSERT_TRUE(status(kAxis1, kPositionInvalid));  // 3602-PI-01 after the configuration
  command(kAxis1, cmd::kAbsoluteMove, {.target = 100});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
  reset_errors(kAxis1);
  command(kAxis1, cmd::kRelativeMove, {.target = 100});  // relative is allowed
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), 100);
}

TEST_F(Motion3602, PI_01_PI_C1_ConfigurationInvalidatesPresetValidates) {
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_EQ(position(kAxis1), 0);
  command(kAxis1, cmd::kPresetPosition, {.target = 123, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));
  EXPECT_EQ(position(kAxis1), 123);
  command(kAxis1, cmd::kAbsoluteMove, {.target = -77});
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), -200);
  EXPECT_EQ(position(kAxis1), -77);
}

TEST_F(Motion3602, CE_09_ResumeWhenNotInHold) {
  command(kAxis1, cmd::kResume);
  EXPECT_TRUE(status(kAxis1, kCommandError));
}

TEST_F(Motion3602, HLD_01_HoldThenResumeReachesTheTarget) {
  set_command(kAxis1, cmd::kRelativeMove, {.target = 20'000});
  vm_.scans(3);
  word(kAxis1, m2::out_word::kMsw) = 0;
  vm_.run_for(500 * kNsPerMs);
  command(kAxis1, cmd::kHold);
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_TRUE(status(kAxis1, kHoldState));
  EXPECT_TRUE(status(kAxis1, kStopped));  // 3602-STP-01: in Hold too
  EXPECT_LT(motor(kAxis1), 20'000);
  command(kAxis1, cmd::kResume, {.target = 0, .speed = 15'000});
  EXPECT_FALSE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), 20'000);
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
}

TEST_F(Motion3602, HLD_01_ExternalInputHoldsAMove) {
  start_relative_move(kAxis1, 20'000);
  force(kAxis1, InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_TRUE(status(kAxis1, kHoldState));
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kExternalActive));
}

TEST_F(Motion3602, PI_02_ImmediateStopInvalidatesThePosition) {
  command(kAxis1, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  start_relative_move(kAxis1, 20'000);
  command(kAxis1, cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(kAxis1, 10 * kNsPerMs));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_FALSE(status(kAxis1, kMoveComplete));
  EXPECT_TRUE(moving(kAxis2) == false);
}

TEST_F(Motion3602, IE_02_PI_04_IE_C1_LimitDuringAMoveThenTheNextMoveClearsIE) {
  start_relative_move(kAxis2, -20'000);
  force(kAxis2, InputLine::kCwLimit, true);  // either limit stops an absolute/relative move
  ASSERT_TRUE(wait_idle(kAxis2));
  EXPECT_TRUE(status(kAxis2, kInputError));
  EXPECT_TRUE(status(kAxis2, kPositionInvalid));
  // IE-C1: the next move clears IE once no input is active.
  force(kAxis2, InputLine::kCwLimit, false);
  command(kAxis2, cmd::kRelativeMove, {.target = -100});
  EXPECT_FALSE(status(kAxis2, kInputError));
  EXPECT_FALSE(status(kAxis2, kCommandError));
}

// 3602-IE-C1, every clause (manual Ch.9 bit 11: "latched but you do not have to issue a Clear
// Errors command block ... The next move command will clear this bit automatically if none of
// the inputs are active when the command is issued"):
TEST_F(Motion3602, IE_C1_LatchedClearedByTheNextMoveOnlyWithNoInputActive) {
  start_relative_move(kAxis1, 20'000);
  force(kAxis1, InputLine::kCwLimit, true);
  ASSERT_TRUE(wait_idle(kAxis1));
  ASSERT_TRUE(status(kAxis1, kInputError));
  // Latched: the input going inactive again leaves it set.
  force(kAxis1, InputLine::kCwLimit, false);
  vm_.scans(20);
  EXPECT_TRUE(status(kAxis1, kInputError));
  // A move command issued while an input is active (the CW limit again; the move goes CCW, away
  // from it, and runs) does not clear it, not even when that move completes.
  force(kAxis1, InputLine::kCwLimit, true);
  const std::int64_t at = motor(kAxis1);
  command(kAxis1, cmd::kRelativeMove, {.target = -500});
  EXPECT_TRUE(status(kAxis1, kInputError));
  EXPECT_FALSE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), at - 500);
  EXPECT_TRUE(status(kAxis1, kInputError));
  // No Reset Errors: with no input active, the next move command clears it.
  force(kAxis1, InputLine::kCwLimit, false);
  command(kAxis1, cmd::kRelativeMove, {.target = -100});
  EXPECT_FALSE(status(kAxis1, kInputError));
  EXPECT_FALSE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), at - 600);
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
}

TEST_F(Motion3602, IE_05_JogTowardAnActiveLimit) {
  force(kAxis1, InputLine::kCwLimit, true);
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kCwActive));
  set_command(kAxis1, cmd::kJogCw, {.target = 0, .speed = 5'000});
  vm_.scans(20);
  EXPECT_TRUE(status(kAxis1, kInputError));
  EXPECT_EQ(motor(kAxis1), 0);
  // Driven off the limit the other way.
  set_command(kAxis1, 0, {});
  vm_.scans(2);
  set_command(kAxis1, cmd::kJogCcw, {.target = 0, .speed = 5'000});
  vm_.run_for(200 * kNsPerMs);
  EXPECT_LT(motor(kAxis1), 0);
}

TEST_F(Motion3602, IE_03_PI_05_SameDirectionLimitDuringAJog) {
  set_command(kAxis1, cmd::kJogCw, {.target = 0, .speed = 5'000});
  vm_.run_for(300 * kNsPerMs);
  force(kAxis1, InputLine::kCwLimit, true);
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_TRUE(status(kAxis1, kInputError));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
}

TEST_F(Motion3602, JogRampedRunsWhileHeldAndDeceleratesOnRelease) {
  set_command(kAxis1, cmd::kJogCw, {.target = 0, .speed = 5'000, .accel = 10, .decel = 10});
  vm_.run_for(kNsPerSec);
  EXPECT_TRUE(status(kAxis1, kMovingCw));
  const std::int64_t at = motor(kAxis1);
  EXPECT_GT(at, 2'000);
  word(kAxis1, m2::out_word::kMsw) = 0;
  EXPECT_TRUE(vm_.run_until_true([this] { return status(kAxis1, kDecelerating); }, 50 * kNsPerMs));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_GT(motor(kAxis1), at);
  EXPECT_TRUE(status(kAxis1, kStopped));
  EXPECT_FALSE(status(kAxis1, kMoveComplete));  // MC-01: jogs do not set it
}

// A14: a jog whose initial Vp is <= Vs runs at constant speed (no ramp): Vp = Vs = 1,000 steps/s
// outputs 1,000 steps/s from the first step.
TEST_F(Motion3602, CE_J1_IP_08_ConstantSpeedJogAndItsSpeedChange) {
  set_command(kAxis1, cmd::kJogCcw, {.target = 0, .speed = 1'000});
  vm_.run_for(500 * kNsPerMs);
  const auto& t = vm_.step_times(kAxis1);
  ASSERT_GE(t.size(), 10u);
  EXPECT_NEAR(static_cast<double>(t[2] - t[1]), 1e6, 2e4);  // 1 ms per step from the start
  EXPECT_FALSE(status(kAxis1, kAccelerating));
  // J1: a speed change on such a jog is refused (CE + IP).
  put_split(kAxis1, m2::out_word::kSpeedMsw, 3'000);
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
}

TEST_F(Motion3602, JogOneShotAtVsWithSpeedZero) {
  command(kAxis1, cmd::kJogCw, {.target = 0, .speed = 0});
  vm_.scans(10);
  EXPECT_EQ(motor(kAxis1), 1);
  command(kAxis1, cmd::kJogCcw, {.target = 0, .speed = 0});
  vm_.scans(10);
  EXPECT_EQ(motor(kAxis1), 0);
}

// Registration: a jog with a position offset; after the External edge it moves exactly the
// offset, then stops (3602 manual ch. 2).
TEST_F(Motion3602, RegistrationMovesTheOffsetAfterTheExternalEdge) {
  set_command(kAxis1, cmd::kJogCw, {.target = 6'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(700 * kNsPerMs);
  ASSERT_TRUE(moving(kAxis1));
  force(kAxis1, InputLine::kExternal, true);
  std::int64_t steps_then = 0;
  const auto& t = vm_.step_times(kAxis1);
  // The step count when the input rose: the steps before its time.
  const Nanos edge = vm_.now() - 2 * kNsPerMs;
  for (Nanos s : t) {
    if (s <= edge) ++steps_then;
  }
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_NEAR(static_cast<double>(motor(kAxis1)), static_cast<double>(steps_then + 6'000), 25.0);
}

TEST_F(Motion3602, CE_R4_IP_12_OffsetShorterThanTheStop) {
  // Vs 1,000 -> Vp 10,000 at 10 steps/ms/s needs 4,950 steps to stop (3602 manual ch. 2).
  command(kAxis1, cmd::kJogCw, {.target = 4'949, .speed = 10'000, .accel = 10, .decel = 10});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
  reset_errors(kAxis1);
  set_command(kAxis1, cmd::kJogCw, {.target = 4'950, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.scans(5);
  EXPECT_FALSE(status(kAxis1, kCommandError));
  EXPECT_TRUE(moving(kAxis1));
}

// LSW bit 2: program the minimum registration distance (words 2/3); status LSW bit 10 reports a
// non-zero distance. With one set, a registration may start with External active (a difference
// between the manuals).
TEST_F(Motion3602, LSW_01_MinimumRegistrationDistanceSetAndUsed) {
  EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kMinRegistrationSet));
  set_command(
      kAxis1, 0,
      {.target = 2'000, .speed = 0, .accel = 0, .decel = 0, .lsw = lsw::kProgramMinRegistration});
  vm_.scans(3);
  clear_words(kAxis1);
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kMinRegistrationSet));
  EXPECT_FALSE(status(kAxis1, kCommandError));
  force(kAxis1, InputLine::kExternal, true);
  set_command(kAxis1, cmd::kJogCw, {.target = 6'000, .speed = 10'000});
  vm_.scans(5);
  EXPECT_FALSE(status(kAxis1, kCommandError));
  EXPECT_TRUE(moving(kAxis1));
}

TEST_F(Motion3602, CE_R1_NegativeMinimumRegistrationDistance) {
  set_command(
      kAxis1, 0,
      {.target = -1, .speed = 0, .accel = 0, .decel = 0, .lsw = lsw::kProgramMinRegistration});
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kMinRegistrationSet));
}

// 3602-CE-08, second clause: Hold during a registration move -> CE; the axis is not held (no
// Hold state). Writing the Hold word drops the level-held jog bit, so the motion stops as at a
// release, controlled.
TEST_F(Motion3602, CE_R2_CE_08_HoldDuringARegistration) {
  command(kAxis1, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  set_command(kAxis1, cmd::kJogCw, {.target = 6'000, .speed = 10'000});
  vm_.run_for(200 * kNsPerMs);
  set_command(kAxis1, cmd::kHold, {.target = 6'000, .speed = 10'000});
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_FALSE(status(kAxis1, kHoldState));
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));  // a controlled stop
}

// 3602-CE-08's note, A5: Hold during a jog is not in the list; the choice is CE plus the
// controlled stop that follows because the Hold word clears the jog bit (as on the 3601/3202).
TEST_F(Motion3602, CE_08_HoldDuringAJogIsCommandErrorAndAControlledStop) {
  command(kAxis1, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  set_command(kAxis1, cmd::kJogCw, {.target = 0, .speed = 5'000});
  vm_.run_for(500 * kNsPerMs);
  const std::int64_t at_hold = motor(kAxis1);
  set_command(kAxis1, cmd::kHold);
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_FALSE(status(kAxis1, kHoldState));
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));
  // Controlled: from 5,000 to Vs 1,000 steps/s at 10 steps/ms/s takes 1,200 steps (an immediate
  // stop would take none).
  EXPECT_GE(motor(kAxis1) - at_hold, 1'000);
  EXPECT_EQ(position(kAxis1), motor(kAxis1));
}

// Blend: program 2 segments (first block + 2 segment blocks, handshake on LSW bits 4/5 and status
// LSW bit 9), run it CW: exact total, Move Complete.
TEST_F(Motion3602, MC_01_BlendProgrammedWithTheHandshakeRunsItsTotal) {
  const std::array<std::int16_t, 6> first = {2, 0, 0, 10, 0, 0};  // 2 segments, final decel 10
  ASSERT_TRUE(
      program_blend(kAxis1, {first, segment(50'800, 20'000, 20), segment(20'000, 5'000, 20)}));
  EXPECT_FALSE(status(kAxis1, kInvalidProfile));
  EXPECT_FALSE(status(kAxis1, kCommandError));
  command(kAxis1, cmd::kRunBlendCw, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kBlendRunning));
  ASSERT_TRUE(wait_idle(kAxis1, 20 * kNsPerSec));
  EXPECT_EQ(motor(kAxis1), 70'800);
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
  EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kBlendRunning));
  // Run blend - runs it back.
  command(kAxis1, cmd::kRunBlendCcw, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  ASSERT_TRUE(wait_idle(kAxis1, 20 * kNsPerSec));
  EXPECT_EQ(motor(kAxis1), 0);
}

TEST_F(Motion3602, CE_B1_RunBlendBeforeAProfileWasProgrammed) {
  command(kAxis2, cmd::kRunBlendCw, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_TRUE(status(kAxis2, kCommandError));
  vm_.scans(10);
  EXPECT_EQ(motor(kAxis2), 0);
}

TEST_F(Motion3602, CE_R8_IP_16_AccelChangedWithASpeedChangeDuringRegistration) {
  set_command(kAxis1, cmd::kJogCw, {.target = 6'000, .speed = 10'000});
  vm_.run_for(300 * kNsPerMs);
  word(kAxis1, m2::out_word::kAccel) = 20;  // alone: not examined
  vm_.scans(3);
  EXPECT_FALSE(status(kAxis1, kCommandError));
  put_split(kAxis1, m2::out_word::kSpeedMsw, 8'000);  // with a speed change: examined
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  ASSERT_TRUE(wait_idle(kAxis1, 20 * kNsPerMs));
}

TEST_F(Motion3602, IP_02_MoveParameterOutOfRange) {
  command(kAxis1, cmd::kRelativeMove, {.target = 100, .accel = 2'001});
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  EXPECT_TRUE(status(kAxis1, kCommandError));
  reset_errors(kAxis1);
  command(kAxis1, cmd::kRelativeMove, {.target = 100, .decel = 0});
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
}

TEST_F(Motion3602, CE_B3_RunBlendWithReservedWordsNonZero) {
  const std::array<std::int16_t, 6> first = {2, 0, 0, 10, 0, 0};
  ASSERT_TRUE(
      program_blend(kAxis1, {first, segment(20'000, 10'000, 20), segment(20'000, 5'000, 20)}));
  command(kAxis1, cmd::kRunBlendCw, {.target = 0, .speed = 0, .accel = 0, .decel = 1});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
}

// 3602-CE-08, first clause: Hold during a blend (CE-B5: the blend runs on, CE clears at its end).
TEST_F(Motion3602, CE_B5_CE_08_HoldDuringABlendFinishesItThenSelfClears) {
  const std::array<std::int16_t, 6> first = {2, 0, 0, 10, 0, 0};
  ASSERT_TRUE(
      program_blend(kAxis1, {first, segment(20'000, 10'000, 20), segment(20'000, 5'000, 20)}));
  command(kAxis1, cmd::kRunBlendCw, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  vm_.run_for(300 * kNsPerMs);
  command(kAxis1, cmd::kHold);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1, 20 * kNsPerSec));
  vm_.scans(3);
  EXPECT_EQ(motor(kAxis1), 40'000);
  EXPECT_FALSE(status(kAxis1, kCommandError));
}

TEST_F(Motion3602, CE_B4_ProgrammingStartedWhileABlendRuns) {
  const std::array<std::int16_t, 6> first = {2, 0, 0, 10, 0, 0};
  ASSERT_TRUE(
      program_blend(kAxis1, {first, segment(20'000, 10'000, 20), segment(20'000, 5'000, 20)}));
  command(kAxis1, cmd::kRunBlendCw, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  vm_.run_for(300 * kNsPerMs);
  // The first block of a new cycle offered (program + transmit).
  word(kAxis1, m2::out_word::kLsw) = lsw::kProgramBlend | lsw::kBlendTransmit;
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  ASSERT_TRUE(wait_idle(kAxis1, 20 * kNsPerSec));
  EXPECT_LT(motor(kAxis1), 40'000);  // brought down with the final deceleration
}

TEST_F(Motion3602, IP_20_SegmentLengthOutOfRange) {
  const std::array<std::int16_t, 6> first = {2, 0, 0, 10, 0, 0};
  program_blend(kAxis1, {first, segment(1'073'741'823, 5'000, 20), segment(20'000, 3'000, 20)});
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  reset_errors(kAxis1);
  program_blend(kAxis1, {first, segment(0, 5'000, 20), segment(20'000, 3'000, 20)});
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
}

// ---- Refused at the start: Command Error + Invalid Profile, and no step ------------------------

struct RefusedStart {
  const char* name;
  std::uint16_t command;
  Move3602 words;
  bool external_active = false;  // the External input active before the command
};

const RefusedStart kRefusedStarts[] = {
    {"CE_06_IP_01_VpBelowVsForAMove", cmd::kRelativeMove, {.target = 100, .speed = 999}},
    {"CE_R5_IP_13_NegativeRegistrationOffset", cmd::kJogCw, {.target = -5'000, .speed = 10'000}},
    {"CE_R3_IP_11_ExternalActiveWithMinimumDistanceZero",
     cmd::kJogCw,
     {.target = 6'000, .speed = 10'000},
     true},
};

class RefusedStart3602 : public Motion3602, public ::testing::WithParamInterface<RefusedStart> {};

TEST_P(RefusedStart3602, NoStep) {
  const RefusedStart& r = GetParam();
  if (r.external_active) force(kAxis1, InputLine::kExternal, true);
  command(kAxis1, r.command, r.words);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
}

INSTANTIATE_TEST_SUITE_P(Items, RefusedStart3602, ::testing::ValuesIn(kRefusedStarts), RowName{});

// ---- A jog's or registration's word changed while it runs: Command Error + Invalid Profile, and
// an immediate stop (within a few steps) ---------------------------------------------------------

struct ChangeOnTheFly {
  const char* name;
  std::uint16_t jog;
  Move3602 words;  // the jog as started (target: the registration offset)
  unsigned word;   // the MSW of the split value then written
  std::int32_t value;
  bool preset = false;  // Preset Position (0) before the jog
};

const ChangeOnTheFly kChangesOnTheFly[] = {
    {"CE_J2_IP_09_InvalidSpeedChangeWhileJoggingStopsImmediately",
     cmd::kJogCw,
     {.target = 0, .speed = 5'000},
     m2::out_word::kSpeedMsw,
     1'000'001,
     true},
    {"CE_J3_IP_10_OffsetWrittenWhileJoggingStopsImmediately",
     cmd::kJogCcw,
     {.target = 0, .speed = 5'000},
     m2::out_word::kTargetMsw,
     2'000},
    {"CE_R6_IP_14_OffsetChangedDuringRegistration",
     cmd::kJogCw,
     {.target = 6'000, .speed = 10'000},
     m2::out_word::kTargetMsw,
     7'000},
    {"CE_R7_IP_15_SpeedIncreasedDuringRegistration",
     cmd::kJogCw,
     {.target = 6'000, .speed = 10'000},
     m2::out_word::kSpeedMsw,
     12'000},
};

class ChangeOnTheFly3602 : public Motion3602,
                           public ::testing::WithParamInterface<ChangeOnTheFly> {};

TEST_P(ChangeOnTheFly3602, StopsImmediately) {
  const ChangeOnTheFly& r = GetParam();
  if (r.preset) {
    command(kAxis1, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  }
  set_command(kAxis1, r.jog, r.words);
  vm_.run_for(300 * kNsPerMs);
  put_split(kAxis1, r.word, r.value);
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_TRUE(status(kAxis1, kInvalidProfile));
  ASSERT_TRUE(wait_idle(kAxis1, 20 * kNsPerMs));
}

INSTANTIATE_TEST_SUITE_P(Items, ChangeOnTheFly3602, ::testing::ValuesIn(kChangesOnTheFly),
                         RowName{});

// ---- Blend profiles refused when programmed
// ------------------------------------------------------

struct RefusedBlend {
  const char* name;
  std::array<std::int16_t, 6> first;  // segment count, type pairs, final deceleration
  std::vector<std::array<std::int32_t, 3>> segments;  // length, speed, acceleration
  std::uint16_t error;                                // the status MSW bit the profile raises
};

const RefusedBlend kRefusedBlends[] = {
    {"CE_B2_ProfileWithoutFinalDeceleration",
     {2, 0, 0, 0, 0, 0},
     {{1'000, 5'000, 20}, {1'000, 3'000, 20}},
     kCommandError},
    {"IP_04_BlendSegmentCountOutOfRange", {1, 0, 0, 10, 0, 0}, {}, kInvalidProfile},
    {"IP_07_IP_19_AccelerationPairOfBinary10",
     {2, 0, 0b10, 10, 0, 0},  // segment 1: pair 10
     {{1'000, 5'000, 20}, {1'000, 3'000, 20}},
     kInvalidProfile},
    {"IP_06_ConsecutiveSegmentsWithTheSameSpeed",
     {2, 0, 0, 10, 0, 0},
     {{20'000, 5'000, 20}, {20'000, 5'000, 20}},
     kInvalidProfile},
    {"IP_05_SegmentTooShortToReachItsSpeed",
     {2, 0, 0, 10, 0, 0},
     {{100, 50'000, 1}, {20'000, 5'000, 20}},
     kInvalidProfile},
};

class RefusedBlend3602 : public Motion3602, public ::testing::WithParamInterface<RefusedBlend> {};

TEST_P(RefusedBlend3602, ErrorBitSet) {
  const RefusedBlend& r = GetParam();
  std::vector<std::array<std::int16_t, 6>> blocks{r.first};
  for (const auto& [length, speed, accel] : r.segments) {
    blocks.push_back(segment(length, speed, static_cast<std::int16_t>(accel)));
  }
  program_blend(kAxis1, blocks);
  EXPECT_TRUE(status(kAxis1, r.error));
}

INSTANTIATE_TEST_SUITE_P(Items, RefusedBlend3602, ::testing::ValuesIn(kRefusedBlends), RowName{});

}  // namespace
}  // namespace stepmod::testing
