// The TCP/IP Interface (0xF5) and Ethernet Link (0xF6) objects through the message router, on
// the fake board interface of router_fakes.hpp (10.0.0.5/24 on eth0): Get_Attributes_All byte for
// byte (every attribute in order, the ones stepmod does not have as their defaults),
// Get_Attribute_Single, and the refusals.
#include <gtest/gtest.h>

#include <array>

#include "fieldbus/enip/message_router.hpp"
#include "fieldbus/enip/tcpip_objects.hpp"
#include "tests/enip/enip_bytes.hpp"
#include "tests/enip/router_fakes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;
using Bytes = std::vector<std::uint8_t>;

// The router as the router's tests ask it, on the fake board interface.
class EnipInterfaceObjects : public test::RouterFixture {};

// Attribute 5: 10.0.0.5, 255.255.255.0, gateway and name server 10.0.0.1, no second one, domain
// "plant.local" (11 characters and a pad byte).
const Bytes kInterfaceConfiguration =
    hex("0500000a 00ffffff 0100000a 0100000a 00000000 0b00 706c616e742e6c6f63616c 00");
const Bytes kHostName = hex("0a00 737465706d6f642d7069");  // "stepmod-pi", even: no pad

TEST_F(EnipInterfaceObjects, TcpIpGetAttributesAllGivesAttributes1To13InOrder) {
  const Bytes want = cat(cat(hex("81 00 00 00"
                                 "01000000"          // 1 status: configured
                                 "00000000"          // 2 capability: nothing settable
                                 "00000000"          // 3 control: the stored configuration
                                 "0200 20f6 2401"),  // 4 the path to Ethernet Link 1
                             kInterfaceConfiguration),
                         cat(kHostName, hex("000000000000"         // 7 safety network number
                                            "01"                   // 8 TTL
                                            "00 00 0000 00000000"  // 9 multicast
                                            "00"                   // 10 select ACD
                                            "0000000000000000000000000000000000"
                                            "000000000000000000000000000000000000"  // 11
                                            "00"                                    // 12
                                            "0000")));  // 13 inactivity timeout: off
  EXPECT_EQ(ask(hex("01 02 20 f5 24 01")), want);
}

TEST_F(EnipInterfaceObjects, TcpIpSingleAttributes) {
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 01")), hex("8e 00 00 00 01000000"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 04")), hex("8e 00 00 00 0200 20f6 2401"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 05")), cat(hex("8e 00 00 00"), kInterfaceConfiguration));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 06")), cat(hex("8e 00 00 00"), kHostName));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 0d")), hex("8e 00 00 00 0000"));
  // Only defaults inside Get_Attributes_All: not served alone.
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 07")), hex("8e 00 14 00"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 0b")), hex("8e 00 14 00"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 01 30 0e")), hex("8e 00 14 00"));
}

TEST_F(EnipInterfaceObjects, EthernetLinkGetAttributesAllGivesAttributes1To11InOrder) {
  const Bytes interface_counters = cat(hex("44332211"), Bytes(40, 0));
  const Bytes media_counters = cat(hex("00000000 07000000"), Bytes(40, 0));
  const Bytes want = cat(cat(hex("81 00 00 00"
                                 "64000000"        // 1 speed: 100 Mbit/s
                                 "0f000000"        // 2 flags: link, full duplex, negotiated
                                 "d83add010203"),  // 3 MAC
                             cat(interface_counters, media_counters)),
                         hex("0100 0000"       // 6 control: auto-negotiation
                             "02"              // 7 type: twisted pair
                             "01 01"           // 8, 9 interface and admin state: enabled
                             "04 65746830"     // 10 label "eth0"
                             "02000000 00"));  // 11 capability: auto-negotiation
  EXPECT_EQ(ask(hex("01 02 20 f6 24 01")), want);
  EXPECT_EQ(ask(hex("0e 03 20 f6 24 01 30 03")), hex("8e 00 00 00 d83add010203"));
  EXPECT_EQ(ask(hex("0e 03 20 f6 24 01 30 0a")), hex("8e 00 00 00 04 65746830"));
  EXPECT_EQ(ask(hex("0e 03 20 f6 24 01 30 0c")), hex("8e 00 14 00"));  // no HC counters
}

