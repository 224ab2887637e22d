#pragma once
// A coordinated path in the X-Y plane: the 3602's interpolated moves (3602 manual ch. 3). X is axis
// 1's step count, Y axis 2's, increasing counts = CW pulses on that axis; X to the right and Y up,
// so "CCW" is the mathematical positive sense. Coordinates are relative to the path's start point
// S = (0, 0). The module builds a PathSpec (the manual's methods and its "integer world" check
// live there); the planner turns it into both axes' steps on one time base.
//
// The law: the manuals' profile (ch. 2) on the path length s; each axis' position is the
// path's X or Y at s, and each axis steps when that position reaches its next integer in its
// direction of travel. Both axes solve the same s(t), so their steps interleave as the path
// demands, and both end on the exact end point.
#include <cstdint>

#include "planner/ramp.hpp"

namespace stepmod::planner {

enum class PathShape : std::uint8_t { kLine, kArc };

struct PathSpec {
  PathShape shape = PathShape::kLine;
  // E - S in steps: the exact end point. Both axes end on it whatever the path's length.
  std::int64_t end_x = 0;
  std::int64_t end_y = 0;
  // Arc only. C - S (need not be integers: the radius and via-point methods compute it).
  double centre_x = 0.0;
  double centre_y = 0.0;
  // Arc only: the signed angle swept from S to E around C, rad: > 0 CCW, < 0 CW,
  // 0 < |sweep| <= 2 pi (2 pi: a full circle, E = S). The radius runs linearly in the angle from
  // |S - C| at S to |E - C| at E (in the integer world they differ by less than a step), so the
  // path passes through both points exactly.
  double sweep = 0.0;
  // The profile on the path: vector speeds (steps/s) and rates (steps/s^2).
  double vs = 1.0;
  double vp = 1.0;
  Ramp accel;
  Ramp decel;
};

// Which of the path's coordinates an axis follows.
enum class PathCoordinate : std::uint8_t { kX = 0, kY = 1 };

// Starts motion `epoch` of the command's axis as `coordinate` of the path. Both axes' starts
// carry one GroupTag of size 2, so they share one time 0.
struct PathStart {
  PathSpec spec;
  PathCoordinate coordinate = PathCoordinate::kX;
};

// Starts motion `epoch` of the command's axis as the continuation of its held path (the last path
// motion, ended by a PathHold) from where the hold left it to the path's exact end, with a new
// profile (vs is the path's). A group of 2, as PathStart. Without a held path to continue (an
// abort or another motion since), the motion ends at once without a step.
struct PathResume {
  PathCoordinate coordinate = PathCoordinate::kX;
  double vp = 1.0;
  Ramp accel;
  Ramp decel;
};

// Controlled stop along the path (Hold, External input): sent on either axis, applied by the
// planner to both axes of the running path from one point of the path, so the axes stay on the
// path while they decelerate. The path stays resumable (PathResume).
struct PathHold {
  Ramp ramp;
};

}  // namespace stepmod::planner
