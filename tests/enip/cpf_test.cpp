// The common packet format: items as views into the packet, every length checked.
#include "fieldbus/enip/cpf.hpp"

#include <gtest/gtest.h>

#include <array>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

// SendRRData's data: interface 0, timeout 10, a null address item and an unconnected data item
// holding Get_Attributes_All of the Identity object.
const auto kRRData =
    hex("00000000 0a00"
        "0200 0000 0000 b200 0600 01 02 20 01 24 01");

TEST(EnipCpf, ParsesSendDataAndItsItems) {
  SendData s;
  ASSERT_EQ(parse_send_data(kRRData, s), CpfParse::kOk);
  EXPECT_EQ(s.interface_handle, 0u);
  EXPECT_EQ(s.timeout, 10);
  ASSERT_EQ(s.cpf.count, 2u);
  EXPECT_EQ(s.cpf.items[0].type, cpf_item::kNullAddress);
  EXPECT_TRUE(s.cpf.items[0].data.empty());
  EXPECT_EQ(s.cpf.items[1].type, cpf_item::kUnconnectedData);
  ASSERT_EQ(s.cpf.items[1].data.size(), 6u);
  EXPECT_EQ(s.cpf.items[1].data[0], 0x01);
}

TEST(EnipCpf, EveryTruncationIsRefused) {
  for (std::size_t n = 0; n < kRRData.size(); ++n) {
    SendData s;
    EXPECT_NE(parse_send_data(std::span(kRRData).first(n), s), CpfParse::kOk) << n;
  }
}

TEST(EnipCpf, AnItemLongerThanThePacketIsTruncated) {
  auto b = kRRData;
  b[14] = 0x07;  // the data item claims 7 bytes, 6 are there
  SendData s;
  EXPECT_EQ(parse_send_data(b, s), CpfParse::kTruncated);
}

TEST(EnipCpf, BytesAfterTheLastItemAreRefused) {
  auto b = kRRData;
  b.push_back(0);
  SendData s;
  EXPECT_EQ(parse_send_data(b, s), CpfParse::kTrailingBytes);
}

TEST(EnipCpf, NoItemsOrTooManyAreRefused) {
  Cpf c;
  EXPECT_EQ(parse_cpf(hex("0000"), c), CpfParse::kTooManyItems);
  EXPECT_EQ(parse_cpf(hex("0500 0000 0000 0000 0000 0000 0000 0000 0000 0000 0000"), c),
            CpfParse::kTooManyItems);
  EXPECT_EQ(parse_cpf(hex("ffff"), c), CpfParse::kTooManyItems);
}

TEST(EnipCpf, WritesItemsWithTheirLengths) {
  std::array<std::uint8_t, 32> buf{};
  Writer w(buf);
  w.u16(2);
  put_item(w, cpf_item::kNullAddress, {});
  CpfItemWriter data(w, cpf_item::kUnconnectedData);
  w.u8(0x81);
  w.u8(0);
  w.u8(0);
  w.u8(0);
  data.end();
  ASSERT_TRUE(w.ok());
  const auto want = hex("0200 0000 0000 b200 0400 81 00 00 00");
  EXPECT_EQ(std::vector<std::uint8_t>(w.written().begin(), w.written().end()), want);
  Cpf back;
  EXPECT_EQ(parse_cpf(w.written(), back), CpfParse::kOk);
}

}  // namespace
}  // namespace stepmod::enip
