#pragma once
// Slip (issue 18): a late edge delays the rest of its motion — of its whole group — instead of
// being caught up in a burst. Edges carry *planned* times on their motion's time base; the pulse
// engine writes each at planned time + the slip of the motion's group, and a write later than
// that by more than kSlipFreeNs adds the excess to the slip. So no step interval on the wire is
// shorter than planned by more than kSlipFreeNs, and pulse width and direction set-up stay full.
//
// Two small channels, each a lone 64-bit atomic word packing (epoch << 32 | value), so that a
// reader never mixes two motions' values:
//  * planner -> pulse thread (rt::AxisControl::motion_group / motion_vs), stored before the
//    motion's first edge is pushed (the ring's release orders them): the motion's group (the
//    axes that share one slip: a path's coordinates) and its starting speed Vs, which the
//    late-edge guard needs (below Vs a pause is harmless, above it the motor may drop out).
//  * pulse thread -> everyone (rt::AxisFeedback::slip): the slip of the axis' motion, so that
//    what the planner derives from motion time (cut and stop times, registration distances, hold
//    times, the lookahead) is converted between wall time and the motion's planned time.
#include <cmath>
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::rt {

// Lateness up to this does not move the schedule: the line write and the clock read around it
// take about this long, and a wake-up's jitter of a few microseconds is not a pause. An interval
// on the wire is never shorter than planned by more than this.
inline constexpr Nanos kSlipFreeNs = 2 * kNsPerUs;

// A new motion whose first edge is planned less than this after (the slipped end of) the axis'
// previous motion continues it (a blend, a start that replaces a running motion): it inherits
// the previous motion's slip, so the gap between them is not squeezed. Later (a start from rest:
// stepmodd's start delay is 100 us after the planner's clock read, which is after the
// previous motion's last write) it starts on time with no slip.
inline constexpr Nanos kChainGapNs = 50 * kNsPerUs;

inline constexpr std::uint64_t pack_epoch(std::uint32_t epoch, std::uint32_t value) noexcept {
  return static_cast<std::uint64_t>(epoch) << 32 | value;
}
inline constexpr std::uint32_t packed_epoch(std::uint64_t word) noexcept {
  return static_cast<std::uint32_t>(word >> 32);
}
inline constexpr std::uint32_t packed_value(std::uint64_t word) noexcept {
  return static_cast<std::uint32_t>(word & 0xffff'ffffu);
}
// Step interval at the starting speed, ns, as carried in motion_vs (0: unknown). Capped at
// 4.29 s (Vs >= 0.24 steps/s; the modules' Vs is >= 1).
inline std::uint32_t vs_interval_ns(double vs) noexcept {
  if (!(vs > 0.0)) return 0;
  const double ns = 1e9 / vs;
  return ns >= 4.29e9 ? 4'290'000'000u : static_cast<std::uint32_t>(std::llround(ns));
}
// Published slip: microseconds (a planner conversion does not need finer), capped.
inline constexpr std::uint32_t slip_us(Nanos slip) noexcept {
  const Nanos us = slip / kNsPerUs;
  return us >= 0xffff'ffff ? 0xffff'ffffu : static_cast<std::uint32_t>(us);
}

}  // namespace stepmod::rt
