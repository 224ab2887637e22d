// The rules the three manuals share, tested once on the shared axis and run for each module
// type's ModuleRules (3601, 3602, 3202): a module inherits them by using module/axis/. Test names
// carry the 3601 checklist id of the rule; the 3602 and 3202 lists state the same rule under their
// own ids (their "Latch rules as on the 3601"; mode changes and the command handshake: manuals
// 3601/3202 ch. 3-4, 3602 ch. 8-9).
#include <ostream>

#include "registry/module_registry.hpp"
#include "tests/module/axis_rig.hpp"

namespace stepmod {
// GoogleTest prints the parameter into the test names ctest lists: the type number, not bytes.
inline void PrintTo(ModuleType t, std::ostream* os) {
  *os << static_cast<unsigned>(t);
}
}  // namespace stepmod

namespace stepmod::testing {
namespace {

using ax::CommandKind;

class AxisShared : public ::testing::TestWithParam<ModuleType> {
 protected:
  AxisShared() : rig_(*registry::row_of(GetParam()).rules) {}
  const ax::ModuleRules& rules() const { return *registry::row_of(GetParam()).rules; }
  AxisRig rig_;
};

// Command handshake (manuals 3601/3202 ch. 4, 3602 ch. 9): a command fires on its 0->1 edge, once;
// a relative move outputs exactly its steps and ends with Move Complete (3601-MC-01).
TEST_P(AxisShared, MC_01_RelativeMoveOutputsExactlyItsStepsOnce) {
  rig_.configure();
  rig_.hold(CommandKind::kRelativeMove, {.target = 3'000});
  ASSERT_TRUE(rig_.run_until_true([this] { return rig_.status().move_complete; }, 10 * kNsPerSec));
  EXPECT_EQ(rig_.motor(), 3'000);
  EXPECT_EQ(rig_.status().position, 3'000);
  // Still held: no new edge, no second move.
  rig_.scans(50);
  EXPECT_EQ(rig_.motor(), 3'000);
  rig_.clear();
  rig_.scans(1);
  rig_.command(CommandKind::kRelativeMove, {.target = 1'000});
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.motor(), 4'000);
}

// 3601-MC-01 and DIR-01 in one scan's status: the scan that clears the moving bits sets Move
// Complete. Here the move's last edge goes out while the control thread is held off between its
// scan and its status (a loaded machine). A status that took "moving" from that later instant and
// the outcome from the scan's start showed one scan with neither, and a PLC that waits for the
// moving bits to clear and then reads Move Complete took the move for one that did not complete.
TEST_P(AxisShared, MC_01_DIR_01_TheScanThatClearsTheMovingBitsSetsMoveComplete) {
  rig_.configure();
  rig_.preempt_between_scan_and_status(AxisRig::kScan - kNsPerUs);
  for (const std::int32_t target : {2'000, -1'500, 777}) {
    rig_.command(CommandKind::kRelativeMove, {.target = target});
    ASSERT_TRUE(rig_.moving()) << target;
    ASSERT_TRUE(rig_.run_until_true([this] { return !rig_.moving(); }, 10 * kNsPerSec));
    EXPECT_TRUE(rig_.status().move_complete) << target;
    // 3601/3202-STP-N1: a completed move is not Stopped (the 3602's Stopped is "idle", STP-01).
    EXPECT_EQ(rig_.status().stopped, rules().stopped_means_idle) << target;
  }
  EXPECT_EQ(rig_.motor(), 2'000 - 1'500 + 777);
}

// 3601-CE-02 (3202/3602: "more than one command bit"): several commands at once are a Command
// Error and nothing moves.
TEST_P(AxisShared, CE_02_SeveralCommandsAtOnce) {
  rig_.configure();
  rig_.image().commands.set(CommandKind::kRelativeMove);
  rig_.image().commands.set(CommandKind::kAbsoluteMove);
  rig_.image().target = 1'000;
  rig_.image().speed = 10'000;
  rig_.image().accel = rig_.image().decel = 10'000;
  rig_.scans(3);
  EXPECT_TRUE(rig_.status().command_error);
  rig_.run_for(100 * kNsPerMs);
  EXPECT_EQ(rig_.motor(), 0);
}

// 3601-CE-03: a move while another is in progress is refused; the running move is unaffected.
TEST_P(AxisShared, CE_03_MoveWhileMovingIsRefused) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 10'000});
  rig_.command(CommandKind::kRelativeMove, {.target = 500});
  EXPECT_TRUE(rig_.status().command_error);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.motor(), 10'000);
}

// 3601-CE-L1 / CE-L2 (3602, 3202: "as 3601"): while CE is set every command but Reset Errors is
// ignored, Immediate Stop included; Reset Errors clears CE, and a command then needs a new edge.
TEST_P(AxisShared, CE_L1_CE_L2_OnlyResetErrorsWhileCommandError) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 20'000});
  rig_.command(CommandKind::kResume);  // not in Hold: CE, the move goes on
  ASSERT_TRUE(rig_.status().command_error);
  rig_.command(CommandKind::kImmediateStop);
  EXPECT_TRUE(rig_.moving());
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.motor(), 20'000);
  rig_.command(CommandKind::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(rig_.status().command_error);
  rig_.command(CommandKind::kRelativeMove, {.target = 100});
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.motor(), 20'100);
}

// 3202-CE-05 / IP-03 / HI-04: a module's reserved command words not 0 (the dialect's
// AxisCommand::reserved_words_nonzero) refuse the command with CE + IP, and HI for a homing;
// nothing moves. Modules without such words never set the flag, so the rule is inert for them.
TEST_P(AxisShared, CE_05_IP_03_HI_04_ReservedWordsNotZero) {
  rig_.configure();
  rig_.image().reserved_words_nonzero = true;
  rig_.command(CommandKind::kRelativeMove, {.target = 100});
  EXPECT_TRUE(rig_.status().command_error);
  EXPECT_TRUE(rig_.status().invalid_profile);
  EXPECT_FALSE(rig_.status().home_invalid);
  rig_.image().reserved_words_nonzero = true;
  rig_.command(CommandKind::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  EXPECT_TRUE(rig_.status().command_error);  // Reset Errors too is refused with them
  rig_.image().reserved_words_nonzero = false;
  rig_.command(CommandKind::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  ASSERT_FALSE(rig_.status().command_error);
  rig_.image().reserved_words_nonzero = true;
  rig_.command(CommandKind::kFindHomeCw, {.target = 0});
  EXPECT_TRUE(rig_.status().home_invalid);
  rig_.run_for(100 * kNsPerMs);
  EXPECT_EQ(rig_.motor(), 0);
}

// A whole blend profile at once (Axis::program_blend, the 3202's message, 3202 manual ch. 5): the
// block cycle's checks; stored only when valid, runs the sum of its lengths; refused with IP and
// nothing stored otherwise; refused before the axis is configured (3202-IP-15).
TEST_P(AxisShared, BlendProgrammedAtOnceChecksStoresAndRuns) {
  ax::BlendFirstBlock first;
  first.segments = 2;
  first.final_shape = planner::AccelShape::kConstant;
  first.final_decel = 100'000;
  std::array<ax::BlendSegmentBlock, 2> segs{};
  segs[0].length = 6'000;
  segs[0].speed = 5'000;
  segs[0].rate = 100'000;
  segs[1].length = 4'000;
  segs[1].speed = 2'000;
  segs[1].rate = 100'000;
  EXPECT_FALSE(rig_.axis().program_blend(first, segs));  // not configured
  rig_.scans(1);
  EXPECT_TRUE(rig_.status().invalid_profile);
  rig_.configure();
  EXPECT_TRUE(rig_.axis().program_blend(first, segs));
  rig_.command(CommandKind::kRunBlendCw, {.speed = 0, .accel = 0, .decel = 0});
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.motor(), 10'000);
  EXPECT_TRUE(rig_.status().move_complete);
  // Same speed twice: refused, and the earlier profile is gone too (the manuals' blend
  // rules: 3601/3202 ch. 4-5, 3602 ch. 9).
  segs[1].speed = 5'000;
  EXPECT_FALSE(rig_.axis().program_blend(first, segs));
  rig_.scans(1);
  EXPECT_TRUE(rig_.status().invalid_profile);
  rig_.command(CommandKind::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  rig_.command(CommandKind::kRunBlendCw, {.speed = 0, .accel = 0, .decel = 0});
  EXPECT_TRUE(rig_.status().command_error);
  rig_.run_for(100 * kNsPerMs);
  EXPECT_EQ(rig_.motor(), 10'000);
}

// 3202-CE-07 (3202 manual Ch.4 "Hold Move" note 2): Hold during the deceleration of a move is
// ignored on the 3202; the 3601 and 3602 hold (rules.hpp hold_ignored_while_decelerating).
TEST_P(AxisShared, CE_07_HoldDuringTheDecelerationPerModule) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 12'000});
  ASSERT_TRUE(rig_.run_until_true([this] { return rig_.status().decelerating; }, 10 * kNsPerSec));
  rig_.command(CommandKind::kHold);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_FALSE(rig_.status().command_error);
  if (rules().hold_ignored_while_decelerating) {
    EXPECT_FALSE(rig_.status().hold);
    EXPECT_TRUE(rig_.status().move_complete);
    EXPECT_EQ(rig_.motor(), 12'000);
  } else {
    EXPECT_TRUE(rig_.status().hold);
    EXPECT_FALSE(rig_.status().move_complete);
  }
}

// 3601-CE-04 / IP-02: a speed or rate outside the module's range (rules.hpp) is refused with CE
// and Invalid Profile.
TEST_P(AxisShared, CE_04_IP_02_OutOfRangeParameters) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 100, .speed = rules().speed_max + 1});
  EXPECT_TRUE(rig_.status().command_error);
  EXPECT_TRUE(rig_.status().invalid_profile);
  rig_.command(CommandKind::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  rig_.command(CommandKind::kRelativeMove, {.target = 100, .accel = rules().accel_max + 1});
  EXPECT_TRUE(rig_.status().invalid_profile);
  rig_.command(CommandKind::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
  rig_.command(CommandKind::kRelativeMove, {.target = rules().target_max});
  EXPECT_FALSE(rig_.status().command_error);  // the largest target is accepted
  EXPECT_TRUE(rig_.moving());
  rig_.command(CommandKind::kImmediateStop);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.status().position, rig_.motor());
}

// 3601-CE-01 (7.15): configuration requested while moving: CE, the move finishes, then the axis
// enters configuration mode and CE clears.
TEST_P(AxisShared, CE_01_ConfigurationRequestWhileMovingFinishesTheMoveFirst) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 10'000});
  rig_.image().configuration_mode = true;
  rig_.scans(3);
  EXPECT_TRUE(rig_.status().command_error);
  EXPECT_FALSE(rig_.status().configuration_mode);
  ASSERT_TRUE(
      rig_.run_until_true([this] { return rig_.status().configuration_mode; }, 10 * kNsPerSec));
  EXPECT_EQ(rig_.motor(), 10'000);
  EXPECT_FALSE(rig_.status().command_error);
}

// 3601-CFG-13 / PI-01 (7.15): a valid configuration clears CfgE; back in command mode the
// position is 0 and invalid. An invalid one leaves CfgE set and commands are refused.
TEST_P(AxisShared, CFG_13_PI_01_ConfigurationZeroesAndInvalidatesThePosition) {
  rig_.configure();
  rig_.command(CommandKind::kPresetPosition, {.target = 1'234, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(rig_.status().position, 1'234);
  EXPECT_FALSE(rig_.status().position_invalid);
  rig_.configure();
  EXPECT_FALSE(rig_.status().configuration_error);
  EXPECT_EQ(rig_.status().position, 0);
  EXPECT_TRUE(rig_.status().position_invalid);
  rig_.configure(std::nullopt);
  EXPECT_TRUE(rig_.status().configuration_error);
  rig_.command(CommandKind::kRelativeMove, {.target = 100});
  EXPECT_TRUE(rig_.status().command_error);
  rig_.run_for(100 * kNsPerMs);
  EXPECT_EQ(rig_.motor(), 0);
}

// Issue 12 item 3 (7.15/7.16): a command in the image that leaves configuration mode is a 0->1
// edge (the configuration words are not command words) and acts.
TEST_P(AxisShared, CFG_13_CommandInTheImageThatLeavesConfigurationModeActs) {
  rig_.configure();  // ends in command mode; configure again, leaving with a command
  rig_.image().configuration_mode = true;
  rig_.scans(3);
  ASSERT_TRUE(rig_.status().configuration_mode);
  rig_.hold(CommandKind::kRelativeMove, {.target = 2'000});
  rig_.image().configuration_mode = false;
  ASSERT_TRUE(rig_.run_until_true([this] { return rig_.status().move_complete; }, 10 * kNsPerSec));
  EXPECT_EQ(rig_.motor(), 2'000);
  EXPECT_FALSE(rig_.status().command_error);
}

// 3601-HLD-01 / HLD-C1: Hold is a controlled stop to the Hold state; Resume goes on to the held
// target with the parameters given now.
TEST_P(AxisShared, HLD_01_HoldThenResumeReachesTheTarget) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 30'000});
  rig_.run_for(300 * kNsPerMs);
  rig_.command(CommandKind::kHold);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_TRUE(rig_.status().hold);
  EXPECT_FALSE(rig_.status().move_complete);
  EXPECT_LT(rig_.motor(), 30'000);
  rig_.command(CommandKind::kResume, {.speed = 20'000});
  ASSERT_TRUE(rig_.run_until_true([this] { return rig_.status().move_complete; }, 10 * kNsPerSec));
  EXPECT_FALSE(rig_.status().hold);
  EXPECT_EQ(rig_.motor(), 30'000);
}

// 3601-PI-02: Immediate Stop ends a move at once and invalidates the position; the reported
// position still counts every step output.
TEST_P(AxisShared, PI_02_ImmediateStopInvalidatesThePosition) {
  rig_.configure();
  rig_.command(CommandKind::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  rig_.command(CommandKind::kRelativeMove, {.target = 50'000});
  rig_.run_for(200 * kNsPerMs);
  rig_.command(CommandKind::kImmediateStop);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_TRUE(rig_.status().position_invalid);
  EXPECT_FALSE(rig_.status().move_complete);
  EXPECT_EQ(rig_.status().position, rig_.motor());
  EXPECT_LT(rig_.motor(), 50'000);
}

// 3601-IE-01 / PI-03 / STP-02: the E-stop during a move: immediate stop, Input Error, Position
// Invalid; no move starts while it is active (A15).
TEST_P(AxisShared, IE_01_EStopStopsTheMoveAndBlocksTheNext) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 50'000});
  rig_.run_for(200 * kNsPerMs);
  rig_.force(InputLine::kEStop, true);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_TRUE(rig_.status().input_error);
  EXPECT_TRUE(rig_.status().position_invalid);
  const std::int64_t at = rig_.motor();
  rig_.command(CommandKind::kRelativeMove, {.target = 100});
  rig_.run_for(100 * kNsPerMs);
  EXPECT_EQ(rig_.motor(), at);
  EXPECT_TRUE(rig_.status().input_error);
}

// ---- What differs between the manuals, as data -----------------------------------------------

// Power-up: 3601/3602 report CfgE until configured; the 3202 does not (it powers up disabled).
TEST_P(AxisShared, CFG_01_PowerUpConfigurationErrorPerModule) {
  rig_.scans(2);
  EXPECT_EQ(rig_.status().configuration_error, rules().powers_up_with_configuration_error);
  EXPECT_FALSE(rig_.status().configuration_mode);
}

// 3601-MC-03 vs 3602-MC-02: Preset Position leaves Move Complete on the 3601 and 3202 and clears
// it on the 3602.
TEST_P(AxisShared, MC_03_PresetPositionAndMoveCompletePerModule) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 500});
  ASSERT_TRUE(rig_.wait_idle());
  ASSERT_TRUE(rig_.status().move_complete);
  rig_.command(CommandKind::kPresetPosition, {.target = 7, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(rig_.status().position, 7);
  EXPECT_EQ(rig_.status().move_complete, !rules().preset_clears_move_complete);
}

// Stopped: an event bit on the 3601/3202 (3601-STP-N1: not after a completed move; 3601-STP-03:
// after an Immediate Stop), "idle in command mode" on the 3602 (3602-STP-01).
TEST_P(AxisShared, STP_03_StoppedMeaningPerModule) {
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 500});
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.status().stopped, rules().stopped_means_idle);
  rig_.command(CommandKind::kRelativeMove, {.target = 50'000});
  EXPECT_FALSE(rig_.status().stopped);  // moving
  rig_.command(CommandKind::kImmediateStop);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_TRUE(rig_.status().stopped);
}

// 3601-CE-13 / HI-03 vs the 3602: a home command needs the end limit in its own direction on
// the 3601 and 3202; the 3602 needs only the home input.
TEST_P(AxisShared, CE_13_HomingPrerequisitePerModule) {
  ax::AxisConfig cfg = full_axis_config();
  cfg.inputs_used &=
      static_cast<std::uint16_t>(~(1u << static_cast<unsigned>(InputLine::kCwLimit)));
  rig_.configure(cfg);
  rig_.command(CommandKind::kFindHomeCw, {.target = 0, .speed = 5'000});
  if (rules().homing_needs_limit_ahead) {
    EXPECT_TRUE(rig_.status().command_error);
    EXPECT_TRUE(rig_.status().home_invalid);
    EXPECT_FALSE(rig_.moving());
  } else {
    EXPECT_FALSE(rig_.status().command_error);
    EXPECT_TRUE(rig_.moving());
  }
}

// 3601-CE-27 / IP-12 vs the 3602: the External input active when a registration move starts is
// always an error on the 3601, on the 3602 only with a minimum registration distance of 0. The
// 3202 has no registration move.
TEST_P(AxisShared, CE_27_RegistrationWithExternalActivePerModule) {
  if (!rules().has_registration) GTEST_SKIP() << "no registration move on this module";
  rig_.configure();
  // Store a minimum registration distance of 500 (the store flag rising, no command set).
  rig_.image().store_min_registration = true;
  rig_.image().target = 500;
  rig_.image().speed = 0;
  rig_.image().accel = rig_.image().decel = 0;
  rig_.scans(3);
  rig_.image() = ax::AxisCommand{};
  rig_.scans(1);
  ASSERT_TRUE(rig_.status().min_registration_set);
  ASSERT_FALSE(rig_.status().command_error);
  rig_.force(InputLine::kExternal, true);
  rig_.scans(1);
  rig_.hold(CommandKind::kManualCw, {.target = 6'000});
  rig_.scans(3);
  if (rules().registration_external_always_error) {
    EXPECT_TRUE(rig_.status().command_error);
    EXPECT_TRUE(rig_.status().invalid_profile);
    EXPECT_FALSE(rig_.moving());
  } else {
    EXPECT_FALSE(rig_.status().command_error);
    EXPECT_TRUE(rig_.moving());
    // The input, active from the start, is honoured at step Dmin + 1 (A42), then exactly R.
    ASSERT_TRUE(rig_.wait_idle());
    EXPECT_EQ(rig_.motor(), 500 + 1 + 6'000);
    EXPECT_TRUE(rig_.status().stopped);
  }
}

// A19 (3602 config MSW bit 14, 3202 bit 28): a disabled axis ignores every command and stays
// idle, without a Command Error. The 3601 has no disable bit: its dialect never sets the flag.
TEST_P(AxisShared, EN_01_DisabledAxisIgnoresCommandsPerModule) {
  if (!rules().has_disable) GTEST_SKIP() << "no disable bit on this module";
  ax::AxisConfig cfg = full_axis_config();
  cfg.disabled = true;
  rig_.configure(cfg);
  rig_.command(CommandKind::kRelativeMove, {.target = 500});
  rig_.hold(CommandKind::kManualCw, {.target = 0, .speed = 2'000});
  rig_.scans(100);
  rig_.clear();
  rig_.command(CommandKind::kAbsoluteMove, {.target = 50});
  rig_.scans(20);
  EXPECT_EQ(rig_.motor(), 0);
  EXPECT_FALSE(rig_.moving());
  EXPECT_FALSE(rig_.status().command_error);
  // Enabled again by a new configuration, the same move runs.
  rig_.configure();
  rig_.command(CommandKind::kRelativeMove, {.target = 500});
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.motor(), 500);
}

// 3602 (3602 manual table 8.2, 3602-IE-01 / PI-03): a CW / CCW input configured as an E-stop stops
// a move in either direction (IE, PI) and blocks the next; configured unused it does nothing. The
// 3601 and 3202 inputs are always end limits (their dialects leave the function at kLimit).
TEST_P(AxisShared, IE_01_CwInputConfiguredAsEStopPerModule) {
  if (!rules().cw_ccw_inputs_configurable) GTEST_SKIP() << "CW/CCW inputs are always limits";
  ax::AxisConfig cfg = full_axis_config();
  cfg.inputs_used &= static_cast<std::uint16_t>(~(1u << static_cast<unsigned>(InputLine::kEStop)));
  cfg.cw_input = ax::LimitFunction::kEStop;
  cfg.ccw_input = ax::LimitFunction::kUnused;
  cfg.inputs_used &=
      static_cast<std::uint16_t>(~(1u << static_cast<unsigned>(InputLine::kCcwLimit)));
  rig_.configure(cfg);
  // The unused CCW input: a CCW move runs through its activation.
  rig_.command(CommandKind::kRelativeMove, {.target = -3'000});
  rig_.run_for(100 * kNsPerMs);
  rig_.force(InputLine::kCcwLimit, true);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_EQ(rig_.motor(), -3'000);
  EXPECT_FALSE(rig_.status().input_error);
  // The CW input as an E-stop stops a CCW move: not a limit "in its direction" but an E-stop.
  rig_.command(CommandKind::kRelativeMove, {.target = -50'000});
  rig_.run_for(200 * kNsPerMs);
  rig_.force(InputLine::kCwLimit, true);
  ASSERT_TRUE(rig_.wait_idle());
  EXPECT_TRUE(rig_.status().input_error);
  EXPECT_TRUE(rig_.status().position_invalid);
  EXPECT_GT(rig_.motor(), -50'000);
  const std::int64_t at = rig_.motor();
  // A15: no move starts, in either direction, while it is active.
  rig_.command(CommandKind::kRelativeMove, {.target = -100});
  rig_.run_for(100 * kNsPerMs);
  EXPECT_EQ(rig_.motor(), at);
  EXPECT_TRUE(rig_.status().input_error);
}

// 3602-HI-07 (A16): a homing still running T s after its command stops (controlled) with Home
// Invalid; modules without a homing timeout never set one (their dialects leave T = 0).
TEST_P(AxisShared, HI_07_HomingTimeoutPerModule) {
  if (!rules().has_homing_timeout) GTEST_SKIP() << "no homing timeout on this module";
  ax::AxisConfig cfg = full_axis_config();
  cfg.homing_timeout = kNsPerSec;
  rig_.configure(cfg);
  rig_.command(CommandKind::kFindHomeCw, {.target = 0, .speed = 1'500});
  rig_.run_for(800 * kNsPerMs);
  EXPECT_TRUE(rig_.moving());
  EXPECT_FALSE(rig_.status().home_invalid);
  ASSERT_TRUE(rig_.wait_idle(3 * kNsPerSec));
  EXPECT_TRUE(rig_.status().home_invalid);
  EXPECT_FALSE(rig_.status().at_home);
  const std::int64_t at = rig_.motor();
  rig_.run_for(3 * kNsPerSec);
  EXPECT_EQ(rig_.motor(), at);
}

// Find Home with S-curve: CE everywhere (3601-CE-10, 3602-CE-11), HI on the 3602 (3602-HI-02).
TEST_P(AxisShared, CE_10_HomingWithSCurvePerModule) {
  rig_.configure();
  rig_.image().shape = planner::AccelShape::kTriangularS;
  rig_.command(CommandKind::kFindHomeCw, {.target = 0, .speed = 5'000});
  EXPECT_TRUE(rig_.status().command_error);
  EXPECT_EQ(rig_.status().home_invalid, rules().homing_s_curve_sets_home_invalid);
  rig_.scans(20);
  EXPECT_EQ(rig_.motor(), 0);
}

// 3602-HI-06: the home input and an end limit active together during homing is a homing error
// on the 3602; on the 3601 / 3202 the limit ahead is the H-C reversal, no error.
TEST_P(AxisShared, HI_06_HomeWithLimitDuringHomingPerModule) {
  rig_.configure();
  rig_.command(CommandKind::kFindHomeCw, {.target = 0, .speed = 5'000});
  rig_.run_for(100 * kNsPerMs);
  rig_.force(InputLine::kHome, true);
  rig_.scans(2);
  rig_.force(InputLine::kCwLimit, true);
  rig_.scans(5);
  EXPECT_EQ(rig_.status().home_invalid, rules().homing_home_with_limit_is_error);
}

// 3601-AH-01 (3202 alike): a completed homing zeroes the position and the encoder as of one
// instant. Input events reach the control thread some time after the pulse thread has reported
// the motion's end (a loaded machine): the A/B edges of the last steps, delivered after the zero,
// are motion of before it and must not count after it.
TEST_P(AxisShared, AH_01_EncoderEdgesDeliveredAfterTheHomingsEndDoNotCountPastTheZero) {
  if (!rules().has_encoder) GTEST_SKIP() << "no encoder input on this module";
  rig_.configure();
  rig_.delay_inputs(3'500 * kNsPerUs);
  rig_.command(CommandKind::kFindHomeCw, {.target = 0, .speed = 5'000});
  ASSERT_TRUE(rig_.run_until_true([this] { return rig_.status().at_home; }, 30 * kNsPerSec));
  const std::int64_t rest = rig_.motor();
  rig_.scans(20);  // every event delivered
  EXPECT_EQ(rig_.motor(), rest);
  EXPECT_EQ(rig_.status().position, 0);
  EXPECT_EQ(rig_.status().encoder, 0);
  // The home edge came late too: the creep went a few steps past it, and the zero is there.
  EXPECT_GT(rest, 5'000);
}

std::string module_name(const ::testing::TestParamInfo<ModuleType>& info) {
  return std::to_string(static_cast<unsigned>(info.param));
}

INSTANTIATE_TEST_SUITE_P(Modules, AxisShared, ::testing::ValuesIn(kModuleTypes), module_name);

}  // namespace
}  // namespace stepmod::testing
