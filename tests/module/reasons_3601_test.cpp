// 3601 error reasons (docs/error-reasons.md): each error bit a module sets comes with the checklist
// item that set it and a sentence, kept per axis and published with the input image. At least
// one test per error list (CFG, CE, IP, IE, HI, PI) of each module, named after the item.
#include <gtest/gtest.h>

#include "module/axis/error_items.hpp"
#include "tests/module/plc_3601.hpp"
#include "tests/module/reasons_rig.hpp"

namespace stepmod::testing {
namespace {

// ---- 3601 --------------------------------------------------------------------------------------

using Reasons3601 = ReasonsRig<Plc3601>;

TEST_F(Reasons3601, CFG_01_PowerUpHasItsReason) {
  vm_.scans(2);
  EXPECT_EQ(reason().code, 10101u);
  EXPECT_EQ(text(reason()), "3601-CFG-01: not configured since power-up");
}

TEST_F(Reasons3601, CFG_03_NoEndLimitNamesItsItem) {
  configure(m::cfg_msw::kHomeUsed | m::cfg_msw::kStepDirOutput);
  EXPECT_TRUE(status(m::status_msw::kConfigurationError));
  EXPECT_EQ(reason().code, 10103u);
  EXPECT_EQ(text(reason()), "3601-CFG-03: neither CW nor CCW end limit configured");
}

TEST_F(Reasons3601, CE_05_VpBelowVsNamesBothSpeeds) {
  configure();
  const std::uint32_t seq = reason().seq;
  command(m::cmd_msw::kRelativeMove, {.target = 100, .speed = 500});
  EXPECT_TRUE(status(m::status_msw::kCommandError));
  EXPECT_TRUE(status(m::status_msw::kInvalidProfile));
  EXPECT_EQ(reason().seq, seq + 1);
  EXPECT_EQ(reason().code, 10205u);
  EXPECT_EQ(text(reason()), "3601-CE-05: Vp 500 is below Vs 1000");
}

// stepmod's own: the manual only says the module must be configured before any operation.
TEST_F(Reasons3601, CE_S2_MoveBeforeConfigurationNamesItsItem) {
  vm_.scans(2);
  command(m::cmd_msw::kRelativeMove, {.target = 100});
  EXPECT_TRUE(status(m::status_msw::kCommandError));
  EXPECT_EQ(reason().code, 10292u);
  EXPECT_EQ(text(reason()), "3601-CE-S2: not configured: configure the axis first");
}

// A jog's target changed while it runs: the move stops with its own item, not the list's.
TEST_F(Reasons3601, CE_30_TargetWrittenIntoARunningJog) {
  configure();
  set_words(m::cmd_msw::kManualCw, 0, 0, 10'000, 10, 10);
  vm_.run_for(100 * kNsPerMs);
  set_words(m::cmd_msw::kManualCw, 0, 500, 10'000, 10, 10);
  vm_.scans(2);
  EXPECT_TRUE(status(m::status_msw::kCommandError));
  EXPECT_EQ(reason().code, 10230u);
  EXPECT_EQ(text(reason()), "3601-CE-30: a target written while a jog runs");
}

// 3601-HI-02 (A8: Command Error as well): the reason names the manual's item, Home Invalid's.
TEST_F(Reasons3601, HI_02_FindHomeWithATargetNamesTheHomeInvalidItem) {
  configure();
  command(m::cmd_msw::kFindHomeCw, {.target = 300});
  EXPECT_TRUE(status(m::status_msw::kCommandError));
  EXPECT_TRUE(status(m::status_msw::kHomeInvalid));
  EXPECT_EQ(reason().code, 10502u);
  EXPECT_EQ(text(reason()), "3601-HI-02: Find Home with a target 300 (must be 0)");
}

TEST_F(Reasons3601, CE_L1_ReasonSurvivesResetErrorsAndIgnoredCommands) {
  configure();
  command(m::cmd_msw::kRelativeMove, {.target = 100, .speed = 500});
  const ErrorReason r = reason();
  command(m::cmd_msw::kHold);  // ignored while CE is set: no new reason
  EXPECT_EQ(reason(), r);
  command(m::cmd_msw::kResetErrors, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_FALSE(status(m::status_msw::kCommandError));
  EXPECT_EQ(reason(), r);  // docs/interface.md 3.4: kept until the next one
}

TEST_F(Reasons3601, IP_04_BlendSegmentCountNamesTheCount) {
  configure();
  plc::BlendProfile one;
  one.segments = {{10'000, 5'000, 10, plc::AccelType::kConstant}};
  one.final_decel = 10;
  const plc::Outcome o = plc_.blend_program(one);
  EXPECT_FALSE(o.ok);
  EXPECT_TRUE(status(m::status_msw::kInvalidProfile));
  EXPECT_EQ(reason().code, 10304u);
  EXPECT_EQ(text(reason()), "3601-IP-04: 1 blend segments (2..16)");
}

TEST_F(Reasons3601, IE_02_LimitDuringAMoveNamesTheLimit) {
  configure();
  command(m::cmd_msw::kRelativeMove, {.target = 50'000});
  vm_.run_for(200 * kNsPerMs);
  force(InputLine::kCwLimit, true);
  vm_.scans(3);
  EXPECT_TRUE(status(m::status_msw::kInputError));
  EXPECT_EQ(reason().code, 10402u);
  EXPECT_EQ(text(reason()).rfind("3601-IE-02: CW limit active: stopped at ", 0), 0u)
      << text(reason());
}

TEST_F(Reasons3601, HI_05_OppositeLimitFirstIsAHomingReason) {
  configure();
  command(m::cmd_msw::kFindHomeCw, {.target = 0, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(200 * kNsPerMs);
  force(InputLine::kCcwLimit, true);
  vm_.scans(3);
  EXPECT_TRUE(status(m::status_msw::kHomeInvalid));
  EXPECT_EQ(reason().code, 10505u);
  EXPECT_EQ(text(reason()).rfind("3601-HI-05: homing: the wrong limit active", 0), 0u)
      << text(reason());
}

TEST_F(Reasons3601, PI_02_ImmediateStopWhileMoving) {
  configure();
  command(m::cmd_msw::kRelativeMove, {.target = 50'000});
  vm_.run_for(200 * kNsPerMs);
  command(m::cmd_msw::kImmediateStop);
  EXPECT_TRUE(status(m::status_msw::kPositionInvalid));
  EXPECT_EQ(reason().code, 10602u);
  EXPECT_EQ(text(reason()).rfind("3601-PI-02: stopped at ", 0), 0u) << text(reason());
}

TEST_F(Reasons3601, PI_07_PlcLeavingRunModeWhileMoving) {
  configure();
  command(m::cmd_msw::kRelativeMove, {.target = 50'000});
  vm_.run_for(100 * kNsPerMs);
  vm_.stack().personality().plc_stopped(vm_.now());
  EXPECT_EQ(reason().code, 10607u);
  EXPECT_EQ(text(reason()), "3601-PI-07: the PLC left Run mode while moving");
  ASSERT_TRUE(wait_idle());
  vm_.stack().personality().stop_every_axis(module::axis::items::kPiLeaseExpired, vm_.now());
  EXPECT_EQ(reason().code, 10607u) << "idle now: nothing new";
}

// stepmod's own: the daemon lost an input edge (a kernel line FIFO overflowed) while moving.
TEST_F(Reasons3601, PI_S3_InputEdgeLostWhileMoving) {
  configure();
  command(m::cmd_msw::kRelativeMove, {.target = 50'000});
  vm_.run_for(100 * kNsPerMs);
  vm_.stack().personality().stop_every_axis(module::axis::items::kPiInputLost, vm_.now());
  EXPECT_TRUE(status(m::status_msw::kPositionInvalid));
  EXPECT_EQ(reason().code, 10693u);
  EXPECT_EQ(text(reason()), "3601-PI-S3: an input edge was lost (stepmod)");
}

}  // namespace
}  // namespace stepmod::testing
