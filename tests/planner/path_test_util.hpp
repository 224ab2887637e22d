#pragma once
// Shared helpers of the path tests: two axes of one planner in virtual time (each with its ring,
// control block and MotionPort), the path rebuilt from the two step trains, and paths to command.
// The independent reference of the ideal path and its checkers are in path_ideal.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include "core/spsc_ring.hpp"
#include "planner/motion_port.hpp"
#include "planner/planner.hpp"
#include "planner_test_util.hpp"
#include "rt/axis_feedback.hpp"
#include "rt/edge.hpp"
#include "tests/planner/path_ideal.hpp"

namespace stepmod::planner::test {

// Two axes (X = axis 0, Y = axis 1), the pulse thread's side only collects their edges.
struct PathRig {
  explicit PathRig(PlannerOptions opt = {}, AxisTiming timing = {}) {
    for (unsigned i = 0; i < 2; ++i) {
      rings[i] = std::make_unique<SpscRing<rt::Edge>>(1u << 16);
      axes[i] = PlannerAxis{rings[i].get(), &control[i], timing, &feedback[i]};
    }
    planner = std::make_unique<Planner>(std::span<const PlannerAxis>(axes), opt);
    for (unsigned i = 0; i < 2; ++i) {
      ports[i] = std::make_unique<MotionPort>(i, *planner, feedback[i], control[i], history[i]);
    }
  }
  void service() {
    planner->service(now);
    for (unsigned i = 0; i < 2; ++i) {
      rt::Edge e;
      while (rings[i]->try_pop(e)) {
        edges[i].push_back(e);
        if ((e.flags & rt::edge_flag::kLast) != 0) finished[i].push_back(e.epoch);
      }
    }
  }
  // Both axes' path starts in one group; returns false if a submit failed.
  bool start(const PathSpec& p) {
    const GroupTag g = ids.next(2);
    return ports[0]->start_path(p, PathCoordinate::kX, g) != 0 &&
           ports[1]->start_path(p, PathCoordinate::kY, g) != 0;
  }
  bool resume(double vp, Ramp accel, Ramp decel) {
    const GroupTag g = ids.next(2);
    return ports[0]->resume_path(PathCoordinate::kX, vp, accel, decel, g) != 0 &&
           ports[1]->resume_path(PathCoordinate::kY, vp, accel, decel, g) != 0;
  }
  bool done(unsigned axis, std::uint32_t epoch) const {
    return std::find(finished[axis].begin(), finished[axis].end(), epoch) != finished[axis].end();
  }
  // Services every `tick` until both axes' newest motions have ended (or `limit` passed).
  bool run_until_done(Nanos limit = 600 * kNsPerSec, Nanos tick = kNsPerMs) {
    const Nanos end = now + limit;
    while (now < end) {
      service();
      if (done(0, ports[0]->epoch()) && done(1, ports[1]->epoch())) return true;
      now += tick;
    }
    return false;
  }
  void run_for(Nanos d, Nanos tick = kNsPerMs) {
    for (const Nanos end = now + d; now < end; now += tick) service();
  }

  std::array<std::unique_ptr<SpscRing<rt::Edge>>, 2> rings;
  std::array<rt::AxisControl, 2> control;
  std::array<rt::AxisFeedback, 2> feedback;
  std::array<rt::StepHistory, 2> history;
  std::array<PlannerAxis, 2> axes;
  std::unique_ptr<Planner> planner;
  std::array<std::unique_ptr<MotionPort>, 2> ports;
  std::array<std::vector<rt::Edge>, 2> edges;
  std::array<std::vector<std::uint32_t>, 2> finished;
  GroupIds ids;
  Nanos now = kT0;
};

// The two step trains merged by time (axis 0 first on a tie), counts accumulated from (x0, y0).
// Only the steps of motions with epoch >= first_epoch[axis].
inline std::vector<PathPoint> rebuild(const PathRig& r,
                                      std::array<std::uint32_t, 2> first_epoch = {1, 1},
                                      std::int64_t x0 = 0, std::int64_t y0 = 0) {
  std::array<std::vector<rt::Edge>, 2> st;
  for (unsigned a = 0; a < 2; ++a) {
    for (const rt::Edge& e : r.edges[a]) {
      if (e.dpos != 0 && e.epoch >= first_epoch[a]) st[a].push_back(e);
    }
  }
  std::vector<PathPoint> out;
  out.reserve(st[0].size() + st[1].size());
  std::size_t i = 0, j = 0;
  std::int64_t x = x0, y = y0;
  while (i < st[0].size() || j < st[1].size()) {
    const bool take_x = j >= st[1].size() || (i < st[0].size() && st[0][i].t <= st[1][j].t);
    if (take_x) {
      x += st[0][i].dpos;
      out.push_back({st[0][i++].t, 0, x, y});
    } else {
      y += st[1][j].dpos;
      out.push_back({st[1][j++].t, 1, x, y});
    }
  }
  return out;
}

inline std::int64_t steps_of(const PathRig& r, unsigned axis, std::uint32_t epoch) {
  std::int64_t n = 0;
  for (const rt::Edge& e : r.edges[axis]) n += e.dpos != 0 && e.epoch == epoch;
  return n;
}

inline PathSpec line(std::int64_t dx, std::int64_t dy, double vs = 1'000, double vp = 20'000,
                     double accel = 200'000, double decel = 200'000) {
  PathSpec p;
  p.shape = PathShape::kLine;
  p.end_x = dx;
  p.end_y = dy;
  p.vs = vs;
  p.vp = vp;
  p.accel = Ramp{accel, AccelShape::kConstant};
  p.decel = Ramp{decel, AccelShape::kConstant};
  return p;
}

// An arc from S = (0, 0) around C = S + (cx, cy), sweeping `sweep` rad; the end point is the
// circle's point at that angle rounded to integers (the module's integer world).
inline PathSpec arc(double cx, double cy, double sweep, double vs = 1'000, double vp = 20'000,
                    double accel = 200'000, double decel = 200'000) {
  PathSpec p;
  p.shape = PathShape::kArc;
  p.centre_x = cx;
  p.centre_y = cy;
  p.sweep = sweep;
  const double r = std::hypot(cx, cy);
  const double a = std::atan2(-cy, -cx) + sweep;
  p.end_x = std::llround(cx + r * std::cos(a));
  p.end_y = std::llround(cy + r * std::sin(a));
  // The sweep is the angle to the rounded end point (path_spec.hpp): the nominal one corrected
  // by the rounding's angle (a fraction of a step over the radius).
  double da = std::atan2(static_cast<double>(p.end_y) - cy, static_cast<double>(p.end_x) - cx) - a;
  da = std::remainder(da, 2 * kPi);
  p.sweep = sweep + da;
  p.vs = vs;
  p.vp = vp;
  p.accel = Ramp{accel, AccelShape::kConstant};
  p.decel = Ramp{decel, AccelShape::kConstant};
  return p;
}

}  // namespace stepmod::planner::test
