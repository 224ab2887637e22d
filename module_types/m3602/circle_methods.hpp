#pragma once
// The geometry of the 3602's interpolated moves, as the manual defines it (3602 manual Ch.3
// "Interpolated Move Profiles", Ch.9 Tables 9.23-9.26): the end point, and for circular moves the
// centre by the centre-point, radius or via-point method, the sense and the swept angle, with the
// manual's "integer world" check. The result is the planner's PathSpec (planner/path_spec.hpp)
// relative to the start point S, or the reason the move is refused.
//
// Coordinates reach +-2^31 (a start point anywhere in int32, points within +-2^30), so squared
// distances need more than 64 bits: exact integer work in __int128, the rest in long double.
#include <cstdint>

#include "module_types/m3602/interpolated_command.hpp"
#include "planner/path_spec.hpp"

namespace stepmod::module::m3602 {

enum class GeometryFault : std::uint8_t {
  kNone,
  kOverflow,        // 3602-IP-03 (A32): an end point more than 2^31 - 1 steps from the start
  kRadiiDiffer,     // 3602-CE-I7: |S - C| and |E - C| differ after rounding (A36)
  kStartIsEnd,      // 3602-CE-I7: E = S for the radius or via-point method
  kCollinear,       // 3602-CE-I7: S, V, E not distinct or on one line
  kRadiusTooSmall,  // 3602-CE-I7: |R| < |E - S| / 2
  kRadiusTooLarge,  // 3602-CE-I7: the circle's radius above 2,147,483,647
};

struct PathGeometry {
  GeometryFault fault = GeometryFault::kNone;
  planner::PathSpec spec;  // shape, end, centre, sweep; the profile is the caller's
  double radius = 0.0;     // arcs: |S - C|
};

// The path of `c` from the start point (start_x, start_y) (the axes' positions; used for
// absolute coordinates).
PathGeometry path_geometry(const InterpolatedCommand& c, std::int64_t start_x,
                           std::int64_t start_y) noexcept;

// The manual's rounding of a distance (fraction >= 0.5 rounds up), exact for an integer vector.
std::int64_t rounded_length(std::int64_t dx, std::int64_t dy) noexcept;

}  // namespace stepmod::module::m3602
