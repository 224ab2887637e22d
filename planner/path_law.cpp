#include "planner/path_law.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace stepmod::planner {

namespace {
constexpr double kPi = std::numbers::pi;
// Reversals closer than this (rad) to the path's ends are the ends themselves.
constexpr double kAngleEps = 1e-12;

int sign_of(double v) noexcept {
  return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0);
}
}  // namespace

void PathLaw::init(const PathSpec& p, PathCoordinate c) noexcept {
  *this = PathLaw{};
  y_ = c == PathCoordinate::kY;
  shape_ = p.shape;
  end_ = y_ ? p.end_y : p.end_x;
  // An arc without a sweep or a radius has no circle to follow (the module never sends one):
  // it is planned as the line to its end point, so the end is still exact.
  if (shape_ == PathShape::kArc &&
      (!(std::fabs(p.sweep) > 0.0) || std::hypot(p.centre_x, p.centre_y) == 0.0)) {
    shape_ = PathShape::kLine;
  }
  if (shape_ == PathShape::kLine) {
    init_line(p);
  } else {
    init_arc(p);
  }
}

void PathLaw::init_line(const PathSpec& p) noexcept {
  length_ = std::hypot(static_cast<double>(p.end_x), static_cast<double>(p.end_y));
  inv_end_ = end_ != 0 ? 1.0 / static_cast<double>(end_) : 0.0;
  n_ = 1;
  seg_[0].u1 = 1.0;
  seg_[0].dir = end_ > 0 ? 1 : (end_ < 0 ? -1 : 0);
  seg_[0].target = end_;
}

void PathLaw::init_arc(const PathSpec& p) noexcept {
  c_ = y_ ? p.centre_y : p.centre_x;
  const double sx = -p.centre_x;  // S - C
  const double sy = -p.centre_y;
  const double ex = static_cast<double>(p.end_x) - p.centre_x;  // E - C
  const double ey = static_cast<double>(p.end_y) - p.centre_y;
  r0_ = std::hypot(sx, sy);
  dr_ = std::hypot(ex, ey) - r0_;
  theta0_ = std::atan2(sy, sx);
  sweep_ = p.sweep;
  inv_sweep_ = sweep_ != 0.0 ? 1.0 / sweep_ : 0.0;
  length_ = (r0_ + 0.5 * dr_) * std::fabs(sweep_);
  off_ = y_ ? kPi / 2 : 0.0;
  phi0_ = theta0_ - off_;
  std::array<double, kMaxSegments> ends{};
  const std::size_t n = arc_reversals(ends);
  arc_segments(ends, n);
}

std::size_t PathLaw::arc_reversals(std::array<double, kMaxSegments>& ends) const noexcept {
  // The reversals: phi = k pi strictly inside the sweep, in path order.
  std::size_t n_ends = 0;
  const double phi1 = phi0_ + sweep_;
  const double lo = std::min(phi0_, phi1);
  const double hi = std::max(phi0_, phi1);
  for (double k = std::floor(lo / kPi) + 1.0; k * kPi < hi; k += 1.0) {
    const double phik = k * kPi;
    if (phik - lo <= kAngleEps || hi - phik <= kAngleEps) continue;
    if (n_ends + 1 >= kMaxSegments) break;
    ends[n_ends++] = (phik - phi0_) * inv_sweep_;
  }
  // k runs up: the reversals come in path order for a CCW sweep, in reverse for a CW one.
  if (sweep_ < 0.0) {
    for (std::size_t i = 0, j = n_ends; i + 1 < j; ++i, --j) std::swap(ends[i], ends[j - 1]);
  }
  ends[n_ends++] = 1.0;
  return n_ends;
}

