// stepmodctl's blend profile input (every module): options and the readable file.
#include "tools/ctl_blend.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace stepmod::tools::ctl {
namespace {

std::string write_temp(const std::string& text) {
  char path[] = "/tmp/stepmod_blend_XXXXXX";
  const int fd = mkstemp(path);
  EXPECT_GE(fd, 0);
  std::ofstream(path) << text;
  return path;
}

TEST(CtlBlend, BlendFileReadsSegmentsAndFinalDeceleration) {
  const std::string p = write_temp(
      "# two segments\nsegment = 6000:5000:100000:tri\nsegment = 0x10:16#20:1000\n"
      "final_decel = 100000\nfinal_type = trap   # trapezoidal\n");
  const plc::BlendProfile b = read_blend_file(p);
  std::remove(p.c_str());
  ASSERT_EQ(b.segments.size(), 2u);
  EXPECT_EQ(b.segments[0].length, 6'000);
  EXPECT_EQ(b.segments[0].type, plc::AccelType::kTriangularS);
  EXPECT_EQ(b.segments[1].length, 16);
  EXPECT_EQ(b.segments[1].speed, 32);
  EXPECT_EQ(b.segments[1].type, plc::AccelType::kConstant);
  EXPECT_EQ(b.final_decel, 100'000);
  EXPECT_EQ(b.final_type, plc::AccelType::kTrapezoidalS);
}

TEST(CtlBlend, BlendFileErrorsNameTheLine) {
  const std::string p = write_temp("segment = 1:2:3\nspeed = 5\n");
  try {
    read_blend_file(p);
    ADD_FAILURE() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find(":2: unknown key 'speed'"), std::string::npos) << e.what();
  }
  std::remove(p.c_str());
  EXPECT_THROW(read_blend_file("/nonexistent/blend.txt"), UsageError);
  EXPECT_THROW(parse_blend_segment("1:2"), UsageError);
  EXPECT_THROW(parse_blend_segment("1:2:x"), UsageError);
  EXPECT_THROW(parse_blend_segment("1:2:3:wave"), UsageError);
}

}  // namespace
}  // namespace stepmod::tools::ctl
