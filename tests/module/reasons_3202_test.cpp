// 3202 error reasons (docs/error-reasons.md): each error bit a module sets comes with the checklist
// item that set it and a sentence, kept per axis and published with the input image. At least
// one test per error list (CFG, CE, IP, IE, HI, PI) of each module, named after the item.
#include <gtest/gtest.h>

#include "ipc/stepmod_image.h"
#include "module_types/m3202/blend_message_3202.hpp"
#include "tests/module/plc_3202.hpp"
#include "tests/module/reasons_rig.hpp"

namespace stepmod::testing {
namespace {

// ---- 3202 --------------------------------------------------------------------------------------

using Reasons3202 = ReasonsRig<Plc3202>;

TEST_F(Reasons3202, CFG_09_ReservedBitNamesItsItem) {
  configure(0, kFull3202 | (1u << 7));  // bit 7 reserved; CFG-08 is old firmware's only
  EXPECT_TRUE(status(0, m2::status_bit::kConfigurationError));
  EXPECT_EQ(reason(0).code, 30109u);
}

TEST_F(Reasons3202, CE_04_VpBelowVs) {
  configure(0);
  command(0, m2::cmd_bit::kRelativeMove, {.target = 100, .speed = 999});
  EXPECT_EQ(reason(0).code, 30204u);
  EXPECT_EQ(text(reason(0)), "3202-CE-04: Vp 999 is below Vs 1000");
}

// A channel never configured is disabled and ignores commands (3202-DIS-01); after an invalid
// configuration it refuses them.
TEST_F(Reasons3202, CE_S2_MoveBeforeConfigurationNamesItsItem) {
  configure(1, kFull3202 | (1u << 7));  // 3202-CFG-09: not configured
  command(1, m2::cmd_bit::kRelativeMove, {.target = 100});
  EXPECT_TRUE(status(1, m2::status_bit::kCommandError));
  EXPECT_EQ(reason(1).code, 30292u);
  EXPECT_EQ(text(reason(1)), "3202-CE-S2: not configured: configure the axis first");
}

// The 3202 states it (Ch.4, the moves' note 2) without numbering it in its list: stepmod's S3.
TEST_F(Reasons3202, CE_S3_MoveWhileAnotherRuns) {
  configure(0);
  command(0, m2::cmd_bit::kRelativeMove, {.target = 50'000});
  command(0, m2::cmd_bit::kAbsoluteMove, {.target = 100});
  EXPECT_TRUE(status(0, m2::status_bit::kCommandError));
  EXPECT_EQ(reason(0).code, 30293u);
  EXPECT_EQ(text(reason(0)), "3202-CE-S3: a move while a motion is running");
}

// No registration on the 3202: a manual move with a target is 3202-CE-12 (IP-07 also).
TEST_F(Reasons3202, CE_12_ManualMoveWithATarget) {
  configure(0);
  command(0, m2::cmd_bit::kManualCw, {.target = -300});
  EXPECT_TRUE(status(0, m2::status_bit::kInvalidProfile));
  EXPECT_EQ(reason(0).code, 30212u);
  EXPECT_EQ(text(reason(0)), "3202-CE-12: manual move with target -300 (must be 0)");
}

TEST_F(Reasons3202, IP_15_BlendMessageBeforeTheChannelIsConfigured) {
  std::array<std::int32_t, STEPMOD_MSG_DINTS> msg{};
  msg[m2::msg_dint::kChannel] = 2;
  EXPECT_NE(vm_.stack().personality().on_message(msg, vm_.now()), m2::kMessageAccepted);
  EXPECT_EQ(reason(1).code, 30315u);
  EXPECT_EQ(reason(0).seq, 0u);  // channel 1 untouched (powers up without an error)
}

TEST_F(Reasons3202, IE_02_LimitDuringAMove) {
  configure(0);
  command(0, m2::cmd_bit::kRelativeMove, {.target = 50'000});
  vm_.run_for(200 * kNsPerMs);
  force(0, InputLine::kCwLimit, true);
  vm_.scans(3);
  EXPECT_EQ(reason(0).code, 30402u);
}

TEST_F(Reasons3202, HI_03_HomeWithoutLimitAhead) {
  configure(0, kFull3202 & ~m2::cfg_bit::kCwLimitUsed);
  command(0, m2::cmd_bit::kFindHomeCw, {.target = 0, .speed = 10'000});
  EXPECT_TRUE(status(0, m2::status_bit::kHomeInvalid));
  EXPECT_EQ(reason(0).code, 30222u);  // recorded as its Command Error item, 3202-CE-22
  EXPECT_EQ(text(reason(0)), "3202-CE-22: Find Home +: no CW limit configured");
}

TEST_F(Reasons3202, PI_02_ImmediateStop) {
  configure(0);
  command(0, m2::cmd_bit::kRelativeMove, {.target = 50'000});
  vm_.run_for(200 * kNsPerMs);
  command(0, m2::cmd_bit::kImmediateStop);
  EXPECT_EQ(reason(0).code, 30602u);
}

}  // namespace
}  // namespace stepmod::testing
