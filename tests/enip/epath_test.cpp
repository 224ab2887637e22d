// Padded EPATHs: request paths and Forward_Open connection paths, every segment bounds-checked.
#include "fieldbus/enip/epath.hpp"

#include <gtest/gtest.h>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

TEST(EnipEpath, RequestPathWithEightAndSixteenBitSegments) {
  RequestPath p;
  ASSERT_TRUE(parse_request_path(hex("20 01 24 01 30 07"), p));
  EXPECT_EQ(p.class_id, 1u);
  EXPECT_EQ(p.instance, 1u);
  EXPECT_TRUE(p.has_attribute);
  EXPECT_EQ(p.attribute, 7u);
  ASSERT_TRUE(parse_request_path(hex("20 04 25 00 96 00 30 03"), p));
  EXPECT_EQ(p.instance, 150u);
  ASSERT_TRUE(parse_request_path(hex("21 00 f5 00 26 00 01 00 00 00"), p));
  EXPECT_EQ(p.class_id, 0xF5u);
  EXPECT_EQ(p.instance, 1u);
  EXPECT_FALSE(p.has_attribute);
}

TEST(EnipEpath, RequestPathRefusals) {
  RequestPath p;
  EXPECT_FALSE(parse_request_path(hex(""), p));
  EXPECT_FALSE(parse_request_path(hex("24 01"), p));              // no class
  EXPECT_FALSE(parse_request_path(hex("20 01 30 01"), p));        // attribute before instance
  EXPECT_FALSE(parse_request_path(hex("20 01 24 01 24 02"), p));  // two instances
  EXPECT_FALSE(parse_request_path(hex("20 01 25 00 01"), p));     // a 16-bit value cut short
  EXPECT_FALSE(parse_request_path(hex("20 01 24"), p));           // an 8-bit value missing
  EXPECT_FALSE(parse_request_path(hex("91 03 61 62 63 00"), p));  // symbolic: not served
  EXPECT_FALSE(parse_request_path(hex("23 01"), p));              // reserved logical format
}

TEST(EnipEpath, PortSegments) {
  Segment s;
  // The reader views the bytes: they must outlive it.
  const auto plain_bytes = hex("01 00");  // port 1 (the backplane), link 0
  EpathReader plain(plain_bytes);
  ASSERT_TRUE(plain.next(s));
  EXPECT_EQ(s.kind, SegmentKind::kPort);
  EXPECT_EQ(s.value, 1u);
  ASSERT_EQ(s.data.size(), 1u);
  EXPECT_EQ(s.data[0], 0);
  EXPECT_FALSE(plain.next(s));
  EXPECT_FALSE(plain.failed());
  // Port 2, an extended link address of 9 bytes ("127.0.0.1"), padded to even.
  const auto ext_bytes = hex("12 09 31 32 37 2e 30 2e 30 2e 31 00 20 02");
  EpathReader ext(ext_bytes);
  ASSERT_TRUE(ext.next(s));
  EXPECT_EQ(s.value, 2u);
  EXPECT_EQ(s.data.size(), 9u);
  ASSERT_TRUE(ext.next(s));
  EXPECT_EQ(s.kind, SegmentKind::kClass);
  const auto cut_bytes = hex("12 09 31 32");
  EpathReader cut(cut_bytes);
  EXPECT_FALSE(cut.next(s));
  EXPECT_TRUE(cut.failed());
}

// The connection path st-ethernet-ip sends: a zero (match anything) electronic key, assembly
// class, configuration 151, O→T point 150, T→O point 100.
const auto kScannerPath = hex("34 04 0000 0000 0000 00 00  20 04 24 97 2c 96 2c 64");

TEST(EnipEpath, ConnectionPathOfAnIoScanner) {
  ConnectionPath p;
  ASSERT_TRUE(parse_connection_path(kScannerPath, p));
  EXPECT_TRUE(p.has_key);
  EXPECT_EQ(p.key.vendor, 0);
  EXPECT_EQ(p.class_id, 4u);
  EXPECT_EQ(p.config_instance, 151u);
  ASSERT_EQ(p.point_count, 2u);
  EXPECT_EQ(p.points[0], 150u);
  EXPECT_EQ(p.points[1], 100u);
  EXPECT_FALSE(p.has_data);
}

TEST(EnipEpath, ConnectionPathWithKeyFieldsAndDataSegment) {
  ConnectionPath p;
  ASSERT_TRUE(
      parse_connection_path(hex("34 04 ffff 2b00 110e 81 01  20 04 24 97 2c 96 2c 64 80 00"), p));
  EXPECT_EQ(p.key.vendor, 0xFFFF);
  EXPECT_EQ(p.key.product_code, 3601);
  EXPECT_TRUE(p.key.compatibility());
  EXPECT_EQ(p.key.major(), 1);
  EXPECT_TRUE(p.has_data);
  EXPECT_TRUE(p.data.empty());
  // A production inhibit time (network segment) is skipped.
  ASSERT_TRUE(parse_connection_path(hex("43 05 20 04 24 97 2c 96 2c 64"), p));
  EXPECT_EQ(p.point_count, 2u);
}

TEST(EnipEpath, ConnectionPathRefusals) {
  ConnectionPath p;
  EXPECT_FALSE(parse_connection_path(hex("34 05 0000 0000 0000 00 00 20 04"), p));  // format
  EXPECT_FALSE(parse_connection_path(hex("34 04 0000 0000 0000 00"), p));           // key cut short
  EXPECT_FALSE(parse_connection_path(hex("2c 96 2c 64"), p));                       // no class
  EXPECT_FALSE(parse_connection_path(hex("20 04 2c 96 2c 64 2c 65"), p));           // three points
  EXPECT_FALSE(parse_connection_path(hex("20 04 2c 96 24 97 2c 64"), p));  // config after a point
  EXPECT_FALSE(parse_connection_path(hex("20 04 24 97 2c 96 80 01 00"), p));     // data cut short
  EXPECT_FALSE(parse_connection_path(hex("01 00 20 04 24 97 2c 96 2c 64"), p));  // a route
  EXPECT_FALSE(parse_connection_path(hex("20 04 24 97 2c 96 2c 64 34 04 0000 0000 0000 00 00"),
                                     p));  // the key after the class
}

TEST(EnipEpath, EveryTruncationOfAValidPathFailsOrStopsCleanly) {
  // A prefix either parses (it ends between segments) or fails; it never reads past its end
  // (ASan runs this).
  for (std::size_t n = 0; n <= kScannerPath.size(); ++n) {
    std::vector<std::uint8_t> cut(kScannerPath.begin(), kScannerPath.begin() + n);
    ConnectionPath p;
    const bool ok = parse_connection_path(cut, p);
    if (n == kScannerPath.size()) {
      EXPECT_TRUE(ok);
    }
    if (n < 10) {
      EXPECT_FALSE(ok) << n;
    }
  }
}

}  // namespace
}  // namespace stepmod::enip
