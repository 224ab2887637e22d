#pragma once
// A 3602 path read back from a VCD trace the way an outside checker would, and the ideal arc of a
// commanded geometry to check it against (tests/planner/path_ideal.hpp): shared by the daemon's
// path test and the VM's circle case.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "planner/path_spec.hpp"
#include "tests/planner/path_ideal.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::testing {

// The path's (x, y) after every step edge of the VCD, in time order: rising edges of
// axisN.step, each counted +1 or -1 by the level of axisN.dir at that instant (high = CW = +1).
inline std::vector<planner::test::PathPoint> rebuild_from_vcd(const Vcd& vcd) {
  std::vector<planner::test::PathPoint> steps;
  for (unsigned a = 0; a < 2; ++a) {
    const std::string ax = "axis" + std::to_string(a + 1);
    const std::vector<VcdChange>& dir = vcd.wires.at(ax + ".dir");
    std::size_t d = 0;
    int level = 0;
    for (const std::int64_t t : vcd.rising(ax + ".step")) {
      while (d < dir.size() && dir[d].t <= t) level = dir[d++].level;
      steps.push_back({t, a, level != 0 ? 1 : -1, 0});  // x: the step's sign for now
    }
  }
  std::stable_sort(steps.begin(), steps.end(),
                   [](const planner::test::PathPoint& l, const planner::test::PathPoint& r) {
                     return l.t < r.t || (l.t == r.t && l.axis < r.axis);
                   });
  std::int64_t x = 0, y = 0;
  for (planner::test::PathPoint& p : steps) {
    (p.axis == 0 ? x : y) += p.x;
    p.x = x;
    p.y = y;
  }
  return steps;
}

// The ideal arc from S = (0, 0) to the end E around the centre C (relative to S) in the given
// sense; E = S: a full circle. Written from the manual's geometry, not from module_types/m3602.
inline planner::PathSpec arc_spec(double cx, double cy, std::int64_t ex, std::int64_t ey, bool cw) {
  planner::PathSpec p;
  p.shape = planner::PathShape::kArc;
  p.centre_x = cx;
  p.centre_y = cy;
  p.end_x = ex;
  p.end_y = ey;
  const double a0 = std::atan2(-cy, -cx);
  const double a1 = std::atan2(static_cast<double>(ey) - cy, static_cast<double>(ex) - cx);
  double sweep = a1 - a0;
  if (cw) {
    while (sweep >= 0) sweep -= 2 * planner::test::kPi;
  } else {
    while (sweep <= 0) sweep += 2 * planner::test::kPi;
  }
  p.sweep = sweep;
  return p;
}

}  // namespace stepmod::testing
