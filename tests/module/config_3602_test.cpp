// 3602 configuration, per axis: the 3602 checklist's "Configuration Error" 3602-CFG-01..08, N1, N2
// (3602 manual Ch.8 "Invalid Configurations" Tables 8.6/8.7, "Starting Speed", "Homing Timeout",
// "Reserved Words"), the echo of the last data written (A26), and the axes' independence
// (3602 manual ch. 8: axis 1 configurable while axis 2 runs).
#include "tests/module/rig_3602.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::status_msw;

class Config3602 : public Rig3602 {
 protected:
  // Writes configuration words to axis 1 in configuration mode; whether CfgE is set.
  bool rejected(std::uint16_t msw, std::uint16_t lsw = kAllActiveHigh3602, std::int32_t vs = 1'000,
                std::int16_t timeout = 0) {
    write_config(kAxis1, msw, lsw, vs, timeout);
    vm_.scans(3);
    EXPECT_TRUE(status(kAxis1, kConfigMode));
    return status(kAxis1, kConfigurationError);
  }
  // A rejected configuration applies nothing: back in command mode the axis is unconfigured
  // (CfgE, commands refused, nothing moves).
  void expect_nothing_applied() {
    clear_words(kAxis1);
    vm_.scans(3);
    EXPECT_FALSE(status(kAxis1, kConfigMode));
    EXPECT_TRUE(status(kAxis1, kConfigurationError));
    EXPECT_FALSE(status(kAxis1, kAxisEnabled));
    command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 100});
    vm_.run_for(100 * kNsPerMs);
    EXPECT_EQ(motor(kAxis1), 0);
  }
};

TEST_F(Config3602, CFG_01_PowerUpBothAxesInCommandModeWithConfigurationError) {
  vm_.scans(2);
  for (unsigned a : {kAxis1, kAxis2}) {
    EXPECT_FALSE(status(a, kConfigMode));
    EXPECT_TRUE(status(a, kConfigurationError));
    EXPECT_FALSE(status(a, kAxisEnabled));  // A19: not enabled before the first configuration
    command(a, m2::cmd_msw::kRelativeMove, {.target = 100});
    EXPECT_TRUE(status(a, kCommandError));
  }
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_EQ(motor(kAxis2), 0);
}

TEST_F(Config3602, CFG_02_ReservedMswBits) {
  for (unsigned b : {8u, 9u, 11u, 12u, 13u}) {
    EXPECT_TRUE(rejected(static_cast<std::uint16_t>(kLimitsConfigMsw | (1u << b)))) << "bit " << b;
  }
  EXPECT_FALSE(rejected(kLimitsConfigMsw));
}

TEST_F(Config3602, CFG_02_RejectedConfigurationAppliesNothing) {
  EXPECT_TRUE(rejected(static_cast<std::uint16_t>(kLimitsConfigMsw | (1u << 8))));
  expect_nothing_applied();
}

TEST_F(Config3602, CFG_03_CwInputFunction11) {
  const auto msw = static_cast<std::uint16_t>((kLimitsConfigMsw & ~m2::cfg_msw::kCwFunction) |
                                              m2::cfg_msw::kCwFunction);
  EXPECT_TRUE(rejected(msw));
  expect_nothing_applied();
}

TEST_F(Config3602, CFG_04_CcwInputFunction11) {
  const auto msw = static_cast<std::uint16_t>((kLimitsConfigMsw & ~m2::cfg_msw::kCcwFunction) |
                                              m2::cfg_msw::kCcwFunction);
  EXPECT_TRUE(rejected(msw));
  // The three valid values of each field are accepted (00 unused, 01 limit, 10 E-stop).
  for (unsigned f : {0u, 1u, 2u}) {
    const auto ok = static_cast<std::uint16_t>(
        (kLimitsConfigMsw & ~(m2::cfg_msw::kCwFunction | m2::cfg_msw::kCcwFunction)) |
        f << m2::cfg_msw::kCwFunctionShift | f << m2::cfg_msw::kCcwFunctionShift);
    EXPECT_FALSE(rejected(ok)) << "function " << f;
  }
}

TEST_F(Config3602, CFG_05_ReservedLswBits) {
  for (unsigned b = 5; b < 16; ++b) {
    EXPECT_TRUE(
        rejected(kLimitsConfigMsw, static_cast<std::uint16_t>(kAllActiveHigh3602 | (1u << b))))
        << "bit " << b;
  }
  expect_nothing_applied();
}

TEST_F(Config3602, CFG_06_StartingSpeedRangeInTheBinarySplit) {
  EXPECT_TRUE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 0));
  EXPECT_TRUE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 1'000'001));  // 16#000F:4241
  EXPECT_TRUE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, -1));         // MSW sign bit
  EXPECT_TRUE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, -1'000'000));
  EXPECT_FALSE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 1));
  EXPECT_FALSE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 1'000'000));  // 16#000F:4240
  // 50,800 = 16#0000:C670: the LSW reads negative as an INT and is still the low 16 bits.
  EXPECT_FALSE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 50'800));
  EXPECT_EQ(word(kAxis1, m2::out_word::kStartingSpeedLsw), -14'736);
}

