#pragma once
// The 3602's interpolated move command as the dialect decodes it from all sixteen output words
// (3602 manual Tables 9.4, 9.23-9.26; Ch.3 "Interpolated Move Profiles"): which method,
// coordinates, the vector profile and the points, in the shared code's units (steps, steps/s,
// steps/s^2). No word or bit knowledge: dialect_3602 builds it, circle_methods turns its geometry
// into a planner::PathSpec, interpolated_move runs it.
#include <cstdint>

#include "planner/ramp.hpp"

namespace stepmod::module::m3602 {

enum class InterpolationMethod : std::uint8_t {
  kLinear,
  kViaPoint,  // circle through S, V, E; sense from the orientation of S -> V -> E
  kCentre,    // centre point C; sense from the command (E = S: a full circle)
  kRadius,    // signed radius R: > 0 the shorter arc, < 0 the longer one; sense from the command
};

// A word-level rule the command breaks, in the order the dialect looks at them.
enum class InterpolationFault : std::uint8_t {
  kNone,
  kPattern,      // 3602-CE-I6 (A34): LSW bits 10..14 not one of the manual's patterns, or LSW bits
                 // outside 0, 1, 7, 9..14 set
  kCommandBits,  // 3602-CE-03: a command MSW bit together with the interpolation bits
  kReserved,     // 3602-CE-I5 / IP-18: words 8, 9 or the method's unused words of 12..15 not 0
  kRange,        // 3602-CE-05 / IP-02: a coordinate outside +-1,073,741,823, radius -2^31 (A35)
};

struct InterpolatedCommand {
  InterpolationFault fault = InterpolationFault::kNone;
  InterpolationMethod method = InterpolationMethod::kLinear;
  bool absolute = false;  // LSW bit 9: points are positions, else offsets from the start point
  bool ccw = false;       // centre / radius: the commanded sense (X right, Y up)
  planner::AccelShape shape = planner::AccelShape::kConstant;
  // The vector profile: speed steps/s, rates steps/s^2 (the words' steps/ms/s times 1000).
  std::int32_t speed = 0;
  std::int64_t accel = 0;
  std::int64_t decel = 0;
  // End point, and the via point / centre (words 12..15); radius (words 12/13).
  std::int32_t end_x = 0;
  std::int32_t end_y = 0;
  std::int32_t point_x = 0;
  std::int32_t point_y = 0;
  std::int32_t radius = 0;
};

}  // namespace stepmod::module::m3602
