// The manual's interpolated-move geometry (3602 manual Ch.3 "Interpolated Move Profiles", Ch.9
// Tables 9.23-9.26; A35, A36, A38).
#include "module_types/m3602/circle_methods.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

namespace stepmod::module::m3602 {

namespace {

using Wide = __int128;
constexpr std::int64_t kInt32Max = 2'147'483'647;
constexpr long double kTwoPi = 2.0L * std::numbers::pi_v<long double>;

struct Point {
  std::int64_t x = 0;
  std::int64_t y = 0;
};

// floor(sqrt(v)) for 0 <= v < 2^100, exact: a long double estimate corrected by integer steps.
Wide isqrt(Wide v) noexcept {
  auto r = static_cast<Wide>(std::sqrt(static_cast<long double>(v)));
  while (r > 0 && r * r > v) --r;
  while ((r + 1) * (r + 1) <= v) ++r;
  return r;
}

// The manual's rounding of a real distance.
long double round_half_up(long double d) noexcept {
  return std::floor(d + 0.5L);
}

// A point of the command relative to the start point S.
Point relative(bool absolute, std::int32_t x, std::int32_t y, std::int64_t sx,
               std::int64_t sy) noexcept {
  return absolute ? Point{x - sx, y - sy} : Point{x, y};
}

// The sweep from S to E around C in the given sense: CCW (theta_E - theta_S) mod 2 pi, CW
// (theta_S - theta_E) mod 2 pi (3602 manual Ch.3); 0 (E = S) is a full circle.
double sweep(long double cx, long double cy, const Point& e, bool ccw, bool full_if_zero) noexcept {
  const long double ts = std::atan2(-cy, -cx);
  const long double te =
      std::atan2(static_cast<long double>(e.y) - cy, static_cast<long double>(e.x) - cx);
  long double d = ccw ? te - ts : ts - te;
  d = std::fmod(d, kTwoPi);
  if (d < 0) d += kTwoPi;
  if (d == 0 && full_if_zero) d = kTwoPi;
  return static_cast<double>(ccw ? d : -d);
}

// The integer-world check and the radius bound, for a centre in real numbers (A36: the centre
// the radius and via-point methods compute is not rounded).
GeometryFault check_radii(long double cx, long double cy, const Point& e, double& radius) noexcept {
  const long double rs = std::hypot(cx, cy);
  const long double re =
      std::hypot(static_cast<long double>(e.x) - cx, static_cast<long double>(e.y) - cy);
  radius = static_cast<double>(rs);
  if (round_half_up(rs) != round_half_up(re)) return GeometryFault::kRadiiDiffer;
  if (rs > static_cast<long double>(kInt32Max)) return GeometryFault::kRadiusTooLarge;
  return GeometryFault::kNone;
}

void arc(PathGeometry& g, long double cx, long double cy, const Point& e, bool ccw,
         bool full_if_zero) {
  g.spec.shape = planner::PathShape::kArc;
  g.spec.centre_x = static_cast<double>(cx);
  g.spec.centre_y = static_cast<double>(cy);
  g.spec.sweep = sweep(cx, cy, e, ccw, full_if_zero);
}

// Centre-point method: C given (integer), the sense from the command; E = S is a full circle.
void centre_method(const InterpolatedCommand& c, const Point& e, const Point& centre,
                   PathGeometry& g) {
  // The manual's example (3602 manual Ch.3, rounding): the rounded integer distances must be equal.
  const std::int64_t rs = rounded_length(-centre.x, -centre.y);
  const std::int64_t re = rounded_length(e.x - centre.x, e.y - centre.y);
  g.radius = std::hypot(static_cast<double>(centre.x), static_cast<double>(centre.y));
  if (rs != re) {
    g.fault = GeometryFault::kRadiiDiffer;
    return;
  }
  if (rs > kInt32Max || g.radius > static_cast<double>(kInt32Max)) {
    g.fault = GeometryFault::kRadiusTooLarge;
    return;
  }
  if (rs == 0) {
    g.fault = GeometryFault::kRadiiDiffer;  // C = S: no circle
    return;
  }
  arc(g, static_cast<long double>(centre.x), static_cast<long double>(centre.y), e, c.ccw, true);
}

// Radius method: the two circles of radius |R| through S and E; R > 0 the shorter arc, R < 0 the
// longer one, in the commanded sense (3602 manual Ch.3: CW short or CCW long -> C = M - h n, CW
// long or CCW short -> C = M + h n, n the left normal of S -> E).
void radius_method(const InterpolatedCommand& c, const Point& e, PathGeometry& g) {
  if (e.x == 0 && e.y == 0) {
    g.fault = GeometryFault::kStartIsEnd;
    return;
  }
  const Wide chord2 = static_cast<Wide>(e.x) * e.x + static_cast<Wide>(e.y) * e.y;
  const Wide r = c.radius;
  if (4 * r * r < chord2) {  // |R| >= |E - S| / 2, exact
    g.fault = GeometryFault::kRadiusTooSmall;
    return;
  }
  const long double chord = std::sqrt(static_cast<long double>(chord2));
  const long double rr = static_cast<long double>(c.radius);
  const long double h = std::sqrt(std::max(0.0L, rr * rr - chord * chord / 4.0L));
  const long double nx = -static_cast<long double>(e.y) / chord;
  const long double ny = static_cast<long double>(e.x) / chord;
  const bool short_arc = c.radius > 0;
  const long double side = (short_arc == c.ccw) ? 1.0L : -1.0L;
  const long double cx = static_cast<long double>(e.x) / 2.0L + side * h * nx;
  const long double cy = static_cast<long double>(e.y) / 2.0L + side * h * ny;
  g.fault = check_radii(cx, cy, e, g.radius);
  if (g.fault == GeometryFault::kNone) arc(g, cx, cy, e, c.ccw, false);
}

// Via-point method: the circle through S, V, E; the sense from the orientation of S -> V -> E,
// z = (V - S) x (E - S): z < 0 CW, z > 0 CCW, z = 0 (not distinct, or collinear) refused.
void via_method(const Point& e, const Point& v, PathGeometry& g) {
  const Wide z = static_cast<Wide>(v.x) * e.y - static_cast<Wide>(v.y) * e.x;
  if (z == 0) {
    g.fault = (e.x == 0 && e.y == 0) ? GeometryFault::kStartIsEnd : GeometryFault::kCollinear;
    return;
  }
  // Circumcentre of (0, 0), V, E.
  const long double vx = v.x, vy = v.y, ex = e.x, ey = e.y;
  const long double v2 = vx * vx + vy * vy;
  const long double e2 = ex * ex + ey * ey;
  const long double d = 2.0L * static_cast<long double>(z);
  const long double cx = (ey * v2 - vy * e2) / d;
  const long double cy = (vx * e2 - ex * v2) / d;
  g.fault = check_radii(cx, cy, e, g.radius);
  if (g.fault == GeometryFault::kNone) arc(g, cx, cy, e, z > 0, false);
}

}  // namespace

std::int64_t rounded_length(std::int64_t dx, std::int64_t dy) noexcept {
  const Wide d2 = static_cast<Wide>(dx) * dx + static_cast<Wide>(dy) * dy;
  const Wide n = isqrt(d2);
  // sqrt(d2) >= n + 0.5  <=>  d2 >= n^2 + n + 1/4  <=>  d2 > n^2 + n (integers).
  return static_cast<std::int64_t>(d2 > n * n + n ? n + 1 : n);
}

PathGeometry path_geometry(const InterpolatedCommand& c, std::int64_t start_x,
                           std::int64_t start_y) noexcept {
  PathGeometry g;
  const Point e = relative(c.absolute, c.end_x, c.end_y, start_x, start_y);
  g.spec.end_x = e.x;
  g.spec.end_y = e.y;
  // A32: a step count that does not fit the module's 32-bit registers (an absolute end point
  // seen from a start point far outside the +-2^30 box).
  if (std::llabs(e.x) > kInt32Max || std::llabs(e.y) > kInt32Max) {
    g.fault = GeometryFault::kOverflow;
    return g;
  }
  switch (c.method) {
    case InterpolationMethod::kLinear:
      g.spec.shape = planner::PathShape::kLine;
      break;
    case InterpolationMethod::kCentre:
      centre_method(c, e, relative(c.absolute, c.point_x, c.point_y, start_x, start_y), g);
      break;
    case InterpolationMethod::kRadius:
      radius_method(c, e, g);
      break;
    case InterpolationMethod::kViaPoint:
      via_method(e, relative(c.absolute, c.point_x, c.point_y, start_x, start_y), g);
      break;
  }
  return g;
}

}  // namespace stepmod::module::m3602
