#pragma once
// The ideal path of a PathSpec and the checkers of step points against it, written from
// path_spec.hpp's contract (not from planner/path_law): an independent reference. Without gtest
// or the planner's code, so that any test program can use it (the path tests in virtual time,
// the daemon's path test and the VM case, which rebuild step points from a VCD).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/clock.hpp"
#include "planner/path_spec.hpp"

namespace stepmod::planner::test {

inline constexpr double kPi = std::numbers::pi;

// One step of either axis, in time order: the point (x, y) after it.
struct PathPoint {
  Nanos t;
  unsigned axis;
  std::int64_t x, y;
};

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
