// Broadcast ListIdentity (docs/ethernetip-design.md, "Encapsulation"): which broadcasts an
// adapter answers, the delay its sender allows, and the bounded queue of delayed answers.
#include "fieldbus/enip/broadcast.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

constexpr std::uint32_t kLimited = BroadcastScope::kLimitedBroadcast;
constexpr std::uint32_t ip(unsigned a, unsigned b, unsigned c, unsigned d) {
  return (a << 24) | (b << 16) | (c << 8) | d;
}
// A board: loopback (1), eth0 (2) 192.168.1.20/24, wlan0 (3) 10.0.0.7/8.
const std::vector<InterfaceAddress> kBoard = {
    {1, ip(127, 0, 0, 1), 0},
    {2, ip(192, 168, 1, 20), ip(192, 168, 1, 255)},
    {3, ip(10, 0, 0, 7), ip(10, 255, 255, 255)},
};

TEST(EnipBroadcast, AnAddressAnswersTheBroadcastsOfItsOwnInterfaceOnly) {
  const BroadcastScope s = BroadcastScope::for_listen(ip(192, 168, 1, 20), kBoard);
  EXPECT_TRUE(s.enabled());
  EXPECT_TRUE(s.needs_own_socket()) << "a socket bound to the address receives no broadcast";
  EXPECT_TRUE(s.accepts(2, kLimited));
  EXPECT_TRUE(s.accepts(2, ip(192, 168, 1, 255)));
  EXPECT_FALSE(s.accepts(3, kLimited)) << "another interface's broadcast";
  EXPECT_FALSE(s.accepts(2, ip(10, 255, 255, 255))) << "another subnet's broadcast";
  EXPECT_FALSE(s.accepts(2, ip(192, 168, 1, 20))) << "unicast is the unicast socket's";
}

TEST(EnipBroadcast, LoopbackOrAnAddressNoInterfaceHoldsAnswersNoBroadcast) {
  for (const std::uint32_t listen : {ip(127, 0, 0, 1), ip(127, 0, 101, 1), ip(192, 168, 9, 9)}) {
    const BroadcastScope s = BroadcastScope::for_listen(listen, kBoard);
    EXPECT_FALSE(s.enabled()) << listen;
    EXPECT_FALSE(s.needs_own_socket()) << listen;
    EXPECT_FALSE(s.accepts(2, kLimited)) << listen;
    EXPECT_FALSE(s.accepts(1, kLimited)) << listen;
  }
}

TEST(EnipBroadcast, AnyAddressAnswersEveryInterfacesBroadcastsOnItsOwnSocket) {
  const BroadcastScope s = BroadcastScope::for_listen(0, kBoard);
  EXPECT_TRUE(s.enabled());
  EXPECT_FALSE(s.needs_own_socket()) << "a socket on 0.0.0.0 receives the broadcasts itself";
  EXPECT_TRUE(s.accepts(2, kLimited));
  EXPECT_TRUE(s.accepts(3, kLimited));
  EXPECT_TRUE(s.accepts(3, ip(10, 255, 255, 255)));
  EXPECT_TRUE(s.accepts(2, ip(192, 168, 1, 255)));
  EXPECT_FALSE(s.accepts(2, ip(192, 168, 1, 20))) << "unicast: answered at once, not delayed";
  EXPECT_FALSE(BroadcastScope::for_listen(0, std::vector<InterfaceAddress>{kBoard[0]}).enabled())
      << "a machine with loopback only";
}

std::vector<std::uint8_t> list_identity_with_context(const char* context_hex) {
  return hex(std::string("6300 0000 00000000 00000000 ") + context_hex + " 00000000");
}

TEST(EnipBroadcast, TheDelayIsTheSendersMaximumWithTheSpecsFloorAndDefault) {
  const auto ms = [](const char* context) {
    return list_identity_max_delay(list_identity_with_context(context)).value_or(-1) / kNsPerMs;
  };
  EXPECT_EQ(ms("0000 000000000000"), 2000) << "0: the default 2000 ms";
  EXPECT_EQ(ms("6400 000000000000"), 500) << "100 ms: raised to 500";
  EXPECT_EQ(ms("f401 000000000000"), 500);
  EXPECT_EQ(ms("dc05 ffffffffffff"), 1500) << "the first 16 bits, little-endian";
  EXPECT_EQ(ms("ffff 000000000000"), 65535);
}

TEST(EnipBroadcast, OnlyAWholeListIdentityIsAnsweredToABroadcast) {
  EXPECT_FALSE(
      list_identity_max_delay(hex("0400 0000 00000000 00000000 0000000000000000 00000000")))
      << "ListServices";
  EXPECT_FALSE(
      list_identity_max_delay(hex("6400 0000 00000000 00000000 0000000000000000 00000000")))
      << "ListInterfaces";
  EXPECT_FALSE(list_identity_max_delay(hex("6300 0000 00000000 00000000 00000000")))
      << "a header cut short";
  EXPECT_FALSE(
      list_identity_max_delay(hex("6300 0000 00000000 01000000 0000000000000000 00000000")))
      << "a status not 0: the spec says ignore";
}

sockaddr_in to(std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = port;
  return a;
}

TEST(EnipBroadcast, DelayedRepliesGoEachAtItsTimeAndAFullQueueTakesNoMore) {
  DelayedReplies q;
  EXPECT_EQ(q.next_due(), std::numeric_limits<Nanos>::max());
  const std::vector<std::uint8_t> reply = {1, 2, 3};
  for (std::size_t i = 0; i < DelayedReplies::kSlots; ++i) {
    EXPECT_TRUE(q.add(static_cast<Nanos>(100 - i), to(static_cast<std::uint16_t>(i)), reply));
  }
  EXPECT_FALSE(q.add(1, to(99), reply)) << "every slot waits: the broadcast is not answered";
  EXPECT_FALSE(q.add(1, to(3), reply)) << "its sender's answer waits already";
  EXPECT_EQ(q.next_due(), static_cast<Nanos>(100 - DelayedReplies::kSlots + 1));
  std::vector<std::uint16_t> sent;
  const auto send = [&](const sockaddr_in& a, std::span<const std::uint8_t> bytes) {
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), reply);
    sent.push_back(a.sin_port);
  };
  q.send_due(97, send);
  EXPECT_EQ(sent, (std::vector<std::uint16_t>{3, 4, 5, 6, 7})) << "due at 97 or before";
  q.send_due(97, send);
  EXPECT_EQ(sent.size(), 5u) << "each is sent once";
  EXPECT_EQ(q.next_due(), 98);
  EXPECT_TRUE(q.add(50, to(42), reply)) << "a sent reply's slot is free again";
  EXPECT_TRUE(q.add(50, to(3), reply)) << "and its sender may ask again";
  EXPECT_FALSE(q.add(50, to(43), std::vector<std::uint8_t>(DelayedReplies::kMaxReply + 1)));
  q.send_due(1000, send);
  EXPECT_EQ(sent.size(), 10u);
  EXPECT_EQ(q.next_due(), std::numeric_limits<Nanos>::max());
}

}  // namespace
}  // namespace stepmod::enip
