// 3602 error reasons (docs/error-reasons.md): each error bit a module sets comes with the checklist
// item that set it and a sentence, kept per axis and published with the input image. At least
// one test per error list (CFG, CE, IP, IE, HI, PI) of each module, named after the item.
#include <gtest/gtest.h>

#include "tests/module/reasons_rig.hpp"
#include "tests/module/rig_3602.hpp"

namespace stepmod::testing {
namespace {

// ---- 3602 --------------------------------------------------------------------------------------

using Reasons3602 = ReasonsRig<Rig3602>;

TEST_F(Reasons3602, CFG_03_CwInputFunction11) {
  write_config(kAxis2, kLimitsConfigMsw | (3u << m2::cfg_msw::kCwFunctionShift));
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis2, m2::status_msw::kConfigurationError));
  EXPECT_EQ(reason(kAxis2).code, 20103u);
  EXPECT_EQ(text(reason(kAxis2)).rfind("3602-CFG-03: ", 0), 0u) << text(reason(kAxis2));
  EXPECT_EQ(reason(kAxis1).code, 20101u);  // axis 1 still as at power-up
}

TEST_F(Reasons3602, CE_S2_MoveBeforeConfigurationNamesItsItem) {
  command(kAxis2, m2::cmd_msw::kRelativeMove, {.target = 100});
  EXPECT_TRUE(status(kAxis2, m2::status_msw::kCommandError));
  EXPECT_EQ(reason(kAxis2).code, 20292u);
  EXPECT_EQ(text(reason(kAxis2)), "3602-CE-S2: not configured: configure the axis first");
}

// A registration move's speed raised while it runs: the 3602's lettered item (3602-CE-R7).
TEST_F(Reasons3602, CE_R7_RegistrationSpeedIncreased) {
  configure(kAxis1);
  set_command(kAxis1, m2::cmd_msw::kJogCw, {.target = 20'000, .speed = 5'000});
  vm_.run_for(100 * kNsPerMs);
  set_command(kAxis1, m2::cmd_msw::kJogCw, {.target = 20'000, .speed = 8'000});
  vm_.scans(2);
  EXPECT_TRUE(status(kAxis1, m2::status_msw::kCommandError));
  EXPECT_EQ(reason(kAxis1).code, 20287u);
  EXPECT_EQ(text(reason(kAxis1)), "3602-CE-R7: a registration move's speed increased");
}

TEST_F(Reasons3602, CE_06_VpBelowVsOnAxis2) {
  configure(kAxis1);
  configure(kAxis2);
  command(kAxis2, m2::cmd_msw::kRelativeMove, {.target = 100, .speed = 400});
  EXPECT_EQ(reason(kAxis2).code, 20206u);
  EXPECT_EQ(text(reason(kAxis2)), "3602-CE-06: Vp 400 is below Vs 1000");
  EXPECT_EQ(reason(kAxis1).code, 20601u);  // its configuration's Position Invalid
}

TEST_F(Reasons3602, IP_03_ProfileOverflowNamesTheRegisters) {
  constexpr std::int32_t kMax = 1'073'741'823;
  configure(kAxis1);
  command(kAxis1, m2::cmd_msw::kPresetPosition,
          {.target = kMax, .speed = 0, .accel = 0, .decel = 0});
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 2});
  ASSERT_TRUE(wait_idle(kAxis1));
  command(kAxis1, m2::cmd_msw::kAbsoluteMove, {.target = -kMax, .speed = 1'000'000, .accel = 2000});
  EXPECT_TRUE(status(kAxis1, m2::status_msw::kInvalidProfile));
  EXPECT_EQ(reason(kAxis1).code, 20303u);
  EXPECT_EQ(text(reason(kAxis1)), "3602-IP-03: the move does not fit 32-bit registers");
}

TEST_F(Reasons3602, IE_02_LimitDuringAMove) {
  configure(kAxis1);
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 50'000});
  vm_.run_for(200 * kNsPerMs);
  vm_.sim().force(kAxis1, 1u << static_cast<unsigned>(InputLine::kCwLimit),
                  1u << static_cast<unsigned>(InputLine::kCwLimit), vm_.now());
  vm_.scans(3);
  EXPECT_EQ(reason(kAxis1).code, 20402u);
}

TEST_F(Reasons3602, HI_07_HomingTimeoutNamesTheTime) {
  configure(kAxis1, kLimitsConfigMsw, kAllActiveHigh3602, 1'000, 1);  // T = 1 s
  command(kAxis1, m2::cmd_msw::kFindHomeCw,
          {.target = 0, .speed = 2'000, .accel = 20, .decel = 20});
  ASSERT_TRUE(wait_idle(kAxis1, 3 * kNsPerSec));
  EXPECT_TRUE(status(kAxis1, m2::status_msw::kHomeInvalid));
  EXPECT_EQ(reason(kAxis1).code, 20507u);
  EXPECT_EQ(text(reason(kAxis1)), "3602-HI-07: homing timeout of 1 s expired");
}

TEST_F(Reasons3602, PI_02_ImmediateStop) {
  configure(kAxis1);
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 50'000});
  vm_.run_for(200 * kNsPerMs);
  command(kAxis1, m2::cmd_msw::kImmediateStop);
  EXPECT_EQ(reason(kAxis1).code, 20602u);
}

}  // namespace
}  // namespace stepmod::testing
