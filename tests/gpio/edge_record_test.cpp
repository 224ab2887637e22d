// The kernel line-event record decoders and their lost-edge rules (v1: repeated direction on a
// both-edges line; v2: line_seqno gaps), on hand-made records of the kernel's layout.
#include "gpio/edge_record.hpp"

#include <gtest/gtest.h>
#include <linux/gpio.h>

namespace stepmod::gpio {
namespace {

DecodedEdge v1(EdgeTrack& t, std::uint64_t ts, bool rising) {
  gpioevent_data e{};
  e.timestamp = ts;
  e.id = rising ? GPIOEVENT_EVENT_RISING_EDGE : GPIOEVENT_EVENT_FALLING_EDGE;
  return decode_edge_record(EdgeRecordFormat::kV1, reinterpret_cast<const std::byte*>(&e), t);
}

DecodedEdge v2(EdgeTrack& t, std::uint64_t ts, bool rising, std::uint32_t line_seqno) {
  gpio_v2_line_event e{};
  e.timestamp_ns = ts;
  e.id = rising ? GPIO_V2_LINE_EVENT_RISING_EDGE : GPIO_V2_LINE_EVENT_FALLING_EDGE;
  e.offset = 5;
  e.seqno = line_seqno + 100;  // the request-wide number is not the one that counts per line
  e.line_seqno = line_seqno;
  return decode_edge_record(EdgeRecordFormat::kV2, reinterpret_cast<const std::byte*>(&e), t);
}

TEST(GpioEdgeRecord, RecordSizesAreTheKernels) {
  EXPECT_EQ(edge_record_size(EdgeRecordFormat::kV1), 16u);
  EXPECT_EQ(edge_record_size(EdgeRecordFormat::kV2), 48u);
}

TEST(GpioEdgeRecord, V1AlternatingEdgesLoseNothing) {
  EdgeTrack t;
  const DecodedEdge a = v1(t, 1000, true);
  EXPECT_EQ(a.t, 1000);
  EXPECT_TRUE(a.level);
  EXPECT_EQ(a.lost, 0u);
  EXPECT_EQ(v1(t, 2000, false).lost, 0u);
  EXPECT_EQ(v1(t, 3000, true).lost, 0u);
}

TEST(GpioEdgeRecord, V1FirstEdgeOfEitherDirectionIsNoLoss) {
  EdgeTrack t;
  EXPECT_EQ(v1(t, 1, false).lost, 0u);
}

TEST(GpioEdgeRecord, V1TwoSameDirectionEdgesInARowAreALoss) {
  EdgeTrack t;
  v1(t, 1, true);
  EXPECT_EQ(v1(t, 2, true).lost, 1u);   // a falling edge between them is missing
  EXPECT_EQ(v1(t, 3, false).lost, 0u);  // back in step
  EXPECT_EQ(v1(t, 4, false).lost, 1u);
}

TEST(GpioEdgeRecord, V2ConsecutiveSequenceNumbersLoseNothing) {
  EdgeTrack t;
  const DecodedEdge a = v2(t, 500, true, 1);
  EXPECT_EQ(a.t, 500);
  EXPECT_TRUE(a.level);
  EXPECT_EQ(a.lost, 0u);
  EXPECT_EQ(v2(t, 600, false, 2).lost, 0u);
  EXPECT_EQ(v2(t, 700, true, 3).lost, 0u);
}

TEST(GpioEdgeRecord, V2SequenceGapIsTheNumberOfLostEdges) {
  EdgeTrack t;
  v2(t, 1, true, 1);
  EXPECT_EQ(v2(t, 2, false, 5).lost, 3u);  // 2, 3 and 4 dropped by the kernel's full FIFO
  EXPECT_EQ(v2(t, 3, true, 6).lost, 0u);
}

TEST(GpioEdgeRecord, V2LossBeforeTheFirstReadEventCounts) {
  EdgeTrack t;
  EXPECT_EQ(v2(t, 1, true, 3).lost, 2u);
}

TEST(GpioEdgeRecord, V2SameDirectionWithoutGapIsNotALoss) {
  // The v2 kernel reads the level for a both-edges event: a glitch shorter than the interrupt
  // latency repeats a direction without losing a record; only the sequence number counts.
  EdgeTrack t;
  v2(t, 1, true, 1);
  EXPECT_EQ(v2(t, 2, true, 2).lost, 0u);
}

TEST(GpioEdgeRecord, SequenceCounterWrapIsNotALoss) {
  EdgeTrack t;
  t.last_seqno = 0xffffffffu;
  EXPECT_EQ(lost_by_seqno(t, 0u), 0u);
  EXPECT_EQ(lost_by_seqno(t, 1u), 0u);
}

}  // namespace
}  // namespace stepmod::gpio
