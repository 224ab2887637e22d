// stepmodctl's status display: every bit by its name in the module's table, numbers in the
// module's encoding.
#include "tools/ctl_status.hpp"

#include <gtest/gtest.h>

#include "module_types/m3601/words_3601.hpp"

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
