// The encapsulation header: every field judged, bad frames discarded or refused, never read
// beyond their end (docs/ethernetip-design.md, "Encapsulation").
#include "fieldbus/enip/encap.hpp"

#include <gtest/gtest.h>

#include <array>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;

// RegisterSession as the npm clients send it: session 0, context 0, version 1, options 0.
const auto kRegister =
    hex("65 00 04 00 00000000 00000000 0102030405060708 00000000"
        "01 00 00 00");

TEST(EnipEncap, ParsesAWholeFrame) {
  EncapFrame f;
  ASSERT_EQ(parse_encap(kRegister, f), EncapParse::kFrame);
  EXPECT_EQ(f.header.command, encap_cmd::kRegisterSession);
  EXPECT_EQ(f.header.length, 4);
  EXPECT_EQ(f.header.context[0], 1);
  EXPECT_EQ(f.header.context[7], 8);
  EXPECT_EQ(f.data.size(), 4u);
  EXPECT_EQ(f.size, 28u);
}

TEST(EnipEncap, WaitsForTheWholeHeaderAndData) {
  EncapFrame f;
  for (std::size_t n = 0; n < kRegister.size(); ++n) {
    EXPECT_EQ(parse_encap(std::span(kRegister).first(n), f), EncapParse::kIncomplete) << n;
  }
}

TEST(EnipEncap, TwoFramesBackToBackAreTakenOneAtATime) {
  const auto two = cat(kRegister, kRegister);
  EncapFrame f;
  ASSERT_EQ(parse_encap(two, f), EncapParse::kFrame);
  EXPECT_EQ(f.size, 28u);
  ASSERT_EQ(parse_encap(std::span(two).subspan(f.size), f), EncapParse::kFrame);
}

TEST(EnipEncap, AnOversizedLengthIsJudgedBeforeItsBytesArrive) {
  auto b = kRegister;
  b[2] = 0x29;  // 0x0229 = 553 fits
  b[3] = 0x02;
  EncapFrame f;
  EXPECT_EQ(parse_encap(b, f), EncapParse::kIncomplete);
  b[2] = 0x41;  // 0x0241 = 577 > 576
  EXPECT_EQ(parse_encap(std::span(b).first(4), f), EncapParse::kTooLong);
  b[3] = 0xFF;
  EXPECT_EQ(parse_encap(b, f), EncapParse::kTooLong);
}

TEST(EnipEncap, NonZeroOptionsAreDiscardedButSkippable) {
  auto b = kRegister;
  b[20] = 1;
  EncapFrame f;
  EXPECT_EQ(parse_encap(b, f), EncapParse::kDiscard);
  EXPECT_EQ(f.size, 28u);  // the next frame on the connection can still be found
}

TEST(EnipEncap, ARequestWithAStatusIsDiscarded) {
  auto b = kRegister;
  b[8] = 1;
  EncapFrame f;
  EXPECT_EQ(parse_encap(b, f), EncapParse::kDiscard);
}

TEST(EnipEncap, KnowsItsCommandsAndWhichMayComeOverUdp) {
  EXPECT_TRUE(is_known_command(encap_cmd::kSendRRData));
  EXPECT_FALSE(is_known_command(0x0001));
  EXPECT_FALSE(is_known_command(0x00C8));  // StartDTLS: not served
  EXPECT_TRUE(allowed_on_udp(encap_cmd::kListIdentity));
  EXPECT_FALSE(allowed_on_udp(encap_cmd::kRegisterSession));
  EXPECT_FALSE(allowed_on_udp(encap_cmd::kSendRRData));
}

TEST(EnipEncap, AStatusReplyEchoesCommandSessionAndContext) {
  auto b = kRegister;
  b[0] = 0x99;  // an unknown command
  b[4] = 0x2A;  // session 42
  EncapFrame f;
  ASSERT_EQ(parse_encap(b, f), EncapParse::kFrame);
  std::array<std::uint8_t, 64> out{};
  const std::size_t n = encode_status_reply(out, f.header, EncapStatus::kInvalidCommand);
  const auto want = hex("99 00 00 00 2a000000 01000000 0102030405060708 00000000");
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + n), want);
}

TEST(EnipEncap, AReplyThatDoesNotFitIsNotSent) {
  EncapFrame f;
  ASSERT_EQ(parse_encap(kRegister, f), EncapParse::kFrame);
  std::array<std::uint8_t, 23> out{};
  EXPECT_EQ(encode_status_reply(out, f.header, EncapStatus::kInvalidLength), 0u);
}

}  // namespace
}  // namespace stepmod::enip
