// The message router and its object table: Identity, Assembly (the owner rule), the Connection
// Manager through Unconnected_Send as the npm clients send it, and every refusal's status.
#include "fieldbus/enip/message_router.hpp"

#include <gtest/gtest.h>

#include <array>

#include "tests/enip/enip_bytes.hpp"
#include "tests/enip/router_fakes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;
using Bytes = std::vector<std::uint8_t>;

class EnipRouter : public test::RouterFixture {
 protected:
  // The request wrapped as st-ethernet-ip and ethernet-ip send it: Unconnected_Send to the
  // Connection Manager, route port 1 / link 0.
  static Bytes ucmm(const Bytes& message, const Bytes& route = hex("01 00")) {
    Bytes b = hex("52 02 20 06 24 01 07 f9");
    b.push_back(static_cast<std::uint8_t>(message.size()));
    b.push_back(static_cast<std::uint8_t>(message.size() >> 8));
    b = cat(b, message);
    if (message.size() % 2 != 0) b.push_back(0);
    b.push_back(static_cast<std::uint8_t>(route.size() / 2));
    b.push_back(0);
    return cat(b, route);
  }
};

const Bytes kGetAll = hex("01 02 20 01 24 01");

TEST_F(EnipRouter, IdentityGetAttributesAllDirectAndThroughUnconnectedSend) {
  const Bytes want = cat(hex("81 00 00 00"), hex("ffff 2b00 110e 0101 3000 04030201 0c"
                                                 "737465706d6f642033363031"));
  EXPECT_EQ(ask(kGetAll), want);
  EXPECT_EQ(ask(ucmm(kGetAll)), want);  // the embedded request's reply is the reply
}

TEST_F(EnipRouter, IdentitySingleAttributesAndRefusals) {
  EXPECT_EQ(ask(hex("0e 03 20 01 24 01 30 07")),
            cat(hex("8e 00 00 00 0c"), hex("737465706d6f642033363031")));
  EXPECT_EQ(ask(hex("0e 03 20 01 24 01 30 09")), hex("8e 00 14 00"));     // no attribute 9
  EXPECT_EQ(ask(hex("0e 02 20 01 24 02")), hex("8e 00 05 00"));           // no instance 2
  EXPECT_EQ(ask(hex("10 03 20 01 24 01 30 07 00")), hex("90 00 08 00"));  // not settable here
  EXPECT_EQ(ask(hex("01 02 20 01 24 01 00")), hex("81 00 15 00"));        // data after the path
  EXPECT_EQ(ask(hex("01 02 20 77 24 01")), hex("81 00 05 00"));           // no class 0x77
}

TEST_F(EnipRouter, MalformedRequests) {
  EXPECT_EQ(ask(hex("01 03 20 01 24 01")), hex("81 00 13 00"));  // the path runs out
  EXPECT_EQ(ask(hex("01")), hex("81 00 13 00"));
  EXPECT_EQ(ask(hex("")), hex("80 00 13 00"));
  EXPECT_EQ(ask(hex("01 01 91 00")), hex("81 00 04 00"));  // not a class path
}

TEST_F(EnipRouter, AssemblyReadsAndTheOwnerRuleOnWrites) {
  EXPECT_EQ(ask(hex("0e 03 20 04 24 64 30 03")),
            hex("8e 00 00 00 10 11 12 13 14 15 16 17 18 19 1a 1b 1c 1d 1e 1f"));
  const Bytes set = cat(hex("10 03 20 04 24 96 30 03"), Bytes(16, 0x5A));
  EXPECT_EQ(ask(set), hex("90 00 00 00"));
  EXPECT_EQ(assemblies.writes, 1);
  EXPECT_EQ(assemblies.output[15], 0x5A);
  EXPECT_EQ(ask(cat(hex("10 03 20 04 24 96 30 03"), Bytes(15, 1))), hex("90 00 13 00"));
  EXPECT_EQ(ask(cat(hex("10 03 20 04 24 96 30 03"), Bytes(17, 1))), hex("90 00 15 00"));
  EXPECT_EQ(ask(cat(hex("10 03 20 04 24 64 30 03"), Bytes(16, 1))), hex("90 00 0e 00"));
  connections.owner = true;
  EXPECT_EQ(ask(set), hex("90 00 0c 00"));  // an owner writes the outputs: explicit writes wait
  EXPECT_EQ(assemblies.writes, 1);
  EXPECT_EQ(ask(hex("0e 03 20 04 24 65 30 03")), hex("8e 00 05 00"));  // no instance 101
}

const Bytes kForwardOpen =
    hex("54 02 20 06 24 01"
        "03 7d 00000000 78563412 3412 3333 37130000 03 000000 10270000 1648 10270000 1248 01"
        "09 34 04 0000 0000 0000 00 00 20 04 24 97 2c 96 2c 64");

TEST_F(EnipRouter, ForwardOpenThroughUnconnectedSendThenASecondOwner) {
  EXPECT_EQ(ask(ucmm(kForwardOpen)),
            hex("d4 00 00 00 d0c0b0a0 78563412 3412 3333 37130000 10270000 10270000 00 00"));
  EXPECT_TRUE(connections.owner);
  EXPECT_EQ(ask(ucmm(kForwardOpen)), hex("d4 00 01 01 0601 3412 3333 37130000 00 00"));
}

TEST_F(EnipRouter, ForwardCloseByTheTriad) {
  ASSERT_EQ(ask(kForwardOpen)[2], 0x00);
  const Bytes close = hex("4e 02 20 06 24 01 03 7d 3412 3333 37130000 03 00 01 00 20 02 24 01");
  EXPECT_EQ(ask(close), hex("ce 00 00 00 3412 3333 37130000 00 00"));
  EXPECT_FALSE(connections.owner);
  EXPECT_EQ(ask(close), hex("ce 00 01 01 0701 3412 3333 37130000 00 00"));
}

TEST_F(EnipRouter, UnconnectedSendRefusals) {
  // A route elsewhere (port 1, slot 3): we have no backplane to forward to.
  EXPECT_EQ(ask(ucmm(kGetAll, hex("01 03"))), hex("d2 00 01 01 1103 01"));
  // An Unconnected_Send inside one is not routed further.
  EXPECT_EQ(ask(ucmm(ucmm(kGetAll))), hex("d2 00 08 00"));
  Bytes cut = ucmm(kGetAll);
  cut.pop_back();
  EXPECT_EQ(ask(cut), hex("d2 00 13 00"));
  Bytes longer = ucmm(kGetAll);
  longer.push_back(0);
  EXPECT_EQ(ask(longer), hex("d2 00 15 00"));
}

}  // namespace
}  // namespace stepmod::enip
