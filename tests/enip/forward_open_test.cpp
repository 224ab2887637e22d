// Forward_Open / Large_Forward_Open / Forward_Close: parsing, each refusal with its standard
// status, and the reply bytes (docs/ethernetip-design.md, "Connection Manager").
#include "fieldbus/enip/forward_open.hpp"

#include <gtest/gtest.h>

#include <array>
#include <deque>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;

// What st-ethernet-ip's I/O scanner sends to a 3601 (16 bytes each way) at RPI 10 ms: timeout
// 2^3 × 125 ms, O→T id 0, its T→O id, serial 0x1234, vendor 0x3333, originator serial 0x1337,
// multiplier 3 (× 32), O→T point-to-point scheduled fixed 22 bytes, T→O 18 bytes, class 1
// cyclic, then its 9-word path.
const auto kFixed =
    hex("03 7d 00000000 78563412 3412 3333 37130000 03 000000"
        "10270000 1648 10270000 1248 01");
const auto kPath = hex("09 34 04 0000 0000 0000 00 00 20 04 24 97 2c 96 2c 64");
const AssemblyLayout k3601 = assembly_layout(2, 8, 8);

// A parsed request views its bytes (its path): the tests' requests are kept for the program's life.
const std::vector<std::uint8_t>& kept(std::vector<std::uint8_t> bytes) {
  static std::deque<std::vector<std::uint8_t>> all;
  all.push_back(std::move(bytes));
  return all.back();
}

ForwardOpen parsed(std::vector<std::uint8_t> bytes, bool large = false) {
  const auto& data = kept(std::move(bytes));
  ForwardOpen fo;
  EXPECT_EQ(parse_forward_open(data, large, fo), cip_general::kSuccess);
  return fo;
}

CipStatus validate(const ForwardOpen& fo, AcceptedOpen* out = nullptr) {
  AcceptedOpen ignored;
  return validate_forward_open(fo, k3601, identity_for(3601, 1), AdapterLimits{},
                               out != nullptr ? *out : ignored);
}

TEST(EnipForwardOpen, AssemblySizesPerModule) {
  EXPECT_EQ(k3601.input_bytes, 16);
  EXPECT_EQ(k3601.output_bytes, 16);
  EXPECT_EQ(assembly_layout(2, 16, 16).output_bytes, 32);  // 3602
  EXPECT_EQ(assembly_layout(4, 16, 16).input_bytes, 64);   // 3202
}

TEST(EnipForwardOpen, ParsesTheScannersRequest) {
  const ForwardOpen fo = parsed(cat(kFixed, kPath));
  EXPECT_EQ(fo.to_id, 0x12345678u);
  EXPECT_EQ(fo.triad.connection_serial, 0x1234);
  EXPECT_EQ(fo.triad.originator_vendor, 0x3333);
  EXPECT_EQ(fo.triad.originator_serial, 0x1337u);
  EXPECT_EQ(fo.timeout_multiplier, 3);
  EXPECT_EQ(fo.ot_rpi_us, 10000u);
  EXPECT_EQ(fo.ot.type, conn_type::kPointToPoint);
  EXPECT_EQ(fo.ot.priority, 2);
  EXPECT_EQ(fo.ot.size, 22);
  EXPECT_EQ(fo.to.size, 18);
  EXPECT_EQ(fo.transport, 0x01);
  EXPECT_EQ(fo.path.size(), 18u);
}

TEST(EnipForwardOpen, AcceptsAnExclusiveOwnerWithItsTimeout) {
  AcceptedOpen a;
  const CipStatus s = validate(parsed(cat(kFixed, kPath)), &a);
  EXPECT_TRUE(s.ok()) << std::hex << s.extended();
  EXPECT_EQ(a.kind, ConnectionKind::kExclusiveOwner);
  EXPECT_EQ(a.timeout_us, 10000u * 32u);
}

TEST(EnipForwardOpen, ShortOrLongRequestsAreGeneralErrors) {
  const auto whole = cat(kFixed, kPath);
  ForwardOpen fo;
  for (std::size_t n = 0; n < whole.size(); ++n) {
    EXPECT_EQ(parse_forward_open(std::span(whole).first(n), false, fo), cip_general::kNotEnoughData)
        << n;
  }
  auto longer = whole;
  longer.push_back(0);
  EXPECT_EQ(parse_forward_open(longer, false, fo), cip_general::kTooMuchData);
}

TEST(EnipForwardOpen, LargeForwardOpenHas32BitParameters) {
  const auto large =
      hex("03 7d 00000000 78563412 3412 3333 37130000 03 000000"
          "10270000 16000048 10270000 12000048 01");
  const ForwardOpen fo = parsed(cat(large, kPath), true);
  EXPECT_TRUE(fo.large);
  EXPECT_EQ(fo.ot.type, conn_type::kPointToPoint);
  EXPECT_EQ(fo.ot.priority, 2);
  EXPECT_EQ(fo.ot.size, 22);
  EXPECT_TRUE(validate(fo).ok());
}

