// 3202 configuration, per channel: the 3202 checklist's "Configuration Error" items 3202-CFG-01..13
// (3202 manual Ch.3 "Invalid Configurations" #1..#11), 3202-DIS-01, 3202-MOK-01 and the
// configuration image (3202 manual ch. 3).
#include "tests/module/plc_3202.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::cfg_bit;
namespace sb = m2::status_bit;

class Config3202 : public Plc3202 {
 protected:
  // Writes configuration DINTs of channel `ch` in configuration mode; whether CfgE is set.
  bool rejected(unsigned ch, std::uint32_t bits, std::int32_t vs = 1'000) {
    write_config(ch, bits, vs);
    vm_.scans(3);
    EXPECT_TRUE(status(ch, sb::kConfigMode));
    return status(ch, sb::kConfigurationError);
  }
  bool rejected_words(unsigned ch, const plc::m3202::ChannelWords& w) {
    put(ch, w);
    vm_.scans(3);
    return status(ch, sb::kConfigurationError);
  }
  static constexpr std::uint32_t kMinimal = kHomeUsed | kCwLimitUsed | kStepDirOutput;
  // The manual's "minimum useful" configuration: bits 2, 4, 5, 18, 20, 21.
  static constexpr std::uint32_t kManualMinimum =
      kHomeUsed | kCwLimitUsed | kCcwLimitUsed | (1u << 18) | (1u << 20) | (1u << 21);
};

TEST_F(Config3202, CFG_01_PowerUpDisabledWithoutConfigurationErrorThenInvalidSetsIt) {
  vm_.scans(2);
  for (unsigned ch = 0; ch < 2; ++ch) {
    EXPECT_FALSE(status(ch, sb::kConfigMode));
    EXPECT_FALSE(status(ch, sb::kConfigurationError));
    EXPECT_TRUE(status(ch, sb::kChannelDisabled));
    EXPECT_TRUE(status(ch, sb::kModuleOk));
  }
  EXPECT_TRUE(rejected(0, kHomeUsed | kStepDirOutput));  // #2
  EXPECT_FALSE(status(1, sb::kConfigurationError));      // the other channel untouched
  EXPECT_FALSE(rejected(0, kManualMinimum));
}

TEST_F(Config3202, CFG_02_NoWayToHome) {
  EXPECT_TRUE(rejected(0, kCwLimitUsed | kStepDirOutput));
  EXPECT_TRUE(rejected(1, kCwLimitUsed | kStepDirOutput));
}

TEST_F(Config3202, CFG_03_NoEndLimit) {
  EXPECT_TRUE(rejected(0, kHomeUsed | kStepDirOutput));
  EXPECT_FALSE(rejected(0, kHomeUsed | kCcwLimitUsed));
}

TEST_F(Config3202, CFG_04_EncoderAndDiagnosticFeedback) {
  EXPECT_TRUE(rejected(1, kMinimal | kQuadratureEncoder | kDiagnosticFeedback));
}

TEST_F(Config3202, CFG_05_MarkerHomingWithoutEncoder) {
  EXPECT_TRUE(rejected(0, kMinimal | kMarkerHoming));
}

TEST_F(Config3202, CFG_06_DiagnosticFeedbackWithCwCcwOutputs) {
  EXPECT_TRUE(rejected(0, kHomeUsed | kCwLimitUsed | kDiagnosticFeedback));
  EXPECT_FALSE(rejected(0, kHomeUsed | kCwLimitUsed | kDiagnosticFeedback | kStepDirOutput));
}

