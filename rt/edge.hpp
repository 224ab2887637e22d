#pragma once
// One scheduled output change: the unit the planner hands to the pulse thread. Edges of one axis
// travel in that axis' SpscRing<Edge> in non-decreasing time order.
#include <cstdint>
#include <limits>

#include "core/clock.hpp"
#include "core/lines.hpp"

namespace stepmod::rt {

// No edge: the time a step output answers when nothing is queued (StepOutput::next_due).
inline constexpr Nanos kNever = std::numeric_limits<Nanos>::max();

// Motion phase of the move an edge belongs to; drives the accelerating/decelerating status bits.
enum class Phase : std::uint8_t { kCruise = 0, kAccel = 1, kDecel = 2 };

namespace edge_flag {
inline constexpr std::uint8_t kPhaseMask = 0x03;  // Phase
inline constexpr std::uint8_t kCcw = 0x04;        // the motion runs CCW (position decreasing)
inline constexpr std::uint8_t kFirst = 0x08;      // first edge of its motion (epoch)
inline constexpr std::uint8_t kLast = 0x10;       // last edge of its motion: axis at rest after it
inline constexpr std::uint8_t kMotion = 0x20;     // belongs to a motion (not a GPO-only change)
// Planned after a cut (rt/edge_cut.hpp): replaces the motion's queued edges from the cut on.
inline constexpr std::uint8_t kReplacement = 0x40;
}  // namespace edge_flag

struct Edge {
  Nanos t = 0;              // CLOCK_MONOTONIC time at which the line must change
  std::uint32_t epoch = 0;  // motion id; edges of an aborted motion are dropped unexecuted
  OutputLine line = OutputLine::kStep;
  std::uint8_t level = 0;  // electrical level to write
  std::int8_t dpos = 0;    // +1/-1 on a step's leading edge: the axis step count changes by this
  std::uint8_t flags = 0;  // edge_flag bits

  Phase phase() const noexcept { return static_cast<Phase>(flags & edge_flag::kPhaseMask); }
};
static_assert(sizeof(Edge) == 16, "Edge is kept at 16 bytes: 4 per cache line");

}  // namespace stepmod::rt
