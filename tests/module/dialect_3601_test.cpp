// The 3601 dialect's translations (module_types/m3601/dialect_3601, config_3601): words -> decoded
// command and configuration, decoded status -> words. The behaviour behind them is tested through
// PLC words in the other *_3601_test.cpp files and on the shared axis in axis_shared_test.cpp.
#include <gtest/gtest.h>

#include <set>

#include "module_types/m3601/config_3601.hpp"
#include "module_types/m3601/dialect_3601.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing {
namespace {

namespace m = module::m3601;
namespace ax = module::axis;

ImageWords words(std::uint16_t msw, std::uint16_t lsw, std::int32_t w23 = 0, std::int32_t w45 = 0,
                 std::int16_t w6 = 0, std::int16_t w7 = 0) {
  ImageWords o;
  const auto a = words::encode_3601(w23);
  const auto b = words::encode_3601(w45);
  o.w = {static_cast<std::int16_t>(msw),
         static_cast<std::int16_t>(lsw),
         a.msw,
         a.lsw,
         b.msw,
         b.lsw,
         w6,
         w7};
  return o;
}

// 3601 manual ch. 5: each command MSW bit 0..14 is one command kind of its own (14: A33's undefined
// bit), bit 15 the mode bit.
TEST(Dialect3601, EveryCommandBitIsOneCommandKind) {
  std::set<std::size_t> seen;
  for (unsigned bit = 0; bit < 15; ++bit) {
    const ax::AxisCommand c = m::command_from_words(words(m::bit(bit), 0));
    ASSERT_EQ(c.commands.count(), 1u) << "bit " << bit;
    EXPECT_FALSE(c.configuration_mode);
    seen.insert(static_cast<std::size_t>(*c.commands.single()));
  }
  EXPECT_EQ(seen.size(), 15u);
  const ax::AxisCommand cfg = m::command_from_words(words(m::cmd_msw::kConfigMode, 0));
  EXPECT_TRUE(cfg.configuration_mode);
  EXPECT_TRUE(cfg.commands.empty());
}

// 3601 manual ch. 5: decimal split target/speed, steps/ms/s -> steps/s^2, S-curve bits.
TEST(Dialect3601, ParametersInTheSharedUnits) {
  const ax::AxisCommand c = m::command_from_words(
      words(m::cmd_msw::kRelativeMove, m::cmd_lsw::kSCurve | m::cmd_lsw::kTrapezoidalS, -12'345,
            250'000, 10, 2000));
  EXPECT_EQ(c.target, -12'345);
  EXPECT_EQ(c.speed, 250'000);
  EXPECT_EQ(c.accel, 10'000);
  EXPECT_EQ(c.decel, 2'000'000);
  EXPECT_EQ(c.shape, planner::AccelShape::kTrapezoidalS);
  ImageWords bad = words(m::cmd_msw::kRelativeMove, 0);
  bad.w[3] = 1000;  // LSW outside -999..999
  EXPECT_FALSE(m::command_from_words(bad).target.has_value());
}

// 3601-CE-09 / CE-15 / CE-21: the "must be 0" word rules of the command table are the dialect's.
TEST(Dialect3601, CE_09_CE_15_CE_21_WordRulesOfTheCommandTable) {
  EXPECT_FALSE(m::command_from_words(words(m::cmd_msw::kPresetPosition, 0, 5)).words_invalid);
  EXPECT_TRUE(m::command_from_words(words(m::cmd_msw::kPresetPosition, 0, 5, 1)).words_invalid);
  EXPECT_TRUE(m::command_from_words(words(m::cmd_msw::kPresetEncoder, 1, 5)).words_invalid);
  EXPECT_TRUE(m::command_from_words(words(m::cmd_msw::kResetErrors, 4)).words_invalid);
  EXPECT_TRUE(m::command_from_words(words(m::cmd_msw::kRunBlendCw, 0, 1)).words_invalid);
  EXPECT_FALSE(m::command_from_words(words(m::cmd_msw::kRunBlendCcw, 0)).words_invalid);
  EXPECT_FALSE(
      m::command_from_words(words(m::cmd_msw::kRelativeMove, 4, 5, 6, 7, 8)).words_invalid);
  // Minimum registration store: LSW exactly bit 10, words 4..7 zero.
  EXPECT_FALSE(
      m::command_from_words(words(0, m::cmd_lsw::kStoreMinRegistration, 100)).words_invalid);
  EXPECT_TRUE(
      m::command_from_words(words(0, m::cmd_lsw::kStoreMinRegistration | 1, 100)).words_invalid);
}

// 3601 manual ch. 3: the configuration bits decoded; the homing option from bits 6 and 12.
TEST(Dialect3601, ConfigurationDecoded) {
  using namespace m::cfg_msw;
  m::Config3601 c;
  c.msw = kHomeUsed | kCwLimitUsed | kQuadratureEncoder | kStepDirOutput | kMarkerHoming;
  c.lsw = 0x0004;
  c.starting_speed = 1'234;
  ax::AxisConfig a = m::to_axis_config(c);
  EXPECT_EQ(a.inputs_used, kHomeUsed | kCwLimitUsed);
  EXPECT_EQ(a.inputs_active_high, 0x0004);
  EXPECT_TRUE(a.quadrature_encoder);
  EXPECT_TRUE(a.step_dir_output);
  EXPECT_FALSE(a.diagnostic_feedback);
  EXPECT_EQ(a.homing, ax::HomingVariant::kMarkerWithHome);
  EXPECT_EQ(a.starting_speed, 1'234);
  c.msw = kHomeUsed | kCwLimitUsed | kBackplaneProximity;
  EXPECT_EQ(m::to_axis_config(c).homing, ax::HomingVariant::kSwitchWithBackplane);
}

// 3601 manual ch. 6: every named status flag lands on its own bit; registers in decimal split.
TEST(Dialect3601, StatusFlagsOnTheirBits) {
  ax::AxisStatus s;
  s.move_complete = true;
  s.command_error = true;
  s.blend_acknowledge = true;
  s.inputs_active = 0x0009;  // capture, E-stop
  s.position = -1'234'567;
  ImageWords in;
  m::status_to_words(s, in);
  const auto msw = static_cast<std::uint16_t>(in.w[m::in_word::kStatusMsw]);
  const auto lsw = static_cast<std::uint16_t>(in.w[m::in_word::kStatusLsw]);
  EXPECT_EQ(msw,
            m::status_msw::kModuleOk | m::status_msw::kMoveComplete | m::status_msw::kCommandError);
  EXPECT_EQ(lsw, m::status_lsw::kBlendAcknowledge | m::status_lsw::kCaptureActive |
                     m::status_lsw::kEStopActive);
  EXPECT_EQ(
      words::decode_3601_report(in.w[m::in_word::kPositionMsw], in.w[m::in_word::kPositionLsw]),
      -1'234'567);
}

}  // namespace
}  // namespace stepmod::testing