TEST_F(Config3202, CFG_07_StartingSpeedOutOfRange) {
  EXPECT_TRUE(rejected(0, kMinimal, 0));
  EXPECT_TRUE(rejected(0, kMinimal, 1'000'001));
  EXPECT_TRUE(rejected(0, kMinimal, -5'000));
  EXPECT_FALSE(rejected(0, kMinimal, 1));
  EXPECT_FALSE(rejected(0, kMinimal, 1'000'000));
}

TEST_F(Config3202, CFG_08_CaptureWithoutEncoderIsValidOnFirmware31) {
  write_config(0, kMinimal | kCaptureUsed);
  vm_.scans(3);
  EXPECT_FALSE(status(0, sb::kConfigurationError));
  // The firmware revision the module reports is 3.1 (major in 31-16, minor in 15-0).
  EXPECT_EQ(in(0, 3), (3 << 16) | 1);
}

TEST_F(Config3202, CFG_09_ReservedConfigurationBits) {
  for (unsigned b : {7u, 11u, 13u, 14u, 15u, 22u, 23u, 24u, 25u, 26u, 27u, 29u, 30u}) {
    EXPECT_TRUE(rejected(0, kMinimal | (1u << b))) << "bit " << b;
  }
}

TEST_F(Config3202, CFG_10_MarkerHomingWithoutProximity) {
  EXPECT_TRUE(rejected(0, kCwLimitUsed | kStepDirOutput | kQuadratureEncoder | kMarkerHoming));
  EXPECT_FALSE(rejected(
      0, kCwLimitUsed | kStepDirOutput | kQuadratureEncoder | kMarkerHoming | kBackplaneProximity));
  EXPECT_FALSE(rejected(0, kMinimal | kQuadratureEncoder | kMarkerHoming));
}

TEST_F(Config3202, CFG_11_MarkerHomingWithBothProximities) {
  EXPECT_TRUE(rejected(0, kMinimal | kQuadratureEncoder | kMarkerHoming | kBackplaneProximity));
}

TEST_F(Config3202, CFG_12_UnusedWordsNonZero) {
  for (unsigned w = 2; w < 8; ++w) {
    auto words = plc::m3202::configuration_words(kMinimal, 1'000);
    words[w] = 1;
    EXPECT_TRUE(rejected_words(1, words)) << "DINT " << w;
  }
  EXPECT_FALSE(rejected_words(1, plc::m3202::configuration_words(kMinimal, 1'000)));
}

TEST_F(Config3202, CFG_13_DisabledChannelNeverShowsConfigurationError) {
  // A19: every other check is skipped for a disabled channel.
  write_config(0, kDisable | (1u << 7), 0);
  vm_.scans(3);
  EXPECT_FALSE(status(0, sb::kConfigurationError));
  EXPECT_TRUE(status(0, sb::kChannelDisabled));
  put(0, {});
  vm_.scans(3);
  EXPECT_FALSE(status(0, sb::kConfigMode));
  EXPECT_FALSE(status(0, sb::kConfigurationError));
  EXPECT_TRUE(status(0, sb::kChannelDisabled));
}

TEST_F(Config3202, DIS_01_DisabledUntilConfiguredAndWhileConfiguredDisabled) {
  vm_.scans(2);
  // A disabled channel takes no command: nothing moves, no error.
  command(0, m2::cmd_bit::kRelativeMove, {.target = 100});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(0), 0);
  EXPECT_FALSE(status(0, sb::kCommandError));
  configure(0);
  EXPECT_FALSE(status(0, sb::kChannelDisabled));
  EXPECT_TRUE(status(1, sb::kChannelDisabled));
  command(0, m2::cmd_bit::kRelativeMove, {.target = 100});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(motor(0), 100);
  configure(0, kDisable);
  EXPECT_TRUE(status(0, sb::kChannelDisabled));
  command(0, m2::cmd_bit::kRelativeMove, {.target = 100});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(0), 100);
}

TEST_F(Config3202, MOK_01_ModuleOkInBothModes) {
  vm_.scans(2);
  EXPECT_TRUE(status(0, sb::kModuleOk));
  write_config(1, kMinimal);
  vm_.scans(3);
  EXPECT_TRUE(status(1, sb::kModuleOk));
  EXPECT_TRUE(status(1, sb::kConfigMode));
  EXPECT_TRUE(status(0, sb::kModuleOk));
}

// 3202 manual ch. 3: the mirror of the accepted bits (A26) with the module's bits, and the speed.
TEST_F(Config3202, ConfigurationImageMirrorsAcceptedWords) {
  write_config(0, kFull3202, 2'500);
  vm_.scans(3);
  EXPECT_EQ(status_word(0), kFull3202 | sb::kModuleOk | sb::kConfigMode);
  EXPECT_EQ(in(0, 1), 2'500);
  EXPECT_EQ(in(0, 2), 0);
  // A26: a rejected configuration leaves the last accepted mirror.
  write_config(0, kFull3202 | (1u << 7), 3'000);
  vm_.scans(3);
  EXPECT_EQ(status_word(0), kFull3202 | sb::kModuleOk | sb::kConfigMode | sb::kConfigurationError);
  EXPECT_EQ(in(0, 1), 2'500);
}

TEST_F(Config3202, ConfiguringOneChannelNeverDisturbsTheOtherWhileItMoves) {
  configure(0);
  configure(1);
  set_command(0, m2::cmd_bit::kRelativeMove, {.target = 20'000});
  vm_.scans(3);
  ASSERT_TRUE(moving(0));
  // Channel 2: an invalid configuration, then a valid one, then command mode.
  write_config(1, kHomeUsed);
  vm_.scans(3);
  EXPECT_TRUE(status(1, sb::kConfigurationError));
  EXPECT_TRUE(moving(0));
  EXPECT_FALSE(status(0, sb::kCommandError | sb::kConfigurationError));
  configure(1, kFull3202, 500);
  EXPECT_FALSE(status(1, sb::kConfigurationError));
  put(0, {});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(motor(0), 20'000);
  EXPECT_EQ(position(0), 20'000);
  EXPECT_TRUE(status(0, sb::kMoveComplete));
  EXPECT_EQ(motor(1), 0);
}

// The homing option by bits 12 / 2 / 6 (3202 manual ch. 3): each variant is taken and homes.
TEST_F(Config3202, HomingVariantsSelectedByBits12And2And6) {
  const std::uint32_t base =
      kCwLimitUsed | kCcwLimitUsed | kStepDirOutput | kQuadratureEncoder | kActiveLevels;
  for (std::uint32_t variant : {kHomeUsed, kHomeUsed | kBackplaneProximity,
                                kHomeUsed | kMarkerHoming, kMarkerHoming | kBackplaneProximity}) {
    EXPECT_FALSE(rejected(0, base | variant)) << std::hex << variant;
  }
}

}  // namespace
}  // namespace stepmod::testing
