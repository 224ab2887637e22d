#pragma once
// Shared helpers of the path tests: two axes of one planner in virtual time (each with its ring,
// control block and MotionPort), the path rebuilt from the two step trains, and an independent
// reference of the ideal path (written from path_spec.hpp's contract, not from planner/path_law).
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

namespace stepmod::planner::test {

inline constexpr double kPi = std::numbers::pi;

// Two axes (X = axis 0, Y = axis 1), the pulse thread's side only collects their edges.
struct PathRig {
  explicit PathRig(PlannerOptions opt = {}, AxisTiming timing = {}) {
    for (unsigned i = 0; i < 2; ++i) {
      rings[i] = std::make_unique<SpscRing<rt::Edge>>(1u << 16);
      axes[i] = PlannerAxis{rings[i].get(), &control[i], timing};
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

// One step of either axis, in time order: the point (x, y) after it.
struct PathPoint {
  Nanos t;
  unsigned axis;
  std::int64_t x, y;
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

// The ideal path of path_spec.hpp, written from its contract: distance of a point from it.
struct IdealPath {
  explicit IdealPath(const PathSpec& p) : s(p) {}
  double distance(double px, double py) const {
    const double ex = static_cast<double>(s.end_x), ey = static_cast<double>(s.end_y);
    if (s.shape == PathShape::kLine) {
      const double l2 = ex * ex + ey * ey;
      if (l2 == 0.0) return std::hypot(px, py);
      const double u = std::clamp((px * ex + py * ey) / l2, 0.0, 1.0);
      return std::hypot(px - u * ex, py - u * ey);
    }
    const double cx = s.centre_x, cy = s.centre_y;
    const double r0 = std::hypot(cx, cy), r1 = std::hypot(ex - cx, ey - cy);
    const double a0 = std::atan2(-cy, -cx);
    const double ap = std::atan2(py - cy, px - cx);
    // Angle from the start in the path's sense, in [0, 2 pi).
    double d = (ap - a0) * (s.sweep > 0 ? 1.0 : -1.0);
    d = std::fmod(d, 2 * kPi);
    if (d < 0) d += 2 * kPi;
    const double to_ends = std::min(std::hypot(px, py), std::hypot(px - ex, py - ey));
    if (d > std::fabs(s.sweep)) return to_ends;
    const double u = d / std::fabs(s.sweep);
    const double r = r0 + (r1 - r0) * u;
    return std::min(to_ends, std::fabs(std::hypot(px - cx, py - cy) - r));
  }
  PathSpec s;
};

// Largest distance of any step point from the ideal path (every `stride`-th point and the last).
// Steps of both axes at the same instant are one event: the point after the last of them counts.
inline double max_path_error(const std::vector<PathPoint>& pts, const PathSpec& p,
                             std::size_t stride = 1) {
  const IdealPath ideal(p);
  double worst = 0.0;
  const auto check = [&](std::size_t i) {
    while (i + 1 < pts.size() && pts[i + 1].t == pts[i].t) ++i;
    worst = std::max(worst,
                     ideal.distance(static_cast<double>(pts[i].x), static_cast<double>(pts[i].y)));
  };
  for (std::size_t i = 0; i < pts.size(); i += stride) check(i);
  if (!pts.empty()) check(pts.size() - 1);
  return worst;
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

// Integer crossings of a coordinate over an arc, counted independently: the coordinate sampled
// densely along the ideal spiral (and at the circle's extremes, where it turns), each monotone
// run counted by the integers it reaches (a value within 1e-7 of an integer reaches it, as a
// tangent extreme on an integer does).
inline std::int64_t arc_crossings(const PathSpec& p, bool y, int samples = 4'096) {
  const double cx = p.centre_x, cy = p.centre_y;
  const double ex = static_cast<double>(p.end_x), ey = static_cast<double>(p.end_y);
  const double r0 = std::hypot(cx, cy), r1 = std::hypot(ex - cx, ey - cy);
  const double a0 = std::atan2(-cy, -cx);
  auto q = [&](double u) {
    const double a = a0 + p.sweep * u, r = r0 + (r1 - r0) * u;
    return y ? cy + r * std::sin(a) : cx + r * std::cos(a);
  };
  std::vector<double> us;
  for (int i = 1; i < samples; ++i) us.push_back(static_cast<double>(i) / samples);
  for (int k = -16; k <= 16; ++k) {
    const double u = (k * kPi / 2 - a0) / p.sweep;
    if (u > 0.0 && u < 1.0) us.push_back(u);
  }
  std::sort(us.begin(), us.end());
  us.push_back(1.0);
  std::int64_t n = 0, count = 0;
  double prev = 0.0;
  int dir = 0;
  for (const double u : us) {
    const double v = u == 1.0 ? (y ? ey : ex) : q(u);
    const int d = v > prev ? 1 : (v < prev ? -1 : 0);
    if (d != 0) dir = d;
    std::int64_t c = count;
    if (dir > 0) c = std::max(count, static_cast<std::int64_t>(std::floor(v + 1e-7)));
    if (dir < 0) c = std::min(count, static_cast<std::int64_t>(std::ceil(v - 1e-7)));
    n += c > count ? c - count : count - c;
    count = c;
    prev = v;
  }
  return n;
}

}  // namespace stepmod::planner::test
