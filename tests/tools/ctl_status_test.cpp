// stepmodctl's status display: every bit by its name in the module's table, numbers in the
// module's encoding.
#include "tools/ctl_status.hpp"

#include <gtest/gtest.h>

#include "module_types/m3202/words_3202.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {
namespace {

namespace m = words::m3601;

ImageWords words(std::initializer_list<std::int32_t> v) {
  ImageWords w;
  unsigned i = 0;
  for (std::int32_t x : v) w.w[i++] = x;
  return w;
}

TEST(CtlStatus, Decodes3601CommandModeBitsAndPositions) {
  ImageWords in = words({m::status_msw::kModuleOk | m::status_msw::kMoveComplete,
                         m::status_lsw::kHomeActive, -12, -345, 40, 0, 0, 7});
  const std::string s = format_status(ModuleType::k3601, in);
  EXPECT_NE(s.find("COMMAND mode"), std::string::npos);
  EXPECT_NE(s.find("[Move Complete, Module OK]"), std::string::npos) << s;
  EXPECT_NE(s.find("[Home Input Active]"), std::string::npos) << s;
  EXPECT_NE(s.find("position = -12345"), std::string::npos) << s;
  EXPECT_NE(s.find("encoder  = 40000"), std::string::npos) << s;
  EXPECT_NE(s.find("capture  = 7"), std::string::npos) << s;
}

TEST(CtlStatus, Decodes3601ConfigMode) {
  ImageWords in =
      words({static_cast<std::int16_t>(0x8000 | 0x4000 | 0x0404), 0x3F, 1, 500, 0, 0, 4, 1});
  const std::string s = format_status(ModuleType::k3601, in);
  EXPECT_NE(s.find("CONFIGURATION mode"), std::string::npos) << s;
  EXPECT_NE(s.find("starting speed = 1500"), std::string::npos) << s;
  EXPECT_NE(s.find("firmware = 4.1"), std::string::npos) << s;
}

TEST(CtlStatus, Decodes3602BinarySplitPerAxis) {
  ImageWords in;
  in.w[0] = 0x4000 | 0x0008;  // axis 1: enabled, stopped
  in.w[2] = 0x00FE;           // 16,702,650 = 16#00FE:DCBA
  in.w[3] = static_cast<std::int16_t>(0xDCBA);
  in.w[8] = static_cast<std::int16_t>(0x8000);  // axis 2 in configuration mode
  const std::string s = format_status(ModuleType::k3602, in);
  EXPECT_NE(s.find("3602 axis 1 in COMMAND mode"), std::string::npos) << s;
  EXPECT_NE(s.find("[Axis Stopped, Axis Enabled]"), std::string::npos) << s;
  EXPECT_NE(s.find("position = 16702650"), std::string::npos) << s;
  EXPECT_NE(s.find("3602 axis 2 in CONFIGURATION mode"), std::string::npos) << s;
}

TEST(CtlStatus, Decodes3202NativeDints) {
  ImageWords in;
  in.w[8] = (1 << 14) | (1 << 30);  // channel 2: Home Invalid, Module OK
  in.w[9] = -2'000'000'000;
  const std::string s = format_status(ModuleType::k3202, in);
  EXPECT_NE(s.find("[Home Invalid, Module OK]"), std::string::npos) << s;
  EXPECT_NE(s.find("position = -2000000000"), std::string::npos) << s;
}

TEST(CtlStatus, RawWordsHexPerWordSize) {
  ImageWords w;
  w.w[0] = -1;
  EXPECT_EQ(format_words(w, 1, 2), "  [ 0]          -1  16#FFFF\n");
  EXPECT_EQ(format_words(w, 1, 4), "  [ 0]          -1  16#FFFFFFFF\n");
}

}  // namespace
}  // namespace stepmod::tools::ctl

namespace stepmod::tools::ctl {
namespace {

// tools/ctl_summary.hpp finds the summary's bits by name in each manual's status table: every
// flag lands on the bit its module's constant names (the 3602's "CW Motion", "Axis Stopped").
TEST(CtlSummary, EachModulesStatusBitsGiveTheirFlags) {
  namespace m1 = words::m3601::status_msw;
  namespace m2 = words::m3602::status_msw;
  namespace m3 = words::m3202::status_bit;
  constexpr auto k3601 = summary_bits_of(words::m3601::kStatusMswBits);
  constexpr auto k3602 = summary_bits_of(words::m3602::kStatusMswBits);
  constexpr auto k3202 = summary_bits_of(words::m3202::kStatusBits);
  AxisSummary s = summary_from_word(m1::kMovingCw | m1::kCommandError | m1::kModuleOk, k3601);
  EXPECT_TRUE(s.moving_cw && s.command_error);
  EXPECT_FALSE(s.moving_ccw || s.stopped || s.configuration_mode);
  s = summary_from_word(m2::kMovingCcw | m2::kStopped | m2::kHomeInvalid, k3602);
  EXPECT_TRUE(s.moving_ccw && s.stopped && s.home_invalid);
  EXPECT_FALSE(s.moving_cw || s.command_error);
  s = summary_from_word(m3::kBlendRunning | m3::kInvalidProfile | m3::kConfigMode, k3202);
  EXPECT_TRUE(s.blend_running && s.invalid_profile && s.configuration_mode);
  EXPECT_FALSE(s.home_invalid || s.hold);
  s = summary_from_word(m3::kHoldState | m3::kAtHome | m3::kMoveComplete | m3::kPositionInvalid |
                            m3::kInputError | m3::kConfigurationError,
                        k3202);
  EXPECT_TRUE(s.hold && s.at_home && s.move_complete && s.position_invalid && s.input_error &&
              s.cfg_error);
}

}  // namespace
}  // namespace stepmod::tools::ctl