// The request with one byte changed (offset into kFixed) and the extended status it gets.
CipStatus with_byte(std::size_t at, std::uint8_t v) {
  auto b = kFixed;
  b[at] = v;
  return validate(parsed(cat(b, kPath)));
}

TEST(EnipForwardOpen, TransportAndConnectionTypeRefusals) {
  EXPECT_EQ(with_byte(34, 0xA3).extended(), cm_status::kTransportClassNotSupported);
  EXPECT_EQ(with_byte(34, 0x11).extended(), cm_status::kTriggerNotSupported);  // change of state
  EXPECT_EQ(with_byte(34, 0x81).extended(), cm_status::kDirectionNotSupported);
  EXPECT_EQ(with_byte(27, 0xC8).extended(), cm_status::kRedundantOwnerNotSupported);
  EXPECT_EQ(with_byte(27, 0x28).extended(), cm_status::kOtConnectionTypeNotSupported);  // multicast
  EXPECT_EQ(with_byte(27, 0x08).extended(), cm_status::kOtConnectionTypeNotSupported);  // null
  EXPECT_EQ(with_byte(33, 0x28).extended(), cm_status::kToConnectionTypeNotSupported);
  EXPECT_EQ(with_byte(34, 0xA3).general, cip_general::kConnectionFailure);
}

TEST(EnipForwardOpen, RpiOutsideTheRangeGetsTheNearestAcceptable) {
  auto b = kFixed;
  b[22] = 0xF4;  // O→T 500 µs, below 1000
  b[23] = 0x01;
  b[30] = 0x40;  // T→O 0x030d40 = 200,000 µs, above 100,000
  b[31] = 0x0d;
  b[32] = 0x03;
  const CipStatus s = validate(parsed(cat(b, kPath)));
  ASSERT_EQ(s.extended(), cm_status::kRpiNotAcceptable);
  ASSERT_EQ(s.word_count, 6);
  EXPECT_EQ(s.words[1], rpi_type::kMinimum | (rpi_type::kMaximum << 8));
  EXPECT_EQ(s.words[2] | (s.words[3] << 16), 1000);
  EXPECT_EQ(s.words[4] | (s.words[5] << 16), 100000);
}

TEST(EnipForwardOpen, WrongSizesGetTheCorrectSize) {
  const CipStatus ot = with_byte(26, 0x14);  // O→T 20 bytes: the run/idle header forgotten
  EXPECT_EQ(ot.extended(), cm_status::kInvalidOtSize);
  ASSERT_EQ(ot.word_count, 2);
  EXPECT_EQ(ot.words[1], 22);
  const CipStatus to = with_byte(32, 0x16);
  EXPECT_EQ(to.extended(), cm_status::kInvalidToSize);
  EXPECT_EQ(to.words[1], 18);
  // The same request is the wrong size for a 3202.
  AcceptedOpen a;
  EXPECT_EQ(validate_forward_open(parsed(cat(kFixed, kPath)), assembly_layout(4, 16, 16),
                                  identity_for(3601, 1), AdapterLimits{}, a)
                .extended(),
            cm_status::kInvalidOtSize);
}

CipStatus with_path(const std::vector<std::uint8_t>& path) {
  return validate(parsed(cat(kFixed, path)));
}

TEST(EnipForwardOpen, ApplicationPathRefusals) {
  EXPECT_EQ(with_path(hex("04 20 04 24 01 2c 96 2c 64")).extended(),
            cm_status::kInvalidConfigurationPath);
  EXPECT_EQ(with_path(hex("04 20 04 24 97 2c 65 2c 64")).extended(),
            cm_status::kInvalidConsumingPath);
  EXPECT_EQ(with_path(hex("04 20 04 24 97 2c 96 2c 65")).extended(),
            cm_status::kInvalidProducingPath);
  EXPECT_EQ(with_path(hex("03 20 04 24 97 2c 96")).extended(), cm_status::kInvalidProducingPath);
  EXPECT_EQ(with_path(hex("04 20 01 24 97 2c 96 2c 64")).extended(),
            cm_status::kInvalidConfigurationPath);  // the Identity class, not the Assembly
  const CipStatus data = with_path(hex("06 20 04 24 97 2c 96 2c 64 80 01 aa bb"));
  EXPECT_EQ(data.extended(), cm_status::kInvalidConfigurationSize);
  EXPECT_EQ(with_path(hex("06 20 04 24 97 2c 96 2c 64 91 01 61 00")).extended(),
            cm_status::kInvalidSegmentInPath);
}

