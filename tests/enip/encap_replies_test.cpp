// ListIdentity, RegisterSession and UnRegisterSession, byte for byte.
#include "fieldbus/enip/encap_replies.hpp"

#include <gtest/gtest.h>

#include <array>

#include "fieldbus/enip/cpf.hpp"
#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

EncapFrame frame_of(const std::vector<std::uint8_t>& b) {
  EncapFrame f;
  EXPECT_EQ(parse_encap(b, f), EncapParse::kFrame);
  return f;
}

std::vector<std::uint8_t> first(const std::array<std::uint8_t, 256>& out, std::size_t n) {
  return {out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n)};
}

const auto kRegister = hex("6500 0400 00000000 00000000 aabbccddeeff0011 00000000 0100 0000");

TEST(EnipReplies, ListIdentityReply) {
  const auto req = hex("6300 0000 00000000 00000000 0000000000000000 00000000");
  std::array<std::uint8_t, 256> out{};
  const IdentityValues id = identity_for(3601, 0x01020304u);
  const std::size_t n =
      encode_list_identity_reply(out, frame_of(req).header, id, {0x7F000001u, 44818});
  const auto want =
      hex("6300 3400 00000000 00000000 0000000000000000 00000000"
          "0100 0c00 2e00"                            // one item, CIP identity, 46 bytes
          "0100 0002 af12 7f000001 0000000000000000"  // version 1, AF_INET, port, address
          "ffff 2b00 110e 0101 3000 04030201"         // vendor .. serial
          "0c 737465706d6f642033363031 03");          // "stepmod 3601", state operational
  EXPECT_EQ(first(out, n), want);
  // The reply is a well-formed frame with one well-formed CPF item.
  const auto reply_bytes = first(out, n);  // the frame views these bytes: keep them
  const EncapFrame back = frame_of(reply_bytes);
  Cpf cpf;
  EXPECT_EQ(parse_cpf(back.data, cpf), CpfParse::kOk);
}

TEST(EnipReplies, RegisterSessionGivesAHandleBoundToTheConnection) {
  SessionTable sessions;
  std::array<std::uint8_t, 256> out{};
  const RegisterResult r = handle_register_session(out, frame_of(kRegister), sessions, 7);
  ASSERT_NE(r.session, 0u);
  EXPECT_TRUE(sessions.valid(r.session, 7));
  EXPECT_FALSE(sessions.valid(r.session, 8));
  const auto reply_bytes = first(out, r.reply_size);  // the frame views these bytes
  const EncapFrame reply = frame_of(reply_bytes);
  EXPECT_EQ(reply.header.session, r.session);
  EXPECT_EQ(reply.header.status, 0u);
  EXPECT_EQ(reply.header.context[0], 0xaa);
  EXPECT_EQ(std::vector<std::uint8_t>(reply.data.begin(), reply.data.end()), hex("0100 0000"));
}

TEST(EnipReplies, RegisterSessionRefusals) {
  SessionTable sessions;
  std::array<std::uint8_t, 256> out{};
  EncapFrame f;
  const auto check = [&](const std::vector<std::uint8_t>& req, EncapStatus want) {
    const RegisterResult r = handle_register_session(out, frame_of(req), sessions, 1);
    EXPECT_EQ(r.session, 0u);
    ASSERT_NE(r.reply_size, 0u);
    // A refusal is a reply, not a frame to discard: its status is read back from the header.
    EXPECT_EQ(parse_encap(first(out, r.reply_size), f),
              want == EncapStatus::kSuccess ? EncapParse::kFrame : EncapParse::kDiscard);
    EXPECT_EQ(f.header.status, static_cast<std::uint32_t>(want));
  };
  check(hex("6500 0200 00000000 00000000 0000000000000000 00000000 0100"),
        EncapStatus::kInvalidLength);
  check(hex("6500 0400 00000000 00000000 0000000000000000 00000000 0200 0000"),
        EncapStatus::kUnsupportedProtocol);
  check(hex("6500 0400 00000000 00000000 0000000000000000 00000000 0100 0100"),
        EncapStatus::kUnsupportedProtocol);
  ASSERT_NE(handle_register_session(out, frame_of(kRegister), sessions, 1).session, 0u);
  check(kRegister, EncapStatus::kInvalidCommand);  // a second session on one connection
  EXPECT_EQ(sessions.size(), 1u);
}

TEST(EnipReplies, SessionsRunOutAndHandlesAreNotReusedSoon) {
  SessionTable sessions;
  std::array<std::uint8_t, 256> out{};
  std::uint32_t last = 0;
  for (std::uint32_t c = 1; c <= kMaxSessions; ++c) {
    last = handle_register_session(out, frame_of(kRegister), sessions, c).session;
    ASSERT_NE(last, 0u);
  }
  const RegisterResult full = handle_register_session(out, frame_of(kRegister), sessions, 99);
  EXPECT_EQ(full.session, 0u);
  EXPECT_EQ(frame_of(kRegister).header.status, 0u);
  sessions.remove(3);
  const RegisterResult again = handle_register_session(out, frame_of(kRegister), sessions, 99);
  EXPECT_GT(again.session, last);
}

TEST(EnipReplies, UnRegisterClosesItsOwnSessionOnly) {
  SessionTable sessions;
  std::array<std::uint8_t, 256> out{};
  const std::uint32_t s = handle_register_session(out, frame_of(kRegister), sessions, 5).session;
  auto req = hex("6600 0000 00000000 00000000 0000000000000000 00000000");
  req[4] = static_cast<std::uint8_t>(s);
  const UnregisterResult other = handle_unregister_session(out, frame_of(req), sessions, 6);
  EXPECT_FALSE(other.close);
  EncapFrame f;
  ASSERT_EQ(parse_encap(first(out, other.reply_size), f), EncapParse::kDiscard);
  EXPECT_EQ(f.header.status, static_cast<std::uint32_t>(EncapStatus::kInvalidSession));
  EXPECT_TRUE(sessions.valid(s, 5));
  const UnregisterResult own = handle_unregister_session(out, frame_of(req), sessions, 5);
  EXPECT_TRUE(own.close);
  EXPECT_EQ(own.reply_size, 0u);
  EXPECT_EQ(sessions.size(), 0u);
}

}  // namespace
}  // namespace stepmod::enip