TEST_F(EnipInterfaceObjects, RefusalsAndNothingSettable) {
  EXPECT_EQ(ask(hex("01 02 20 f5 24 02")), hex("81 00 05 00"));        // no instance 2
  EXPECT_EQ(ask(hex("0e 02 20 f6 24 01")), hex("8e 00 14 00"));        // no attribute given
  EXPECT_EQ(ask(hex("01 03 20 f5 24 01 30 01")), hex("81 00 05 00"));  // All of one attribute
  EXPECT_EQ(ask(hex("01 02 20 f5 24 01 00")), hex("81 00 15 00"));     // data after the path
  EXPECT_EQ(ask(hex("10 03 20 f5 24 01 30 06 0000")), hex("90 00 0e 00"));
  EXPECT_EQ(ask(hex("10 03 20 f6 24 01 30 06 0100 0000")), hex("90 00 0e 00"));
  EXPECT_EQ(ask(hex("10 03 20 f5 24 01 30 0e 00")), hex("90 00 14 00"));  // no attribute 14
  EXPECT_EQ(ask(hex("10 03 20 f6 24 01 30 0c 00")), hex("90 00 14 00"));  // nor 12
  EXPECT_EQ(ask(hex("4b 02 20 f5 24 01")), hex("cb 00 08 00"));           // no such service
  // A request that came in on an address no interface has (it went away): refused, not guessed.
  EXPECT_EQ(ask(hex("01 02 20 f5 24 01"), 0x0A000009u), hex("81 00 0c 00"));
}

// Instance 0: revision, highest instance, instances, highest class and instance attribute.
TEST_F(EnipInterfaceObjects, ClassAttributes) {
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 00 30 01")), hex("8e 00 00 00 0400"));  // revision 4
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 00 30 02")), hex("8e 00 00 00 0100"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 00 30 03")), hex("8e 00 00 00 0100"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 00 30 06")), hex("8e 00 00 00 0700"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 00 30 07")), hex("8e 00 00 00 0d00"));  // 13
  EXPECT_EQ(ask(hex("0e 03 20 f6 24 00 30 01")), hex("8e 00 00 00 0400"));
  EXPECT_EQ(ask(hex("0e 03 20 f6 24 00 30 07")), hex("8e 00 00 00 0b00"));  // 11
  EXPECT_EQ(ask(hex("0e 03 20 01 24 00 30 01")), hex("8e 00 00 00 0100"));  // Identity: 1
  EXPECT_EQ(ask(hex("0e 03 20 01 24 00 30 07")), hex("8e 00 00 00 0800"));
  EXPECT_EQ(ask(hex("0e 03 20 f5 24 00 30 04")), hex("8e 00 14 00"));       // no optional list
  EXPECT_EQ(ask(hex("0e 02 20 f5 24 00")), hex("8e 00 14 00"));             // no attribute
  EXPECT_EQ(ask(hex("0e 03 20 04 24 00 30 01")), hex("8e 00 05 00"));       // not the Assembly's
  EXPECT_EQ(ask(hex("10 03 20 f5 24 00 30 01 0500")), hex("90 00 05 00"));  // not settable
}

TEST(EnipLinkFlags, LinkDuplexAndNegotiation) {
  NetInterface n;
  EXPECT_EQ(interface_flags(n), link_flags::kNegotiationNotAttempted);  // the loopback
  n.link_up = true;
  n.duplex = Duplex::kFull;
  n.negotiation = Negotiation::kAuto;
  EXPECT_EQ(interface_flags(n), 0x0Fu);
  n.link_up = false;  // the cable pulled: negotiating again
  EXPECT_EQ(interface_flags(n), link_flags::kFullDuplex | link_flags::kNegotiationInProgress);
  n.link_up = true;
  n.negotiation = Negotiation::kForced;
  n.duplex = Duplex::kHalf;
  EXPECT_EQ(interface_flags(n), link_flags::kLinkActive | link_flags::kNegotiationNotAttempted);
}

}  // namespace
}  // namespace stepmod::enip