TEST(EnipForwardOpen, ElectronicKeyRefusals) {
  const auto key = [](const char* fields) {
    return with_path(cat(hex("09 34 04"), cat(hex(fields), hex("20 04 24 97 2c 96 2c 64"))))
        .extended();
  };
  EXPECT_EQ(key("ffff 2b00 110e 01 01"), 0);  // our own key, exactly
  EXPECT_EQ(key("0100 0000 0000 00 00"), cm_status::kVendorOrProductMismatch);
  EXPECT_EQ(key("0000 0000 120e 00 00"), cm_status::kVendorOrProductMismatch);  // a 3602's
  EXPECT_EQ(key("0000 0c00 0000 00 00"), cm_status::kDeviceTypeMismatch);
  EXPECT_EQ(key("0000 0000 0000 02 00"), cm_status::kRevisionMismatch);
  EXPECT_EQ(key("0000 0000 0000 01 02"), cm_status::kRevisionMismatch);
  EXPECT_EQ(key("0000 0000 0000 81 02"), cm_status::kRevisionMismatch);  // newer than ours
  EXPECT_EQ(key("0000 0000 0000 81 01"), 0);                             // compatible
}

TEST(EnipForwardOpen, HeartbeatConnectionsAndTheMultiplier) {
  auto b = kFixed;
  b[26] = 0x02;  // O→T: the sequence count alone
  AcceptedOpen a;
  EXPECT_TRUE(validate(parsed(cat(b, hex("04 20 04 24 97 2c c6 2c 64"))), &a).ok());
  EXPECT_EQ(a.kind, ConnectionKind::kInputOnly);
  b[27] = 0x08;  // O→T type null: allowed for a heartbeat
  b[26] = 0x00;
  EXPECT_TRUE(validate(parsed(cat(b, hex("04 20 04 24 97 2c c7 2c 64"))), &a).ok());
  EXPECT_EQ(a.kind, ConnectionKind::kListenOnly);
  EXPECT_EQ(with_byte(18, 8).extended(), cm_status::kParameterError);
}

TEST(EnipForwardOpen, OwnershipRule) {
  OpenConnections open;
  open.free_slots = 4;
  EXPECT_TRUE(check_ownership(ConnectionKind::kExclusiveOwner, open).ok());
  EXPECT_EQ(check_ownership(ConnectionKind::kListenOnly, open).extended(),
            cm_status::kNonListenOnlyNotOpened);
  open.owner = true;
  const CipStatus second = check_ownership(ConnectionKind::kExclusiveOwner, open);
  EXPECT_EQ(second.general, 0x01);  // the contract's refusal of a second owner: 0x01/0x0106
  EXPECT_EQ(second.extended(), 0x0106);
  EXPECT_TRUE(check_ownership(ConnectionKind::kInputOnly, open).ok());
  EXPECT_TRUE(check_ownership(ConnectionKind::kListenOnly, open).ok());
  open.triad_open = true;
  EXPECT_EQ(check_ownership(ConnectionKind::kExclusiveOwner, open).extended(),
            cm_status::kDuplicateForwardOpen);
  open = OpenConnections{};
  EXPECT_EQ(check_ownership(ConnectionKind::kInputOnly, open).extended(),
            cm_status::kOutOfConnections);
}

std::vector<std::uint8_t> bytes_of(const Writer& w) {
  return {w.written().begin(), w.written().end()};
}

TEST(EnipForwardOpen, ReplyBytes) {
  const ForwardOpen fo = parsed(cat(kFixed, kPath));
  std::array<std::uint8_t, 64> buf{};
  Writer ok(buf);
  put_reply_status(ok, cm_service::kForwardOpen, CipStatus{});
  put_forward_open_success(ok, fo, 0xA0B0C0D0u, fo.to_id);
  EXPECT_EQ(bytes_of(ok), hex("d4 00 00 00 d0c0b0a0 78563412 3412 3333 37130000"
                              "10270000 10270000 00 00"));
  Writer refused(buf);
  put_reply_status(refused, cm_service::kForwardOpen,
                   CipStatus::connection(cm_status::kOwnershipConflict));
  put_triad_reply(refused, fo.triad);
  EXPECT_EQ(bytes_of(refused), hex("d4 00 01 01 0601 3412 3333 37130000 00 00"));
}

TEST(EnipForwardOpen, ForwardCloseAsTheScannerSendsIt) {
  // Its path routes to the backplane slot 0 and the message router; we only check it is there.
  const auto req = hex("03 7d 3412 3333 37130000 03 00 01 00 20 02 24 01");
  ForwardClose fc;
  ASSERT_EQ(parse_forward_close(req, fc), cip_general::kSuccess);
  EXPECT_EQ(fc.triad, (ConnectionTriad{0x1234, 0x3333, 0x1337}));
  EXPECT_EQ(fc.path.size(), 6u);
  EXPECT_EQ(parse_forward_close(std::span(req).first(req.size() - 1), fc),
            cip_general::kNotEnoughData);
}

}  // namespace
}  // namespace stepmod::enip
