// A TCP connection's and a UDP datagram's encapsulation requests to their replies, as the npm
// clients send them (docs/ethernetip-design.md, "Encapsulation").
#include "fieldbus/enip/encap_session.hpp"

#include <gtest/gtest.h>

#include <array>

#include "fieldbus/enip/cpf.hpp"
#include "tests/enip/enip_bytes.hpp"
#include "tests/enip/router_fakes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;
using Bytes = std::vector<std::uint8_t>;

const Bytes kRegister = hex("6500 0400 00000000 00000000 0000000000000000 00000000 0100 0000");

// SendRRData with `session` around an Unconnected_Send (route port 1 / link 0) of Identity's
// Get_Attributes_All, as ethernet-ip reads the identity.
Bytes get_all_rr(std::uint8_t session) {
  Bytes b =
      hex("6f00 2400 00000000 00000000 0102030405060708 00000000"
          "00000000 0a00 0200 0000 0000 b200 1400"
          "52 02 20 06 24 01 07 f9 0600 01 02 20 01 24 01 01 00 01 00");
  b[4] = session;
  return b;
}

class EnipSession : public ::testing::Test {
 protected:
  SessionStep tcp(const Bytes& in, std::uint32_t connection = 1) {
    last_ = {};
    const SessionStep s = handle_tcp(in, connection, ctx_, out_);
    last_.assign(out_.begin(), out_.begin() + static_cast<long>(s.reply_size));
    return s;
  }
  // The reply's header status.
  std::uint32_t status() const { return last_.size() >= 12 ? last_[8] | (last_[9] << 8) : 999; }

  SessionTable sessions_;
  IdentityValues identity_ = identity_for(3601, 0x01020304u);
  test::FakeAssemblies assemblies_;
  test::FakeConnections connections_;
  test::FakeNetwork network_;
  RouterContext router_{
      identity_, assembly_layout(2, 8, 8), AdapterLimits{}, assemblies_, connections_,
      network_,  RequestOrigin{}};
  EncapContext ctx_{sessions_, identity_, SocketAddress{0x7F000001u, 44818}, router_};
  std::array<std::uint8_t, kEncapMaxFrame> out_{};
  Bytes last_;
};

TEST_F(EnipSession, RegisterThenReadTheIdentityThroughSendRRData) {
  ASSERT_EQ(tcp(kRegister).action, SessionAction::kReply);
  const std::uint8_t session = last_[4];
  const SessionStep s = tcp(get_all_rr(session));
  ASSERT_EQ(s.action, SessionAction::kReply);
  EXPECT_EQ(s.consumed, get_all_rr(session).size());
  const Bytes want =
      cat(hex("6f00 2f00 01000000 00000000 0102030405060708 00000000"
              "00000000 0000 0200 0000 0000 b200 1f00"),
          hex("81 00 00 00 ffff 2b00 110e 0101 3000 04030201 0c 737465706d6f642033363031"));
  EXPECT_EQ(last_, want);
}

TEST_F(EnipSession, SessionCommandsNeedThisConnectionsSession) {
  ASSERT_EQ(tcp(kRegister, 1).action, SessionAction::kReply);
  EXPECT_EQ(tcp(get_all_rr(1), 2).action, SessionAction::kReply);  // another connection
  EXPECT_EQ(status(), static_cast<std::uint32_t>(EncapStatus::kInvalidSession));
  tcp(get_all_rr(9), 1);
  EXPECT_EQ(status(), static_cast<std::uint32_t>(EncapStatus::kInvalidSession));
}

TEST_F(EnipSession, MalformedSendRRDataIsIncorrectData) {
  tcp(kRegister);
  Bytes b = get_all_rr(1);
  b[32] = 0xA1;  // a connected address item where the null address belongs
  tcp(b);
  EXPECT_EQ(status(), static_cast<std::uint32_t>(EncapStatus::kIncorrectData));
  EXPECT_EQ(assemblies_.writes, 0);
}

TEST_F(EnipSession, UnknownCommandsNopAndUnRegister) {
  Bytes unknown = kRegister;
  unknown[0] = 0x99;
  EXPECT_EQ(tcp(unknown).action, SessionAction::kReply);
  EXPECT_EQ(status(), static_cast<std::uint32_t>(EncapStatus::kInvalidCommand));
  EXPECT_EQ(tcp(hex("0000 0000 00000000 00000000 0000000000000000 00000000")).action,
            SessionAction::kNone);
  tcp(kRegister);
  const Bytes unregister = hex("6600 0000 01000000 00000000 0000000000000000 00000000");
  EXPECT_EQ(tcp(unregister).action, SessionAction::kClose);
}

TEST_F(EnipSession, FramingOutcomes) {
  EXPECT_EQ(tcp(Bytes(kRegister.begin(), kRegister.end() - 1)).consumed, 0u);  // wait for more
  Bytes huge = kRegister;
  huge[3] = 0x10;
  EXPECT_EQ(tcp(huge).action, SessionAction::kClose);
  Bytes with_options = kRegister;
  with_options[20] = 1;
  const SessionStep s = tcp(with_options);
  EXPECT_EQ(s.action, SessionAction::kNone);
  EXPECT_EQ(s.consumed, kRegister.size());  // skipped, the next frame is still found
}

TEST_F(EnipSession, ListServices) {
  tcp(hex("0400 0000 00000000 00000000 0000000000000000 00000000"));
  EXPECT_EQ(last_, hex("0400 1a00 00000000 00000000 0000000000000000 00000000"
                       "0100 0001 1400 0100 2001 436f6d6d756e69636174696f6e730000"));
}

TEST_F(EnipSession, UdpAnswersOnlyTheListCommands) {
  const Bytes list = hex("6300 0000 00000000 00000000 0000000000000000 00000000");
  const std::size_t n = handle_udp(list, ctx_, out_);
  ASSERT_GT(n, 24u);
  EXPECT_EQ(out_[0], 0x63);
  EXPECT_EQ(handle_udp(kRegister, ctx_, out_), 0u);
  EXPECT_EQ(sessions_.size(), 0u);
  EXPECT_EQ(handle_udp(cat(list, hex("00")), ctx_, out_), 0u);  // a trailing byte
  EXPECT_EQ(handle_udp(Bytes(list.begin(), list.end() - 1), ctx_, out_), 0u);
}

}  // namespace
}  // namespace stepmod::enip
