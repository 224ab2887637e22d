// The class 1 connection table: opening through the ownership rule, O→T accepted only from its
// originator with newer sequences, Run/Idle and timeouts as the deadman sees them, T→O timing.
#include "fieldbus/enip/connection_table.hpp"

#include <gtest/gtest.h>

#include <deque>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;
using Bytes = std::vector<std::uint8_t>;

constexpr std::uint32_t kPlc = 0x7F000002u;
constexpr std::int64_t kMs = 1'000'000;

const Bytes kOwnerRequest =
    hex("03 7d 00000000 78563412 3412 3333 37130000 03 000000 10270000 1648 10270000 1248 01"
        "09 34 04 0000 0000 0000 00 00 20 04 24 97 2c 96 2c 64");

class EnipConnections : public ::testing::Test {
 protected:
  // Opens a connection from `ip` with `request` (triad serial changed to `serial`); the status.
  CipStatus open(Bytes request, std::uint16_t serial = 0x1234, std::uint32_t ip = kPlc,
                 std::int64_t now = 0) {
    request[10] = static_cast<std::uint8_t>(serial);
    request[11] = static_cast<std::uint8_t>(serial >> 8);
    kept_.push_back(std::move(request));
    ForwardOpen fo;
    EXPECT_EQ(parse_forward_open(kept_.back(), false, fo), cip_general::kSuccess);
    AcceptedOpen accepted;
    const CipStatus valid = validate_forward_open(fo, assembly_layout(2, 8, 8),
                                                  identity_for(3601, 1), AdapterLimits{}, accepted);
    EXPECT_TRUE(valid.ok());
    return table.open(fo, accepted, RequestOrigin{ip, now}, ot_id);
  }
  Bytes o_to_t(std::uint32_t seq, std::uint16_t count, bool run) const {
    Bytes b = hex("0200 0280 0800 00000000 00000000 b100 1600 0000 00000000");
    for (int i = 0; i < 4; ++i) {
      b[6 + i] = static_cast<std::uint8_t>(ot_id >> (8 * i));
      b[10 + i] = static_cast<std::uint8_t>(seq >> (8 * i));
    }
    b[18] = static_cast<std::uint8_t>(count);
    b[20] = run ? 1 : 0;
    return cat(b, Bytes(16, static_cast<std::uint8_t>(count)));
  }
  IoConnections table{12345};
  std::uint32_t ot_id = 0;
  std::deque<Bytes> kept_;
};

TEST_F(EnipConnections, OwnerOpensAndASecondOwnerIsRefused) {
  ASSERT_TRUE(open(kOwnerRequest).ok());
  EXPECT_NE(ot_id, 0u);
  EXPECT_TRUE(table.owner_open());
  EXPECT_EQ(open(kOwnerRequest, 0x2000).extended(), cm_status::kOwnershipConflict);
  EXPECT_EQ(open(kOwnerRequest).extended(), cm_status::kDuplicateForwardOpen);
}

TEST_F(EnipConnections, RunPacketsWriteOnceEachAndIdleIsTheDeadman) {
  ASSERT_TRUE(open(kOwnerRequest).ok());
  EXPECT_FALSE(table.plc_left_run());  // no owner has been in Run yet: nothing to stop
  OtResult r = table.on_o_to_t(kPlc, o_to_t(1, 1, true), 1 * kMs);
  ASSERT_EQ(r.outcome, OtOutcome::kRunWrite);
  EXPECT_EQ(r.data.size(), 16u);
  // The same CIP count again: the data was written; the PLC is alive in Run (a heartbeat).
  EXPECT_EQ(table.on_o_to_t(kPlc, o_to_t(2, 1, true), 2 * kMs).outcome, OtOutcome::kRunRepeat);
  EXPECT_EQ(table.on_o_to_t(kPlc, o_to_t(2, 2, true), 3 * kMs).outcome, OtOutcome::kDropped);
  EXPECT_EQ(table.on_o_to_t(kPlc, o_to_t(3, 2, true), 4 * kMs).outcome, OtOutcome::kRunWrite);
  EXPECT_EQ(table.identity_status(), 0x0061);  // owned, a connection in Run
  EXPECT_EQ(table.on_o_to_t(kPlc, o_to_t(4, 3, false), 5 * kMs).outcome, OtOutcome::kIdle);
  EXPECT_TRUE(table.plc_left_run());
  EXPECT_EQ(table.on_o_to_t(kPlc, o_to_t(5, 4, true), 6 * kMs).outcome, OtOutcome::kRunWrite);
  EXPECT_FALSE(table.plc_left_run());
}

