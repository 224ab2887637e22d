// Class 1 I/O packets: O→T parsed against its connection's shape, T→O written.
#include "fieldbus/enip/io_packet.hpp"

#include <gtest/gtest.h>

#include <array>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

// What st-ethernet-ip sends to a 3601 (16 bytes): connection id, encapsulation sequence 5,
// CIP count 2, run/idle header 1 (Run), the output words.
const auto kRunPacket =
    hex("0200 0280 0800 d0c0b0a0 05000000 b100 1600 0200 01000000"
        "0100 0200 0300 0400 0500 0600 0700 0800");
const IoShape kOwner3601{true, 16};

TEST(EnipIoPacket, ParsesTheScannersRunPacket) {
  IoPacket p;
  ASSERT_EQ(parse_o_to_t(kRunPacket, kOwner3601, p), IoParse::kOk);
  EXPECT_EQ(p.connection_id, 0xA0B0C0D0u);
  EXPECT_EQ(p.encap_sequence, 5u);
  EXPECT_EQ(p.cip_sequence, 2);
  EXPECT_TRUE(p.run);
  ASSERT_EQ(p.data.size(), 16u);
  EXPECT_EQ(p.data[0], 1);
  EXPECT_EQ(p.data[14], 8);
}

TEST(EnipIoPacket, IdleIsSeen) {
  auto b = kRunPacket;
  b[20] = 0;  // the run/idle header: count 2 + address item 12 + data item header 4 + CIP count 2
  IoPacket p;
  ASSERT_EQ(parse_o_to_t(b, kOwner3601, p), IoParse::kOk);
  EXPECT_FALSE(p.run);
}

TEST(EnipIoPacket, AHeartbeatHasNoHeaderAndNoData) {
  IoPacket p;
  EXPECT_EQ(
      parse_o_to_t(hex("0200 0280 0800 01000000 01000000 b100 0200 0700"), IoShape{false, 0}, p),
      IoParse::kOk);
  EXPECT_EQ(p.cip_sequence, 7);
  EXPECT_FALSE(p.run);
}

TEST(EnipIoPacket, Refusals) {
  IoPacket p;
  EXPECT_EQ(parse_o_to_t(kRunPacket, IoShape{true, 32}, p), IoParse::kWrongSize);  // a 3602's
  auto wrong_item = kRunPacket;
  wrong_item[2] = 0xA1;  // a connected address item (class 3), not a sequenced one
  wrong_item[3] = 0x00;
  EXPECT_EQ(parse_o_to_t(wrong_item, kOwner3601, p), IoParse::kMalformed);
  // Every truncation, and a connected data item too short for its header.
  for (std::size_t n = 0; n < kRunPacket.size(); ++n) {
    EXPECT_NE(parse_o_to_t(std::span(kRunPacket).first(n), kOwner3601, p), IoParse::kOk) << n;
  }
  EXPECT_EQ(parse_o_to_t(hex("0200 0280 0800 01000000 01000000 b100 0300 0700 01"), kOwner3601, p),
            IoParse::kMalformed);
}

TEST(EnipIoPacket, WritesTToOAsTheScannerReadsIt) {
  std::array<std::uint8_t, 128> out{};
  const auto words = hex("1100 2200 3300 4400 5500 6600 7700 8800");
  const std::size_t n = encode_t_to_o(out, 0x12345678u, 9, 3, words);
  // st-ethernet-ip takes the connection id at byte 6, the sequence at 10 and the data at 20.
  const auto want =
      hex("0200 0280 0800 78563412 09000000 b100 1200 0300"
          "1100 2200 3300 4400 5500 6600 7700 8800");
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + static_cast<long>(n)), want);
  EXPECT_EQ(encode_t_to_o(std::span(out).first(20), 1, 1, 1, words), 0u);
}

TEST(EnipIoPacket, SequenceNumbersWrap) {
  EXPECT_TRUE(sequence_newer(6, 5));
  EXPECT_FALSE(sequence_newer(5, 5));
  EXPECT_FALSE(sequence_newer(4, 5));
  EXPECT_TRUE(sequence_newer(2, 0xFFFFFFF0u));
  EXPECT_FALSE(sequence_newer(0xFFFFFFF0u, 2));
}

}  // namespace
}  // namespace stepmod::enip
