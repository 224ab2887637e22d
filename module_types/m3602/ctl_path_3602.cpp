#include "module_types/m3602/ctl_path_3602.hpp"

#include <string>

#include "tools/ctl_dialects.hpp"

namespace stepmod::tools::ctl {

namespace {

// Points and the radius travel as the binary split of two 16-bit words (3602 manual ch. 9): any
// int32.
constexpr Limits kPoint{INT32_MIN, INT32_MAX, "the 3602's two words"};

using Method = plc::PathMove3602::Method;

Method circular(const std::string& sense, Method cw, Method ccw) {
  if (sense == "cw" || sense == "CW") return cw;
  if (sense == "ccw" || sense == "CCW") return ccw;
  throw UsageError("the sense of a circular move is cw or ccw, not '" + sense + "'");
}

}  // namespace

plc::PathMove3602 path_move_3602(const CtlRequest& c, const ProfileLimits& limits) {
  const PathArgs& a = c.path;
  if (c.unit != 0) {
    throw UsageError(
        "an interpolated move drives both axes and is commanded on axis 1: no --axis 2");
  }
  plc::PathMove3602 m;
  m.absolute = a.absolute;
  m.end_x = parse_limited(a.end_x, "X", kPoint);
  m.end_y = parse_limited(a.end_y, "Y", kPoint);
  if (a.method == "line") {
    m.method = Method::kLinear;
  } else if (a.method == "centre") {
    m.method = circular(a.sense, Method::kCentreCw, Method::kCentreCcw);
    m.point_x = parse_limited(a.point_x, "CX", kPoint);
    m.point_y = parse_limited(a.point_y, "CY", kPoint);
  } else if (a.method == "radius") {
    m.method = circular(a.sense, Method::kRadiusCw, Method::kRadiusCcw);
    m.radius = parse_limited(a.radius, "R", kPoint);
  } else if (a.method == "via") {
    m.method = Method::kViaPoint;
    m.point_x = parse_limited(a.point_x, "VX", kPoint);
    m.point_y = parse_limited(a.point_y, "VY", kPoint);
  } else {
    throw UsageError("path: line, centre, radius or via, not '" + a.method + "'");
  }
  m.profile = parse_profile(c.profile, limits);
  return m;
}

plc::Outcome run_path_3602(const CtlRequest& c, plc::Port& port, std::chrono::milliseconds timeout,
                           const ProfileLimits& limits) {
  plc::Interp3602 interp(port, timeout);
  if (c.verb == Verb::kPathWait) {
    if (c.unit != 0) throw UsageError("path wait waits for both axes: no --axis 2");
    return interp.wait_done(millis(c.wait_seconds));
  }
  return interp.move(path_move_3602(c, limits));
}

}  // namespace stepmod::tools::ctl
