#pragma once
// The kernel's line-event records, decoded, and the edges they show were lost. Both uAPI
// generations are described by <linux/gpio.h> (v1 `gpioevent_data`, v2 `gpio_v2_line_event`),
// so both decoders are always built and unit-tested; the gpiod backend in use picks its format.
#include <cstddef>
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::gpio {

enum class EdgeRecordFormat : std::uint8_t {
  kV1,  // struct gpioevent_data: timestamp + rising/falling id (libgpiod 1.6)
  kV2,  // struct gpio_v2_line_event: + offset, seqno, line_seqno (libgpiod 2)
};

std::size_t edge_record_size(EdgeRecordFormat format) noexcept;

// What one line's event stream has shown so far (one per line-event fd).
struct EdgeTrack {
  std::uint32_t last_seqno = 0;  // v2: line_seqno of the last event (the first one is 1)
  std::int8_t last_level = -1;   // level after the last event, -1 before the first
};

// v2: the kernel numbers each line's events 1, 2, 3, ... and keeps counting the ones its FIFO
// drops when full, so a gap in line_seqno is the number of edges lost before this one.
std::uint32_t lost_by_seqno(EdgeTrack& track, std::uint32_t line_seqno) noexcept;

// v1 (no sequence numbers): on a line watched for both edges, the levels must alternate; two
// edges of the same direction in a row mean at least one edge in between was lost (dropped by
// the kernel's FIFO, or a pulse shorter than the interrupt latency). Counts 1 per repeat: the
// true number cannot be known (an even number of lost edges leaves no trace at all).
std::uint32_t lost_by_direction(EdgeTrack& track, bool level) noexcept;

struct DecodedEdge {
  Nanos t = 0;             // kernel timestamp, CLOCK_MONOTONIC
  bool level = false;      // level after the edge (rising: true)
  std::uint32_t lost = 0;  // edges of this line seen lost just before this one
};

// `rec` points at one whole record of `format` (any alignment).
DecodedEdge decode_edge_record(EdgeRecordFormat format, const std::byte* rec,
                               EdgeTrack& track) noexcept;

}  // namespace stepmod::gpio
