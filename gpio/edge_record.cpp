#include "gpio/edge_record.hpp"

#include <linux/gpio.h>

#include <cstring>

namespace stepmod::gpio {

std::size_t edge_record_size(EdgeRecordFormat format) noexcept {
  return format == EdgeRecordFormat::kV2 ? sizeof(gpio_v2_line_event) : sizeof(gpioevent_data);
}

std::uint32_t lost_by_seqno(EdgeTrack& track, std::uint32_t line_seqno) noexcept {
  // Unsigned arithmetic: a wrap of the 32-bit counter (4e9 edges) is not a loss.
  const std::uint32_t lost = line_seqno - track.last_seqno - 1u;
  track.last_seqno = line_seqno;
  // A counter that went backwards (never from the kernel) is not counted as 4e9 losses.
  return lost > (1u << 31) ? 0u : lost;
}

std::uint32_t lost_by_direction(EdgeTrack& track, bool level) noexcept {
  const std::int8_t now = level ? 1 : 0;
  const bool repeat = track.last_level == now;
  track.last_level = now;
  return repeat ? 1u : 0u;
}

DecodedEdge decode_edge_record(EdgeRecordFormat format, const std::byte* rec,
                               EdgeTrack& track) noexcept {
  DecodedEdge out;
  if (format == EdgeRecordFormat::kV2) {
    gpio_v2_line_event ev{};
    std::memcpy(&ev, rec, sizeof ev);
    // The backend asks for CLOCK_MONOTONIC (the default of the v2 uAPI without
    // GPIO_V2_LINE_FLAG_EVENT_CLOCK_REALTIME/HTE), the clock of every stepmod time.
    out.t = static_cast<Nanos>(ev.timestamp_ns);
    out.level = ev.id == GPIO_V2_LINE_EVENT_RISING_EDGE;
    out.lost = lost_by_seqno(track, ev.line_seqno);
    track.last_level = out.level ? 1 : 0;
    return out;
  }
  gpioevent_data ev{};
  std::memcpy(&ev, rec, sizeof ev);
  // Since Linux 5.7 (commit f8850206e160, "gpio: Switch timestamps to ktime_get_ns()") the v1
  // line-event timestamp is CLOCK_MONOTONIC; before it was CLOCK_REALTIME. Debian 12 has 6.1.
  out.t = static_cast<Nanos>(ev.timestamp);
  out.level = ev.id == GPIOEVENT_EVENT_RISING_EDGE;
  out.lost = lost_by_direction(track, out.level);
  return out;
}

}  // namespace stepmod::gpio