TEST_F(EnipConnections, OnlyTheOriginatorAndTheRightIdAreHeard) {
  ASSERT_TRUE(open(kOwnerRequest).ok());
  EXPECT_EQ(table.on_o_to_t(kPlc + 1, o_to_t(1, 1, true), kMs).outcome, OtOutcome::kDropped);
  Bytes wrong_id = o_to_t(1, 1, true);
  wrong_id[6] ^= 1;
  EXPECT_EQ(table.on_o_to_t(kPlc, wrong_id, kMs).outcome, OtOutcome::kDropped);
  Bytes short_data = o_to_t(1, 1, true);
  short_data.pop_back();
  EXPECT_EQ(table.on_o_to_t(kPlc, short_data, kMs).outcome, OtOutcome::kDropped);
}

TEST_F(EnipConnections, SilenceForRpiTimesMultiplierClosesTheOwner) {
  ASSERT_TRUE(open(kOwnerRequest).ok());  // RPI 10 ms × 32 = 320 ms
  ASSERT_EQ(table.on_o_to_t(kPlc, o_to_t(1, 1, true), 0).outcome, OtOutcome::kRunWrite);
  EXPECT_FALSE(table.expire(319 * kMs));
  EXPECT_TRUE(table.owner_open());
  EXPECT_TRUE(table.expire(320 * kMs));
  EXPECT_FALSE(table.owner_open());
  EXPECT_TRUE(table.plc_left_run());
  EXPECT_EQ(table.identity_status(), 0x0030);
  EXPECT_TRUE(open(kOwnerRequest).ok());  // the PLC may connect again
}

TEST_F(EnipConnections, ForwardCloseOfTheOwnerIsLeavingRunAndClosesItsListeners) {
  ASSERT_TRUE(open(kOwnerRequest).ok());
  Bytes listen = kOwnerRequest;
  listen[26] = 0x02;  // heartbeat O→T size
  listen[51] = 0xC7;  // O→T point 199: listen-only
  ASSERT_TRUE(open(listen, 0x4444, kPlc + 7).ok());
  ASSERT_EQ(table.close(ConnectionTriad{0x1234, 0x3333, 0x1337}).general, 0);
  EXPECT_TRUE(table.plc_left_run());
  EXPECT_EQ(table.next_due_ns(), std::numeric_limits<std::int64_t>::max());  // nothing open
  EXPECT_EQ(table.close(ConnectionTriad{0x1234, 0x3333, 0x1337}).extended(),
            cm_status::kConnectionNotFound);
}

TEST_F(EnipConnections, TToOIsDueAtOnceThenEveryRpi) {
  ASSERT_TRUE(open(kOwnerRequest, 0x1234, kPlc, 100 * kMs).ok());
  IoConnection& c = table.slots()[0];
  EXPECT_TRUE(IoConnections::to_due(c, 100 * kMs));
  EXPECT_EQ(c.to_id, 0x12345678u);
  IoConnections::advance(c, 100 * kMs);
  EXPECT_FALSE(IoConnections::to_due(c, 109 * kMs));
  EXPECT_TRUE(IoConnections::to_due(c, 110 * kMs));
  EXPECT_EQ(table.next_due_ns(), 110 * kMs);
  IoConnections::advance(c, 175 * kMs);  // late: no burst, the next one an RPI from now
  EXPECT_EQ(c.next_to_ns, 185 * kMs);
  EXPECT_EQ(c.to_encap_sequence, 2u);
}

TEST_F(EnipConnections, IdsAreDistinctAndNeverZero) {
  ASSERT_TRUE(open(kOwnerRequest).ok());
  const std::uint32_t first = ot_id;
  Bytes input_only = kOwnerRequest;
  input_only[26] = 0x02;
  input_only[51] = 0xC6;
  ASSERT_TRUE(open(input_only, 0x5555).ok());
  EXPECT_NE(ot_id, first);
  EXPECT_NE(ot_id, 0u);
}

}  // namespace
}  // namespace stepmod::enip
