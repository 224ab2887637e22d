// 3601 configuration: the 3601 checklist's "Configuration Error" items 3601-CFG-01..13 and N1..N3
// (3601 manual Ch.3 "Invalid Configurations" #1..#11).
#include "tests/module/plc_3601.hpp"

namespace stepmod::testing {
namespace {

using namespace m::cfg_msw;
using m::status_msw::kConfigMode;
using m::status_msw::kConfigurationError;
using m::status_msw::kModuleOk;
using m::status_msw::kPositionInvalid;

class Config3601 : public Plc3601 {
 protected:
  // Writes configuration words in configuration mode and reports whether CfgE is set.
  bool rejected(std::uint16_t msw, std::uint16_t lsw = kAllActiveHigh, std::int32_t vs = 1'000) {
    write_config(msw, lsw, vs);
    vm_.scans(3);
    EXPECT_TRUE(status(kConfigMode));
    return status(kConfigurationError);
  }
  bool rejected_words(const std::array<std::int32_t, 8>& w) {
    for (unsigned i = 0; i < 8; ++i) word(i) = w[i];
    vm_.scans(3);
    return status(kConfigurationError);
  }
  static constexpr std::uint16_t kMinimal = kHomeUsed | kCwLimitUsed | kStepDirOutput;
};

TEST_F(Config3601, CFG_01_PowerUpInCommandModeWithConfigurationError) {
  vm_.scans(2);
  EXPECT_FALSE(status(kConfigMode));
  EXPECT_TRUE(status(kConfigurationError));
  EXPECT_TRUE(status(kModuleOk));
  // Not configured: a move is refused and nothing moves.
  command(m::cmd_msw::kRelativeMove, {.target = 100});
  EXPECT_TRUE(status(m::status_msw::kCommandError));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
}

TEST_F(Config3601, CFG_02_NoWayToHome) {
  EXPECT_TRUE(rejected(kCwLimitUsed | kStepDirOutput));
}

TEST_F(Config3601, CFG_03_NoEndLimit) {
  EXPECT_TRUE(rejected(kHomeUsed | kStepDirOutput));
}

TEST_F(Config3601, CFG_04_EncoderAndDiagnosticFeedback) {
  EXPECT_TRUE(rejected(kMinimal | kQuadratureEncoder | kDiagnosticFeedback));
}

TEST_F(Config3601, CFG_05_MarkerHomingWithoutEncoder) {
  EXPECT_TRUE(rejected(kMinimal | kMarkerHoming));
}

TEST_F(Config3601, CFG_06_DiagnosticFeedbackWithCwCcwOutputs) {
  EXPECT_TRUE(rejected(kHomeUsed | kCwLimitUsed | kDiagnosticFeedback));
  EXPECT_FALSE(rejected(kHomeUsed | kCwLimitUsed | kDiagnosticFeedback | kStepDirOutput));
}

TEST_F(Config3601, CFG_07_StartingSpeedOutOfRange) {
  EXPECT_TRUE(rejected(kMinimal, kAllActiveHigh, 0));
  EXPECT_TRUE(rejected(kMinimal, kAllActiveHigh, 1'000'001));
  EXPECT_TRUE(rejected(kMinimal, kAllActiveHigh, -5'000));
  EXPECT_FALSE(rejected(kMinimal, kAllActiveHigh, 1));
  EXPECT_FALSE(rejected(kMinimal, kAllActiveHigh, 1'000'000));
}

TEST_F(Config3601, CFG_08_StartingSpeedLswOutOfRange) {
  const auto hi = static_cast<std::int16_t>(kMinimal | kConfigMode);
  EXPECT_TRUE(rejected_words({hi, kAllActiveHigh, 1, 1000, 0, 0, 0, 0}));
  EXPECT_TRUE(rejected_words({hi, kAllActiveHigh, 0, -1, 0, 0, 0, 0}));
  EXPECT_FALSE(rejected_words({hi, kAllActiveHigh, 1, 999, 0, 0, 0, 0}));
}

TEST_F(Config3601, CFG_09_ReservedConfigurationBits) {
  for (unsigned b : {7u, 11u, 13u, 14u}) {
    EXPECT_TRUE(rejected(static_cast<std::uint16_t>(kMinimal | (1u << b)))) << "MSW bit " << b;
  }
  for (unsigned b = 6; b < 16; ++b) {
    EXPECT_TRUE(rejected(kMinimal, static_cast<std::uint16_t>(kAllActiveHigh | (1u << b))))
        << "LSW bit " << b;
  }
}

TEST_F(Config3601, CFG_10_MarkerHomingWithoutProximity) {
  EXPECT_TRUE(rejected(kCwLimitUsed | kStepDirOutput | kQuadratureEncoder | kMarkerHoming));
}

TEST_F(Config3601, CFG_11_MarkerHomingWithBothProximities) {
  EXPECT_TRUE(rejected(kMinimal | kQuadratureEncoder | kMarkerHoming | kBackplaneProximity));
}

TEST_F(Config3601, CFG_12_UnusedWordsNotZero) {
  const auto hi = static_cast<std::int16_t>(kMinimal | kConfigMode);
  for (unsigned w = 4; w < 8; ++w) {
    std::array<std::int32_t, 8> words{hi, kAllActiveHigh, 1, 0, 0, 0, 0, 0};
    words[w] = 1;
    EXPECT_TRUE(rejected_words(words)) << "word " << w;
  }
}

TEST_F(Config3601, CFG_13_PI_01_ValidConfigurationClearsErrorAndInvalidatesPosition) {
  configure();
  EXPECT_FALSE(status(kConfigMode));
  EXPECT_FALSE(status(kConfigurationError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_EQ(position(), 0);
  // Moves after a preset, and a new configuration zeroes the position again.
  command(m::cmd_msw::kPresetPosition, {.target = 1234, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(position(), 1234);
  EXPECT_FALSE(status(kPositionInvalid));
  configure();
  EXPECT_EQ(position(), 0);
  EXPECT_TRUE(status(kPositionInvalid));
}

// Issue 12 item 3 (3601 manual ch. 3, 4): a command written in the same image that leaves
// configuration mode is a 0->1 edge of its bit (the configuration word is not a command word)
// and acts, instead of being silently dropped.
TEST_F(Config3601, CFG_13_CommandInTheImageThatLeavesConfigurationModeActs) {
  write_config(kFullConfigMsw, kAllActiveHigh, 1'000);
  vm_.scans(3);
  ASSERT_TRUE(status(kConfigMode));
  set_words(m::cmd_msw::kRelativeMove, 0, 2'000, 10'000, 10, 10);  // mode bit 0 + a command
  vm_.scans(3);
  EXPECT_FALSE(status(kConfigMode));
  ASSERT_TRUE(
      vm_.run_until_true([this] { return status(m::status_msw::kMoveComplete); }, 10 * kNsPerSec));
  EXPECT_EQ(position(), 2'000);
  EXPECT_EQ(motor(), 2'000);
  EXPECT_FALSE(status(m::status_msw::kCommandError));
}

// The same rule, the other way round: a PLC that clears only the mode bit leaves its
// configuration bits in word 0, which the command mode reads as several command bits at once:
// the manual's Command Error (3601-CE-02), never a silent nothing, and no motion.
TEST_F(Config3601, CE_02_ConfigurationBitsLeftInTheCommandWordAreSeveralCommands) {
  write_config(kFullConfigMsw, kAllActiveHigh, 1'000);
  vm_.scans(3);
  word(0) = static_cast<std::int16_t>(kFullConfigMsw);  // only the mode bit cleared
  vm_.scans(3);
  EXPECT_FALSE(status(kConfigMode));
  EXPECT_FALSE(status(kConfigurationError));
  EXPECT_TRUE(status(m::status_msw::kCommandError));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
}

TEST_F(Config3601, CFG_13_MirrorAndFirmwareRevisionInConfigurationMode) {
  write_config(kFullConfigMsw, kAllActiveHigh, 12'345);
  vm_.scans(3);
  const auto& in = vm_.plc_in().w;
  EXPECT_EQ(static_cast<std::uint16_t>(in[0]) & 0x1FFF, kFullConfigMsw & 0x1FFF);
  EXPECT_EQ(in[1], kAllActiveHigh);
  EXPECT_EQ(in[2], 12);
  EXPECT_EQ(in[3], 345);
  EXPECT_EQ(in[4], 0);
  EXPECT_EQ(in[5], 0);
  EXPECT_EQ(in[6], m::kFirmwareMajor);
  EXPECT_EQ(in[7], m::kFirmwareMinor);
  // A26: a rejected configuration leaves the previous mirror.
  write_config(kHomeUsed | kStepDirOutput, kAllActiveHigh, 7);
  vm_.scans(3);
  EXPECT_TRUE(status(kConfigurationError));
  EXPECT_EQ(vm_.plc_in().w[2], 12);
  EXPECT_EQ(vm_.plc_in().w[3], 345);
}

TEST_F(Config3601, CFG_N1_CaptureWithoutEncoderIsValid) {
  EXPECT_FALSE(rejected(kMinimal | kCaptureUsed));
}

TEST_F(Config3601, CFG_N2_ActiveLevelOfUnusedInputIsValid) {
  EXPECT_FALSE(rejected(kMinimal, 0x003F));
  EXPECT_FALSE(rejected(kMinimal, 0x0000));
}

TEST_F(Config3601, CFG_N3_HomeSwitchWithBackplaneProximityIsValid) {
  EXPECT_FALSE(rejected(kMinimal | kBackplaneProximity));
}

TEST_F(Config3601, CFG_N3_MarkerHomingWithOneProximitySourceIsValid) {
  EXPECT_FALSE(rejected(kMinimal | kQuadratureEncoder | kMarkerHoming));
  EXPECT_FALSE(rejected(kCwLimitUsed | kStepDirOutput | kQuadratureEncoder | kMarkerHoming |
                        kBackplaneProximity));
}

TEST_F(Config3601, InvalidConfigurationKeepsAxisUnconfiguredInCommandMode) {
  write_config(kCwLimitUsed, kAllActiveHigh, 1'000);
  vm_.scans(3);
  word(0) = 0;
  vm_.scans(3);
  EXPECT_FALSE(status(kConfigMode));
  EXPECT_TRUE(status(kConfigurationError));
  command(m::cmd_msw::kRelativeMove, {.target = 10});
  EXPECT_TRUE(status(m::status_msw::kCommandError));
  vm_.run_for(50 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
}

}  // namespace
}  // namespace stepmod::testing
