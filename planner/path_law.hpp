#pragma once
// The geometry of an interpolated path (planner/path_spec.hpp) for one of its coordinates: where
// the coordinate is at each point of the path, where it reverses, and at which point of the path
// it reaches a given integer. The step source (planner/path_source.hpp) asks only these
// questions, as Klipper's step solver asks a kinematics only for a position (itersolve.c,
// kin_corexy.c): a new path shape is a new law, the stepping stays the same.
//
// The path is parametrised by u in [0, 1], the fraction of its length L (s = u L):
//   line: q(u) = end_q u;                             L = sqrt(dx^2 + dy^2)
//   arc:  q(u) = c_q + r(u) cos(theta(u) - off_q),    theta(u) = theta0 + sweep u,
//         r(u) = r0 + (r1 - r0) u (path_spec.hpp),    off_x = 0, off_y = pi/2,
//         L = (r0 + r1) / 2 |sweep| (the mean radius times the sweep; exact for a circle, and the
//         spiral's true length differs from it by less than (r1 - r0)^2 / (2 r |sweep|) < 1 step
//         in the integer world, where |r1 - r0| < 1).
// A coordinate of an arc reverses where theta - off_q is a multiple of pi (the extremes of the
// circle through the point; the spiral moves the true extreme by (r1 - r0) / (r |sweep|) rad,
// where the coordinate differs from its value at the circle's extreme by
// (r1 - r0)^2 / (2 r sweep^2): with |r1 - r0| < 1, below 0.01 step once r sweep^2 > 50, e.g. a
// quarter turn of radius 20; only arcs a few steps long can spiral more, and they still end
// exactly). Between two reversals the coordinate is monotone: a *segment*. The segments are
// found once per path (at most 3 for a full turn).
#include <array>
#include <cstddef>
#include <cstdint>

#include "planner/path_spec.hpp"

namespace stepmod::planner {

class PathLaw {
 public:
  // A full turn has at most 2 interior reversals per coordinate; room for rounding at the ends.
  static constexpr std::size_t kMaxSegments = 6;
  // A coordinate this close to an integer (steps) counts as reaching it: the rounding of r cos
  // for radii up to 1e8 steps is far below it.
  static constexpr double kReachTolerance = 1e-7;

  void init(const PathSpec& spec, PathCoordinate c) noexcept;

  double length() const noexcept { return length_; }
  // The exact end count of this coordinate (end_x or end_y).
  std::int64_t end() const noexcept { return end_; }
  // The coordinate at fraction u of the path (u = s / length()).
  double position(double u) const noexcept;

  // Segments in path order: segment i runs from segment_end(i - 1) (0 for i = 0) to
  // segment_end(i); its direction (+1, -1; 0 = the coordinate does not move) and its target, the
  // count reached at its end (the last segment's is end()).
  std::size_t segments() const noexcept { return n_; }
  double segment_end(std::size_t i) const noexcept { return seg_[i].u1; }
  int direction(std::size_t i) const noexcept { return seg_[i].dir; }
  std::int64_t target(std::size_t i) const noexcept { return seg_[i].target; }
  // The path length s of the coordinate's reversals (the interior segment ends).
  double extreme_s(std::size_t i) const noexcept { return seg_[i].u1 * length_; }
  std::size_t extremes() const noexcept { return n_ - 1; }
  // The count reached by point u of segment i: the last integer passed in its direction.
  std::int64_t reached(std::size_t i, double u) const noexcept;

  // The point u of segment i, not before u_lo, at which the coordinate reaches integer n (n lies
  // between the count at u_lo and the segment's target). The per-step path: one acos, on a
  // spiral one Newton step more (a second acos next to a reversal).
  double solve(std::size_t i, double n, double u_lo) const noexcept;

 private:
  struct Segment {
    double u1 = 1.0;
    int dir = 0;
    std::int64_t target = 0;
    // Arc: the half-turn index k of the segment (phi = theta - off_q in [k pi, (k + 1) pi]).
    double k_pi = 0.0;  // k pi
    bool k_odd = false;
  };
  double arc_u(const Segment& sg, double n, double u) const noexcept;
  // init(), by shape: the line's one segment; the arc's geometry, its reversals (the segment
  // ends, in path order, the last one 1) and the segments between them.
  void init_line(const PathSpec& p) noexcept;
  void init_arc(const PathSpec& p) noexcept;
  std::size_t arc_reversals(std::array<double, kMaxSegments>& ends) const noexcept;
  void arc_segments(const std::array<double, kMaxSegments>& ends, std::size_t n) noexcept;

  PathShape shape_ = PathShape::kLine;
  bool y_ = false;  // the Y coordinate (sin) rather than X (cos)
  double length_ = 0.0;
  std::int64_t end_ = 0;
  double inv_end_ = 0.0;  // line: 1 / end_q
  double c_ = 0.0;        // arc: centre coordinate
  double r0_ = 0.0, dr_ = 0.0;
  double theta0_ = 0.0, sweep_ = 0.0, inv_sweep_ = 0.0, phi0_ = 0.0;
  double off_ = 0.0;  // arc: pi/2 for Y
  std::array<Segment, kMaxSegments> seg_{};
  std::size_t n_ = 0;
};

}  // namespace stepmod::planner
