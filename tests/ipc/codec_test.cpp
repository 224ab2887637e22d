// Number encodings of the manuals (3601 ch. 5, 3602 ch. 9, 3202 ch. 5), every range edge in both
// directions.
#include "module_types/m3202/words_3202.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "module_types/m3602/words_3602.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>

namespace stepmod::words {
namespace {

using WP = WordPair;

// ---- 3601 decimal split (3601 manual ch. 5) ----

TEST(Codec3601, ManualExamplesDecode) {
  EXPECT_EQ(decode_3601(12, 345), 12'345);
  EXPECT_EQ(decode_3601(-12, -345), -12'345);
  EXPECT_EQ(decode_3601(12, 0), 12'000);
  EXPECT_EQ(decode_3601(-12, 0), -12'000);
  EXPECT_EQ(decode_3601(0, 345), 345);
  EXPECT_EQ(decode_3601(0, -345), -345);
  EXPECT_EQ(decode_3601(0, 0), 0);
}

TEST(Codec3601, ManualExamplesEncode) {
  EXPECT_EQ(encode_3601(12'345), (WP{12, 345}));
  EXPECT_EQ(encode_3601(-12'345), (WP{-12, -345}));
  EXPECT_EQ(encode_3601(12'000), (WP{12, 0}));
  EXPECT_EQ(encode_3601(-12'000), (WP{-12, 0}));
  EXPECT_EQ(encode_3601(345), (WP{0, 345}));
  EXPECT_EQ(encode_3601(-345), (WP{0, -345}));
  EXPECT_EQ(encode_3601(0), (WP{0, 0}));
}

TEST(Codec3601, OppositeSignsInvalid) {
  EXPECT_EQ(decode_3601(12, -345), std::nullopt);
  EXPECT_EQ(decode_3601(-12, 345), std::nullopt);
  EXPECT_EQ(decode_3601(1, -1), std::nullopt);
  EXPECT_EQ(decode_3601(-1, 1), std::nullopt);
}

TEST(Codec3601, LswRangeEdges) {
  EXPECT_EQ(decode_3601(0, 999), 999);
  EXPECT_EQ(decode_3601(0, -999), -999);
  EXPECT_EQ(decode_3601(0, 1000), std::nullopt);
  EXPECT_EQ(decode_3601(0, -1000), std::nullopt);
  EXPECT_EQ(decode_3601(1, 1000), std::nullopt);  // (1, 1000) is no decimal split
  EXPECT_EQ(decode_3601(-1, -1000), std::nullopt);
  EXPECT_EQ(decode_3601(1, 999), 1'999);
  EXPECT_EQ(decode_3601(-1, -999), -1'999);
}

TEST(Codec3601, TargetRangeEdgesRoundTrip) {
  // Target range -8,388,608 ... 8,388,607 (3601 manual ch. 5).
  EXPECT_EQ(encode_3601(8'388'607), (WP{8'388, 607}));
  EXPECT_EQ(encode_3601(-8'388'608), (WP{-8'388, -608}));
  EXPECT_EQ(decode_3601(8'388, 607), 8'388'607);
  EXPECT_EQ(decode_3601(-8'388, -608), -8'388'608);
  // Speed maximum 1,000,000 and minimum 1.
  EXPECT_EQ(encode_3601(1'000'000), (WP{1'000, 0}));
  EXPECT_EQ(decode_3601_unsigned(1'000, 0), 1'000'000);
  EXPECT_EQ(encode_3601(1), (WP{0, 1}));
  EXPECT_EQ(encode_3601(-1), (WP{0, -1}));
  EXPECT_EQ(encode_3601(999), (WP{0, 999}));
  EXPECT_EQ(encode_3601(1000), (WP{1, 0}));
  EXPECT_EQ(encode_3601(-999), (WP{0, -999}));
  EXPECT_EQ(encode_3601(-1000), (WP{-1, 0}));
  EXPECT_EQ(encode_3601(-1001), (WP{-1, -1}));
}

TEST(Codec3601, MswExtremesDecode) {
  EXPECT_EQ(decode_3601(32'767, 999), 32'767'999);
  EXPECT_EQ(decode_3601(-32'768, -999), -32'768'999);
  EXPECT_EQ(decode_3601(-32'768, 0), -32'768'000);
}

TEST(Codec3601, UnsignedVariantRequiresLsw0To999) {
  EXPECT_EQ(decode_3601_unsigned(0, 0), 0);
  EXPECT_EQ(decode_3601_unsigned(0, 999), 999);
  EXPECT_EQ(decode_3601_unsigned(0, 1000), std::nullopt);
  EXPECT_EQ(decode_3601_unsigned(0, -1), std::nullopt);
  EXPECT_EQ(decode_3601_unsigned(-1, 0), std::nullopt);
  EXPECT_EQ(decode_3601_unsigned(-1, -1), std::nullopt);
  EXPECT_EQ(decode_3601_unsigned(8'388, 607), 8'388'607);
  EXPECT_EQ(decode_3601_unsigned(32'767, 999), 32'767'999);
}

TEST(Codec3601, A9_ReportMswWraps) {
  // 40,000,000 reads back as MSW = -25,536 (16#9C40), LSW = 0.
  const WP p = encode_3601(40'000'000);
  EXPECT_EQ(p, (WP{-25'536, 0}));
  EXPECT_EQ(static_cast<std::uint16_t>(p.msw), 0x9C40);
  // 7FFFh -> 8000h at the thousands boundary.
  EXPECT_EQ(encode_3601(32'767'999), (WP{32'767, 999}));
  EXPECT_EQ(encode_3601(32'768'000), (WP{-32'768, 0}));
  EXPECT_EQ(encode_3601(-32'768'999), (WP{-32'768, -999}));
  EXPECT_EQ(encode_3601(-32'769'000), (WP{32'767, 0}));
  // int32 extremes (the internal count).
  EXPECT_EQ(encode_3601(INT32_MAX), (WP{static_cast<std::int16_t>(2'147'483 & 0xFFFF), 647}));
  EXPECT_EQ(encode_3601(INT32_MIN).lsw, -648);
  // The report decode is the plain sum, modulo the wrap.
  EXPECT_EQ(decode_3601_report(-25'536, 0), -25'536'000);
  EXPECT_EQ(decode_3601_report(12, 345), 12'345);
}

TEST(Codec3601, RawUnsignedWordsMeanTheSameInt) {
  // 0xFFF4 given as an unsigned 16-bit value is the INT -12.
  EXPECT_EQ(decode_3601(0xFFF4, static_cast<std::int32_t>(0xFEA7)), -12'345);
}

TEST(Codec3601, ExhaustiveRoundTripAroundThousands) {
  for (std::int32_t v = -1'000'500; v <= 1'000'500; v += 7) {
    const WP p = encode_3601(v);
    ASSERT_LE(p.lsw, 999);
    ASSERT_GE(p.lsw, -999);
    ASSERT_EQ(decode_3601(p.msw, p.lsw), v) << v;
  }
  for (std::int32_t v = -2'001; v <= 2'001; ++v)
    ASSERT_EQ(decode_3601(encode_3601(v).msw, encode_3601(v).lsw), v);
}

// ---- 3602 binary split (3602 manual ch. 9) ----

struct Row3602 {
  std::int32_t value;
  std::uint32_t hex;
  std::int16_t msw;
  std::int16_t lsw;
};

TEST(Codec3602, SplitTableBothDirections) {
  const Row3602 rows[] = {
      {999, 0x000003E7u, 0, 999},
      {50'800, 0x0000C670u, 0, -14'736},
      {94'784, 0x00017240u, 1, 29'248},
      {16'702'650, 0x00FEDCBAu, 254, -9'030},
      {-16'702'650, 0xFF012346u, -255, 9'030},
      {1'000'000, 0x000F4240u, 15, 16'960},
      {1'073'741'823, 0x3FFFFFFFu, 16'383, -1},
      {-1'073'741'823, 0xC0000001u, -16'384, 1},
  };
  for (const auto& r : rows) {
    EXPECT_EQ(static_cast<std::uint32_t>(r.value), r.hex);
    EXPECT_EQ(encode_3602(r.value), (WP{r.msw, r.lsw})) << r.value;
    EXPECT_EQ(decode_3602(r.msw, r.lsw), r.value) << r.value;
  }
}

TEST(Codec3602, Int32ExtremesAndSignBoundaries) {
  EXPECT_EQ(encode_3602(INT32_MAX), (WP{32'767, -1}));
  EXPECT_EQ(encode_3602(INT32_MIN), (WP{-32'768, 0}));
  EXPECT_EQ(decode_3602(32'767, -1), INT32_MAX);
  EXPECT_EQ(decode_3602(-32'768, 0), INT32_MIN);
  EXPECT_EQ(encode_3602(-1), (WP{-1, -1}));
  EXPECT_EQ(decode_3602(-1, -1), -1);
  EXPECT_EQ(encode_3602(65'535), (WP{0, -1}));
  EXPECT_EQ(encode_3602(65'536), (WP{1, 0}));
  EXPECT_EQ(encode_3602(-65'536), (WP{-1, 0}));
  EXPECT_EQ(decode_3602(0, 0xFFFF), 65'535);  // unsigned LSW given raw
}

TEST(Codec3602, RoundTripSweep) {
  for (std::int64_t v = INT32_MIN; v <= INT32_MAX; v += 9'999'991) {
    const auto x = static_cast<std::int32_t>(v);
    const WP p = encode_3602(x);
    ASSERT_EQ(decode_3602(p.msw, p.lsw), x);
  }
}

// ---- 3202 native (3202 manual ch. 5) ----

TEST(Codec3202, NativeDint) {
  EXPECT_EQ(decode_3202(INT32_MIN), INT32_MIN);
  EXPECT_EQ(decode_3202(INT32_MAX), INT32_MAX);
  EXPECT_EQ(encode_3202(-8'388'608), -8'388'608);
  EXPECT_EQ(encode_3202(8'388'607), 8'388'607);
}

}  // namespace
}  // namespace stepmod::words