TEST_F(Config3602, CFG_07_HomingTimeoutRange) {
  EXPECT_TRUE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 1'000, 301));
  EXPECT_TRUE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 1'000, -1));
  EXPECT_FALSE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 1'000, 300));  // 16#012C
  EXPECT_FALSE(rejected(kLimitsConfigMsw, kAllActiveHigh3602, 1'000, 0));
}

TEST_F(Config3602, CFG_08_ReservedWordsNonZero) {
  for (unsigned w = 5; w < 8; ++w) {
    write_config(kAxis1, kLimitsConfigMsw);
    word(kAxis1, w) = 1;
    vm_.scans(3);
    EXPECT_TRUE(status(kAxis1, kConfigurationError)) << "word " << w;
  }
  expect_nothing_applied();
}

TEST_F(Config3602, CFG_N1_NoHomeInputAndNoLimitsIsValid) {
  EXPECT_FALSE(rejected(m2::cfg_msw::kStepDirOutput));
  clear_words(kAxis1);
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kAxisEnabled));
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 1'234});
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), 1'234);
}

TEST_F(Config3602, CFG_N2_DisabledAxisWithoutConfigurationErrorIgnoresCommands) {
  // A19: accepted without further checks, even with data that would otherwise be invalid.
  EXPECT_FALSE(rejected(static_cast<std::uint16_t>(kLimitsConfigMsw | m2::cfg_msw::kDisableAxis),
                        kAllActiveHigh3602, 0));
  EXPECT_FALSE(status(kAxis1, kAxisEnabled));
  clear_words(kAxis1);
  vm_.scans(3);
  EXPECT_FALSE(status(kAxis1, kConfigurationError));
  EXPECT_FALSE(status(kAxis1, kAxisEnabled));
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 500});
  vm_.run_for(200 * kNsPerMs);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_FALSE(status(kAxis1, kCommandError));
}

TEST_F(Config3602, EN_01_AxisEnabledAfterAValidConfiguration) {
  configure(kAxis1);
  EXPECT_TRUE(status(kAxis1, kAxisEnabled));
  EXPECT_FALSE(status(kAxis1, kConfigurationError));
  EXPECT_FALSE(status(kAxis2, kAxisEnabled));  // axis 2 still unconfigured
}

// A26: the 3602 echoes the last data written, rejected data included.
TEST_F(Config3602, A26_ConfigurationModeEchoesTheLastDataWritten) {
  write_config(kAxis1, kLimitsConfigMsw, kAllActiveHigh3602, 94'784, 12);
  vm_.scans(3);
  EXPECT_EQ(status_msw(kAxis1),
            (kLimitsConfigMsw & 0x1FFF) | kAxisEnabled | m2::status_msw::kConfigMode);
  EXPECT_EQ(status_lsw(kAxis1), kAllActiveHigh3602);
  EXPECT_EQ(in_word(kAxis1, m2::in_word::kStartingSpeedMsw), 1);  // 16#0001:7240
  EXPECT_EQ(in_word(kAxis1, m2::in_word::kStartingSpeedLsw), 29'248);
  EXPECT_EQ(in_word(kAxis1, m2::in_word::kHomingTimeout), 12);
  write_config(kAxis1, kLimitsConfigMsw, kAllActiveHigh3602, 0, 400);  // invalid
  vm_.scans(3);
  EXPECT_TRUE(status(kAxis1, kConfigurationError));
  EXPECT_FALSE(status(kAxis1, kAxisEnabled));
  EXPECT_EQ(in_word(kAxis1, m2::in_word::kStartingSpeedLsw), 0);
  EXPECT_EQ(in_word(kAxis1, m2::in_word::kHomingTimeout), 400);
  for (unsigned w = 5; w < 8; ++w) EXPECT_EQ(in_word(kAxis1, w), 0);
}

// 3602 manual ch. 8: the axes are independent; axis 1 is configured while axis 2 runs, and vice
// versa.
TEST_F(Config3602, AxisConfiguredWhileTheOtherRuns) {
  configure(kAxis2);
  set_command(kAxis2, m2::cmd_msw::kRelativeMove, {.target = 30'000});
  vm_.scans(3);
  ASSERT_TRUE(moving(kAxis2));
  configure(kAxis1);
  EXPECT_TRUE(moving(kAxis2));
  EXPECT_FALSE(status(kAxis2, kCommandError));
  EXPECT_TRUE(status(kAxis1, kAxisEnabled));
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = -2'000});
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_TRUE(moving(kAxis2));
  // Now axis 2 goes to configuration mode (after its move, CE-01) while axis 1 runs.
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 40'000});
  ASSERT_TRUE(wait_idle(kAxis2));
  configure(kAxis2);
  EXPECT_TRUE(moving(kAxis1));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_EQ(motor(kAxis1), 38'000);
  EXPECT_EQ(motor(kAxis2), 30'000);
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
}

}  // namespace
}  // namespace stepmod::testing