void PathLaw::arc_segments(const std::array<double, kMaxSegments>& ends, std::size_t n) noexcept {
  double u0 = 0.0;
  double q0 = 0.0;         // the coordinate at the segment's start (exactly 0 at S)
  std::int64_t count = 0;  // the count at the segment's start
  n_ = n;
  for (std::size_t i = 0; i < n_; ++i) {
    Segment& sg = seg_[i];
    sg.u1 = ends[i];
    const double mid = phi0_ + sweep_ * 0.5 * (u0 + sg.u1);
    const double k = std::floor(mid / kPi);
    sg.k_pi = k * kPi;
    sg.k_odd = std::fmod(std::fabs(k), 2.0) != 0.0;
    const bool last = i + 1 == n_;
    const double q1 = last ? static_cast<double>(end_) : position(sg.u1);
    if (last) {
      // The end count is exact whatever the rounding: the last segment runs to it.
      sg.dir = end_ > count ? 1 : (end_ < count ? -1 : 0);
      sg.target = end_;
    } else {
      sg.dir = sign_of(q1 - q0);
      std::int64_t t = count;
      if (sg.dir > 0)
        t = std::max(count, static_cast<std::int64_t>(std::floor(q1 + kReachTolerance)));
      if (sg.dir < 0)
        t = std::min(count, static_cast<std::int64_t>(std::ceil(q1 - kReachTolerance)));
      sg.target = t;
    }
    count = sg.target;
    u0 = sg.u1;
    q0 = q1;
  }
}

double PathLaw::position(double u) const noexcept {
  if (shape_ == PathShape::kLine) return static_cast<double>(end_) * u;
  const double th = theta0_ + sweep_ * u;
  const double r = r0_ + dr_ * u;
  return c_ + r * (y_ ? std::sin(th) : std::cos(th));
}

std::int64_t PathLaw::reached(std::size_t i, double u) const noexcept {
  const Segment& sg = seg_[i];
  const std::int64_t from = i == 0 ? 0 : seg_[i - 1].target;
  if (u >= sg.u1) return sg.target;
  const double q = position(u);
  if (sg.dir > 0) {
    const auto n = static_cast<std::int64_t>(std::floor(q + kReachTolerance));
    return std::clamp(n, from, sg.target);
  }
  if (sg.dir < 0) {
    const auto n = static_cast<std::int64_t>(std::ceil(q - kReachTolerance));
    return std::clamp(n, sg.target, from);
  }
  return from;
}

double PathLaw::arc_u(const Segment& sg, double n, double u) const noexcept {
  const double r = r0_ + dr_ * u;
  const double cq = std::clamp((n - c_) / r, -1.0, 1.0);
  const double a = std::acos(cq);
  const double phi = sg.k_odd ? sg.k_pi + kPi - a : sg.k_pi + a;
  return (phi - phi0_) * inv_sweep_;
}

double PathLaw::solve(std::size_t i, double n, double u_lo) const noexcept {
  const Segment& sg = seg_[i];
  double u = 0.0;
  if (shape_ == PathShape::kLine) {
    u = n * inv_end_;
  } else {
    // On the circle of the radius at u_lo: one acos.
    const double r_lo = r0_ + dr_ * u_lo;
    const double cq = std::clamp((n - c_) / r_lo, -1.0, 1.0);
    const double a = std::acos(cq);
    u = ((sg.k_odd ? sg.k_pi + kPi - a : sg.k_pi + a) - phi0_) * inv_sweep_;
    if (dr_ != 0.0) {
      // The spiral: one Newton step on q(u) = n from there, without trigonometry (cos phi = cq,
      // sin phi from it and the half-turn), quadratic in the small radius change. Near a reversal
      // q is flat in u and Newton would overshoot: a second acos at the new radius instead.
      const double r = r0_ + dr_ * u;
      const double sa = std::sqrt(std::max(0.0, 1.0 - cq * cq));
      const double f = c_ + r * cq - n;
      const double fp = dr_ * cq - r * (sg.k_odd ? -sa : sa) * sweep_;
      const double step = fp != 0.0 ? f / fp : 0.0;
      if (std::fabs(step) <= 0.5 * std::fabs(u - u_lo)) {
        u -= step;
      } else {
        u = arc_u(sg, n, u);
      }
    }
  }
  return std::clamp(u, u_lo, sg.u1);
}

}  // namespace stepmod::planner
