// T→O production: the packet a scanner takes (encapsulation sequence from 1, newer each time),
// the CIP count moving only when the words change, a new connection in a slot starting afresh,
// and the schedule advancing even when nothing could be written.
#include "fieldbus/enip/t_to_o_producer.hpp"

#include <gtest/gtest.h>

#include <array>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;
using Bytes = std::vector<std::uint8_t>;
constexpr std::int64_t kMs = 1'000'000;

IoConnection connection(std::uint32_t ot_id) {
  IoConnection c;
  c.open = true;
  c.ot_id = ot_id;
  c.to_id = 0x11223344;
  c.to_rpi_ns = 10 * kMs;
  c.next_to_ns = 0;
  return c;
}

Bytes produce(TtoProducer& p, std::size_t slot, IoConnection& c, const Bytes& input,
              std::int64_t now) {
  std::array<std::uint8_t, kMaxIoPacketBytes> out{};
  const std::size_t n = p.produce(slot, c, input, now, out);
  return Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
}

TEST(EnipTtoProducer, SequencesFromOneAndTheCountMovesWithTheWords) {
  TtoProducer p;
  IoConnection c = connection(7);
  const Bytes words = hex("0100 0200 0300 0400 0500 0600 0700 0800");
  EXPECT_EQ(produce(p, 0, c, words, 0),
            cat(hex("0200 0280 0800 44332211 01000000 b100 1200 0100"), words));
  EXPECT_EQ(c.next_to_ns, 10 * kMs);
  // The same words: the encapsulation sequence moves, the CIP count does not.
  EXPECT_EQ(produce(p, 0, c, words, 10 * kMs),
            cat(hex("0200 0280 0800 44332211 02000000 b100 1200 0100"), words));
  Bytes changed = words;
  changed[0] = 9;
  EXPECT_EQ(produce(p, 0, c, changed, 20 * kMs),
            cat(hex("0200 0280 0800 44332211 03000000 b100 1200 0200"), changed));
}

TEST(EnipTtoProducer, ANewConnectionInASlotStartsAfresh) {
  TtoProducer p;
  IoConnection a = connection(7);
  const Bytes words(16, 1);
  produce(p, 1, a, words, 0);
  produce(p, 1, a, Bytes(16, 2), 10 * kMs);  // CIP count 2
  IoConnection b = connection(8);            // the slot reused
  const Bytes first = produce(p, 1, b, Bytes(16, 2), 0);
  ASSERT_EQ(first.size(), 20u + 16u);
  EXPECT_EQ(first[18], 1);  // CIP count 1: its first data
  EXPECT_EQ(first[10], 1);  // encapsulation sequence 1
}

TEST(EnipTtoProducer, TooMuchDataWritesNothingButTheScheduleMoves) {
  TtoProducer p;
  IoConnection c = connection(7);
  EXPECT_TRUE(produce(p, 0, c, Bytes(kMaxAssemblyBytes + 1, 0), 0).empty());
  EXPECT_EQ(c.next_to_ns, 10 * kMs);
  EXPECT_TRUE(produce(p, kMaxIoConnections, c, Bytes(16, 0), 10 * kMs).empty());
  EXPECT_EQ(c.next_to_ns, 20 * kMs);
}

}  // namespace
}  // namespace stepmod::enip
