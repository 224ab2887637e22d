// Modbus/TCP framing (ipc/mbap.hpp) and the [modbus] allow list (ipc/modbus_allow.hpp).
#include "ipc/mbap.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>

#include <vector>

#include "ipc/modbus_allow.hpp"

namespace stepmod::ipc {
namespace {

// A read of input register 0, count 1, with the given header fields; `extra` PDU bytes appended.
std::vector<std::uint8_t> frame(std::uint16_t protocol, std::uint16_t length, std::uint8_t fc = 4,
                                const std::vector<std::uint8_t>& extra = {}) {
  std::vector<std::uint8_t> f = {0x12,
                                 0x34,
                                 static_cast<std::uint8_t>(protocol >> 8),
                                 static_cast<std::uint8_t>(protocol),
                                 static_cast<std::uint8_t>(length >> 8),
                                 static_cast<std::uint8_t>(length),
                                 1,
                                 fc,
                                 0,
                                 0,
                                 0,
                                 1};
  // (push_back, not insert: GCC 12 -O3 -Warray-bounds false positive on the insert)
  for (const std::uint8_t b : extra) f.push_back(b);
  return f;
}

TEST(Mbap, AWholeFrameIsExactlyWhatItsLengthFieldSays) {
  const auto f = frame(0, 6);
  MbapFrame m;
  ASSERT_EQ(parse_mbap(f, m), MbapStatus::kFrame);
  EXPECT_EQ(m.transaction, 0x1234);
  EXPECT_EQ(m.unit, 1);
  EXPECT_EQ(m.size, 12u);
  EXPECT_EQ(m.pdu.size(), 5u);
  // Every shorter prefix: wait for more.
  for (std::size_t n = 0; n < f.size(); ++n) {
    EXPECT_EQ(parse_mbap(std::span(f).first(n), m), MbapStatus::kIncomplete) << n;
  }
}

TEST(Mbap, ProtocolIdOtherThanZeroIsRefusedAsSoonAsItIsThere) {
  MbapFrame m;
  const auto f = frame(1, 6);
  EXPECT_EQ(parse_mbap(std::span(f).first(4), m), MbapStatus::kBadProtocol);
  EXPECT_EQ(parse_mbap(frame(0x100, 6), m), MbapStatus::kBadProtocol);
}

TEST(Mbap, LengthOutside2To254IsRefused) {
  MbapFrame m;
  for (const std::uint16_t bad : {0, 1, 255, 300, 65535}) {
    EXPECT_EQ(parse_mbap(frame(0, bad), m), MbapStatus::kBadLength) << bad;
  }
  // 2 is a frame (unit + function only): the map answers it with exception 03.
  EXPECT_EQ(parse_mbap(frame(0, 2), m), MbapStatus::kFrame);
  EXPECT_EQ(m.pdu.size(), 1u);
  // A length the bytes have not reached yet: incomplete (the server's time-out closes it).
  EXPECT_EQ(parse_mbap(frame(0, 100), m), MbapStatus::kIncomplete);
}

TEST(Mbap, ExceptionFunctionCodesAreRefusedNotAnswered) {
  MbapFrame m;
  EXPECT_EQ(parse_mbap(frame(0, 6, 0x80), m), MbapStatus::kBadFunction);
  EXPECT_EQ(parse_mbap(frame(0, 6, 0xFF), m), MbapStatus::kBadFunction);
  EXPECT_EQ(parse_mbap(frame(0, 6, 0x7F), m), MbapStatus::kFrame);
}

TEST(Mbap, TrailingBytesAreTheNextFrameNotPartOfThisOne) {
  const auto f = frame(0, 6, 4, {0xAA, 0xBB});
  MbapFrame m;
  ASSERT_EQ(parse_mbap(f, m), MbapStatus::kFrame);
  EXPECT_EQ(m.size, 12u);
  EXPECT_EQ(m.pdu.size(), 5u);
}

TEST(Mbap, ResponsesEchoTheHeaderAndCarryTheValuesOrTheException) {
  const auto f = frame(0, 6);
  MbapFrame m;
  ASSERT_EQ(parse_mbap(f, m), MbapStatus::kFrame);
  ModbusResult r;
  r.function = 4;
  r.count = 2;
  r.values[0] = 0x0102;
  r.values[1] = 0xA0B0;
  std::vector<std::uint8_t> out;
  append_response(out, m, r);
  EXPECT_EQ(out, (std::vector<std::uint8_t>{0x12, 0x34, 0, 0, 0, 7, 1, 4, 4, 1, 2, 0xA0, 0xB0}));
  out.clear();
  r.exception = ModbusException::kIllegalDataValue;
  append_response(out, m, r);
  EXPECT_EQ(out, (std::vector<std::uint8_t>{0x12, 0x34, 0, 0, 0, 3, 1, 0x84, 3}));
}

TEST(Mbap, MapAnswersAPduLongerOrShorterThanItsFunctionWithException03) {
  stepmod_image_t img{};
  img.word_bytes = 2;
  img.input_words = 8;
  img.output_words = 8;
  ModbusMap map(img, false);
  const std::vector<std::uint8_t> longer = {4, 0, 0, 0, 1, 0};
  const std::vector<std::uint8_t> shorter = {4, 0, 0, 0};
  const std::vector<std::uint8_t> bare = {4};
  EXPECT_EQ(map.handle(longer).exception, ModbusException::kIllegalDataValue);
  EXPECT_EQ(map.handle(shorter).exception, ModbusException::kIllegalDataValue);
  EXPECT_EQ(map.handle(bare).exception, ModbusException::kIllegalDataValue);
}

std::uint32_t ip(const char* s) {
  in_addr a{};
  inet_pton(AF_INET, s, &a);
  return a.s_addr;
}

TEST(ModbusAllow, AddressesAndNetworks) {
  const std::vector<AllowNet> nets = {*parse_allow_net("127.0.0.1"),
                                      *parse_allow_net("10.0.0.0/8")};
  EXPECT_TRUE(address_allowed(nets, ip("127.0.0.1")));
  EXPECT_FALSE(address_allowed(nets, ip("127.0.0.2")));
  EXPECT_TRUE(address_allowed(nets, ip("10.200.3.4")));
  EXPECT_FALSE(address_allowed(nets, ip("11.0.0.1")));
  EXPECT_TRUE(address_allowed({}, ip("192.0.2.1"))) << "no list: any";
  EXPECT_TRUE(address_allowed(std::vector{*parse_allow_net("0.0.0.0/0")}, ip("192.0.2.1")));
  // Host bits beyond the prefix are ignored.
  EXPECT_TRUE(address_allowed(std::vector{*parse_allow_net("192.168.1.77/24")}, ip("192.168.1.5")));
}

TEST(ModbusAllow, MalformedEntriesAreRefused) {
  for (const char* bad : {"", "localhost", "10.0.0.0/", "10.0.0.0/33", "10.0.0/8", "::1",
                          "10.0.0.0/8x", "1.2.3.4/-1"}) {
    EXPECT_FALSE(parse_allow_net(bad).has_value()) << bad;
  }
}

}  // namespace
}  // namespace stepmod::ipc
