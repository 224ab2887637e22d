// The bounds-checked reader and writer every EtherNet/IP parser is built on.
#include "fieldbus/enip/wire.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

TEST(EnipWire, ReadsLittleEndian) {
  const auto b = hex("01 02 03 04 05 06 07");
  Reader r(b);
  EXPECT_EQ(r.u8(), 0x01);
  EXPECT_EQ(r.u16(), 0x0302);
  EXPECT_EQ(r.u32(), 0x07060504u);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(EnipWire, AShortReadReadsNothingAndStaysFailed) {
  const auto b = hex("01 02 03");
  Reader r(b);
  EXPECT_EQ(r.u32(), 0u);  // not half a value: nothing
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.u8(), 0);  // nothing is read after a failure, even what remains
  EXPECT_TRUE(r.bytes(1).empty());
}

TEST(EnipWire, BytesNeverReachPastTheEnd) {
  const auto b = hex("aa bb");
  Reader r(b);
  EXPECT_TRUE(r.bytes(3).empty());
  EXPECT_FALSE(r.ok());
  Reader r2(b);
  EXPECT_EQ(r2.bytes(2).size(), 2u);
  EXPECT_TRUE(r2.ok());
}

TEST(EnipWire, WritesLittleAndBigEndianAndPatches) {
  std::array<std::uint8_t, 16> buf{};
  Writer w(buf);
  w.u16(0x1234);
  w.u32(0xA1B2C3D4u);
  w.be16(0xAF12);
  w.be32(0x7F000001u);
  w.patch_u16(0, 0xBEEF);
  ASSERT_TRUE(w.ok());
  const auto want = hex("ef be d4 c3 b2 a1 af 12 7f 00 00 01");
  EXPECT_EQ(std::vector<std::uint8_t>(w.written().begin(), w.written().end()), want);
}

TEST(EnipWire, AFullWriterWritesNothingMoreAndFails) {
  std::array<std::uint8_t, 3> buf{};
  Writer w(buf);
  w.u16(0x0102);
  w.u16(0x0304);  // does not fit: not half-written
  w.u8(0x05);     // fits, but the writer has failed: nothing more
  EXPECT_FALSE(w.ok());
  EXPECT_EQ(w.size(), 2u);
  EXPECT_EQ(buf[2], 0);
}

TEST(EnipWire, PatchOutsideWhatWasWrittenFails) {
  std::array<std::uint8_t, 8> buf{};
  Writer w(buf);
  w.u16(1);
  w.patch_u16(1, 5);
  EXPECT_FALSE(w.ok());
}

// CIP SHORT_STRING (the Identity's product name, the Ethernet Link's label): written whole or
// not at all; longer than its one length byte can say, not at all.
TEST(EnipWire, AShortStringIsItsLengthThenItsCharacters) {
  std::array<std::uint8_t, 8> buf{};
  Writer w(buf);
  w.short_string("eth0");
  EXPECT_TRUE(w.ok());
  EXPECT_EQ(std::vector<std::uint8_t>(w.written().begin(), w.written().end()),
            test::hex("04 65746830"));
  w.short_string("four");  // 5 bytes, 3 left
  EXPECT_FALSE(w.ok());
  EXPECT_EQ(w.size(), 5u);
  std::array<std::uint8_t, 300> big{};
  Writer too_long(big);
  too_long.short_string(std::string(256, 'x'));
  EXPECT_FALSE(too_long.ok());
  EXPECT_EQ(too_long.size(), 0u);
}

}  // namespace
}  // namespace stepmod::enip
