// The 3602 dialect alone: the binary split of every 32-bit value in both directions (3602 manual
// ch. 9 "Multi-Word Parameters" and its examples), the command words' decoding and the status words
// (3602 manual ch. 9).
#include <gtest/gtest.h>

#include "module_types/m3602/dialect_3602.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::testing {
namespace {

namespace m2 = module::m3602;
using module::axis::CommandKind;

ImageWords words(std::uint16_t msw, std::uint16_t lsw, std::int16_t w2, std::int16_t w3,
                 std::int16_t w4 = 0, std::int16_t w5 = 0, std::int16_t w6 = 0,
                 std::int16_t w7 = 0) {
  ImageWords w;
  w.w = {static_cast<std::int16_t>(msw), static_cast<std::int16_t>(lsw), w2, w3, w4, w5, w6, w7};
  return w;
}

// The binary split (3602 manual ch. 9): value, MSW, LSW as the PLC's INTs.
struct Split {
  std::int32_t value;
  std::int16_t msw;
  std::int16_t lsw;
};
constexpr Split kManualExamples[] = {
    {999, 0, 999},
    {50'800, 0, -14'736},
    {94'784, 1, 29'248},
    {16'702'650, 254, -9'030},
    {-16'702'650, -255, 9'030},
    {1'000'000, 15, 16'960},
    {1'073'741'823, 16'383, -1},
    {-1'073'741'823, -16'384, 1},
};

TEST(Dialect3602, BinarySplitTargetsDecodeAsTheManualTabulates) {
  for (const Split& s : kManualExamples) {
    const auto c = m2::command_from_words(
        words(m2::cmd_msw::kAbsoluteMove, 0, s.msw, s.lsw, s.msw, s.lsw, 10, 10));
    ASSERT_TRUE(c.target.has_value());
    EXPECT_EQ(*c.target, s.value);
    EXPECT_EQ(*c.speed, s.value);
    EXPECT_TRUE(c.commands.has(CommandKind::kAbsoluteMove));
    EXPECT_FALSE(c.words_invalid);
  }
}

TEST(Dialect3602, BinarySplitPositionEncodesAsTheManualTabulates) {
  for (const Split& s : kManualExamples) {
    module::axis::AxisStatus st;
    st.position = s.value;
    st.capture = -s.value;
    ImageWords in;
    m2::status_to_words(st, {}, in);
    EXPECT_EQ(in.w[m2::in_word::kPositionMsw], s.msw) << s.value;
    EXPECT_EQ(in.w[m2::in_word::kPositionMsw + 1], s.lsw) << s.value;
    EXPECT_EQ(
        words::decode_3602(in.w[m2::in_word::kCaptureMsw], in.w[m2::in_word::kCaptureMsw + 1]),
        -s.value);
  }
}

// 3602 manual ch. 9 table 9.27: the reported position is an int32 and rolls over at +-2^31.
TEST(Dialect3602, ReportedPositionRollsOverAtTwoToThe31) {
  module::axis::AxisStatus st;
  ImageWords in;
  st.position = 2'147'483'647;
  m2::status_to_words(st, {}, in);
  EXPECT_EQ(in.w[m2::in_word::kPositionMsw], 0x7FFF);
  EXPECT_EQ(in.w[m2::in_word::kPositionMsw + 1], -1);
  st.position = 2'147'483'648;  // one step further: -2^31
  m2::status_to_words(st, {}, in);
  EXPECT_EQ(in.w[m2::in_word::kPositionMsw], -32'768);
  EXPECT_EQ(in.w[m2::in_word::kPositionMsw + 1], 0);
  EXPECT_EQ(m2::wrap_to_int32(2'147'483'648), -2'147'483'647 - 1);
  EXPECT_EQ(m2::wrap_to_int32(-2'147'483'649), 2'147'483'647);
}

TEST(Dialect3602, JogBitsAreTheManualKindsAndReservedBitsAreUndefined) {
  EXPECT_TRUE(m2::command_from_words(words(m2::cmd_msw::kJogCw, 0, 0, 0))
                  .commands.has(CommandKind::kManualCw));
  EXPECT_TRUE(m2::command_from_words(words(m2::cmd_msw::kJogCcw, 0, 0, 0))
                  .commands.has(CommandKind::kManualCcw));
  for (unsigned b : {10u, 14u}) {
    EXPECT_TRUE(m2::command_from_words(words(static_cast<std::uint16_t>(1u << b), 0, 0, 0))
                    .commands.has(CommandKind::kUndefined));
  }
}

TEST(Dialect3602, CE_03_SingleAxisCommandWithInterpolationBits) {
  for (unsigned b = 9; b <= 14; ++b) {
    const auto c = m2::command_from_words(
        words(m2::cmd_msw::kRelativeMove, static_cast<std::uint16_t>(1u << b), 0, 100));
    EXPECT_TRUE(c.words_invalid) << "bit " << b;
  }
}

TEST(Dialect3602, CE_10_ReservedWordsOfEachCommand) {
  // Preset: words 4..7 reserved.
  EXPECT_FALSE(m2::command_from_words(words(m2::cmd_msw::kPresetPosition, 0, 0, 5)).words_invalid);
  EXPECT_TRUE(
      m2::command_from_words(words(m2::cmd_msw::kPresetPosition, 0, 0, 5, 0, 0, 1)).words_invalid);
  // Reset Errors / Run Blend: LSW 16#0000 or 16#0080 only, words 2..7 zero.
  for (std::uint16_t cmd :
       {m2::cmd_msw::kResetErrors, m2::cmd_msw::kRunBlendCw, m2::cmd_msw::kRunBlendCcw}) {
    EXPECT_FALSE(m2::command_from_words(words(cmd, 0, 0, 0)).words_invalid);
    EXPECT_FALSE(m2::command_from_words(words(cmd, m2::cmd_lsw::kGpo, 0, 0)).words_invalid);
    EXPECT_TRUE(m2::command_from_words(words(cmd, m2::cmd_lsw::kSCurve, 0, 0)).words_invalid);
    EXPECT_TRUE(m2::command_from_words(words(cmd, 0, 0, 0, 0, 0, 0, 3)).words_invalid);
    EXPECT_TRUE(m2::command_from_words(words(cmd, 0, 1, 0)).words_invalid);
  }
  // Find Home: words 2/3 reserved, checked by the axis (CE + HI, 3602-HI-04), not here.
  EXPECT_FALSE(m2::command_from_words(words(m2::cmd_msw::kFindHomeCw, 0, 0, 1, 0, 5'000, 10, 10))
                   .words_invalid);
  // Set minimum registration distance: LSW 16#0004 or 16#0084, words 4..7 zero.
  EXPECT_FALSE(
      m2::command_from_words(words(0, m2::cmd_lsw::kProgramMinRegistration, 0, 500)).words_invalid);
  EXPECT_FALSE(m2::command_from_words(
                   words(0, m2::cmd_lsw::kProgramMinRegistration | m2::cmd_lsw::kGpo, 0, 500))
                   .words_invalid);
  EXPECT_TRUE(m2::command_from_words(words(0, m2::cmd_lsw::kProgramMinRegistration, 0, 500, 1))
                  .words_invalid);
}

TEST(Dialect3602, AccelerationTypeBitsOfTheCommandLsw) {
  using planner::AccelShape;
  EXPECT_EQ(m2::command_from_words(words(1, 0x0, 0, 0)).shape, AccelShape::kConstant);
  EXPECT_EQ(m2::command_from_words(words(1, 0x1, 0, 0)).shape, AccelShape::kTriangularS);
  EXPECT_EQ(m2::command_from_words(words(1, 0x2, 0, 0)).shape, AccelShape::kConstant);
  EXPECT_EQ(m2::command_from_words(words(1, 0x3, 0, 0)).shape, AccelShape::kTrapezoidalS);
}

TEST(Dialect3602, LSW_01_StatusLswBits) {
  module::axis::AxisStatus st;
  st.inputs_active = 0x3F;  // capture, external, home, (E-stop line), CW, CCW
  st.blend_running = true;
  st.blend_acknowledge = true;
  st.min_registration_set = true;
  st.proximity_echo = true;
  ImageWords in;
  m2::status_to_words(st, {.axis_enabled = true, .gpo = true}, in);
  EXPECT_EQ(static_cast<std::uint16_t>(in.w[m2::in_word::kStatusLsw]),
            0x1F | 1u << 8 | 1u << 9 | 1u << 10 | 1u << 12 | 1u << 13);
  EXPECT_EQ(static_cast<std::uint16_t>(in.w[m2::in_word::kStatusMsw]),
            m2::status_msw::kAxisEnabled);
  // Bits 5..7, 11, 14, 15 are always 0; the CW / CCW inputs are the limit lines 4 / 5.
  st = {};
  st.inputs_active = 1u << 3;  // the InputLine E-stop slot: no such terminal on the 3602
  m2::status_to_words(st, {}, in);
  EXPECT_EQ(in.w[m2::in_word::kStatusLsw], 0);
}

TEST(Dialect3602, StatusMswBitPositions) {
  module::axis::AxisStatus st;
  st.home_invalid = true;
  st.command_error = true;
  st.stopped = true;
  ImageWords in;
  m2::status_to_words(st, {}, in);
  EXPECT_EQ(static_cast<std::uint16_t>(in.w[m2::in_word::kStatusMsw]),
            1u << 8 | 1u << 12 | 1u << 3);
  st = {};
  st.invalid_profile = true;
  st.position_invalid = true;
  st.input_error = true;
  st.configuration_error = true;
  m2::status_to_words(st, {}, in);
  EXPECT_EQ(static_cast<std::uint16_t>(in.w[m2::in_word::kStatusMsw]),
            1u << 9 | 1u << 10 | 1u << 11 | 1u << 13);
}

}  // namespace
}  // namespace stepmod::testing
