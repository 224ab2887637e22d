// The 3602's blend programming blocks as a PLC program writes them (3602 manual tables 9.2, 9.21
// and 9.22), word for word; put_axis leaves the other axis alone.
#include "module_types/m3602/plc_words_3602.hpp"

#include <gtest/gtest.h>

namespace stepmod::plc::m3602 {
namespace {

TEST(Words3602, BlendFirstBlockCountTypePairsAndFinalDeceleration) {
  BlendProfile b;
  for (int i = 0; i < 10; ++i) b.segments.push_back({100, 1000, 10, AccelType::kConstant});
  b.segments[0].type = AccelType::kTriangularS;   // pair 1 = 01
  b.segments[7].type = AccelType::kTrapezoidalS;  // pair 8 = 11
  b.segments[9].type = AccelType::kTriangularS;   // pair 10 (word 3, bits 3..2) = 01
  b.final_decel = 2000;
  b.final_type = AccelType::kTrapezoidalS;
  const std::vector<AxisWords> blocks = blend_blocks(b);
  ASSERT_EQ(blocks.size(), 11u);
  const AxisWords& f = blocks[0];
  EXPECT_EQ(f[0], 0);
  EXPECT_EQ(f[1], 0);  // the handshake bits are the sequencer's
  EXPECT_EQ(f[2], 10);
  EXPECT_EQ(static_cast<std::uint16_t>(f[3]), 0x0004);
  EXPECT_EQ(static_cast<std::uint16_t>(f[4]), 0xC001);
  EXPECT_EQ(static_cast<std::uint16_t>(f[5]), 0xC000 | 2000);  // type 15..14, value 10..0
  EXPECT_EQ(f[6], 0);
  EXPECT_EQ(f[7], 0);
}

TEST(Words3602, BlendSegmentBlocksAreBinarySplit) {
  BlendProfile b;
  b.segments = {{50'800, 70'000, 2000, AccelType::kConstant}, {1, 1000, 1, AccelType::kConstant}};
  b.final_decel = 5;
  const std::vector<AxisWords> blocks = blend_blocks(b);
  ASSERT_EQ(blocks.size(), 3u);
  const AxisWords& s = blocks[1];
  EXPECT_EQ(s[2], 0);  // 50,800 = 16#0000C670
  EXPECT_EQ(s[3], -14'736);
  EXPECT_EQ(s[4], 1);  // 70,000 = 16#00011170
  EXPECT_EQ(s[5], 0x1170);
  EXPECT_EQ(s[6], 2000);
  EXPECT_EQ(s[7], 0);
  EXPECT_EQ(blocks[2][3], 1);
}

TEST(Words3602, PutAxisWritesOnlyThatAxisWords) {
  ImageWords w;
  for (unsigned i = 0; i < 16; ++i) w.w[i] = 7;
  put_axis(w, 1, AxisWords{1, 2, 3, 4, 5, 6, 7, 8});
  for (unsigned i = 0; i < 8; ++i) EXPECT_EQ(w.w[i], 7) << i;
  for (unsigned i = 0; i < 8; ++i) EXPECT_EQ(w.w[8 + i], static_cast<std::int32_t>(i + 1)) << i;
}

}  // namespace
}  // namespace stepmod::plc::m3602
