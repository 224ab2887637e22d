// The interpolated path's speed: the manuals' profile (ch. 2) on the path length. The
// reference is written here from the manuals' formulas (ramp time k |V2 - V1| / A, distance
// T (V1 + V2) / 2, cruise the rest, peak Vpk^2 = Vs^2 + 2L / (ka/a + kd/d) for a triangle), for a
// length that is not an integer, with planner_test_util.hpp's ramp shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "path_test_util.hpp"

namespace stepmod::planner {
namespace {

using test::kPi;
using test::PathRig;

long double shape_k(AccelShape s) {
  return s == AccelShape::kTriangularS ? 2.0L : s == AccelShape::kTrapezoidalS ? 4.0L / 3.0L : 1.0L;
}

// The profile over path length `len` (vp > vs).
test::RefMove ref_path(long double len, const PathSpec& p) {
  const long double ka = shape_k(p.accel.shape), kd = shape_k(p.decel.shape);
  const long double vs = p.vs, vp = p.vp;
  const long double da = ka * (vp * vp - vs * vs) / (2 * p.accel.rate);
  const long double dd = kd * (vp * vp - vs * vs) / (2 * p.decel.rate);
  long double vpk = vp, tp = 0;
  if (da + dd <= len) {
    tp = (len - da - dd) / vp;
  } else {
    vpk = std::sqrt(vs * vs + 2 * len / (ka / p.accel.rate + kd / p.decel.rate));
  }
  return test::RefMove{test::ref_ramp(p.vs, static_cast<double>(vpk), p.accel),
                       test::ref_ramp(static_cast<double>(vpk), p.vs, p.decel), vpk, tp, len};
}

std::vector<Nanos> step_times(const PathRig& r, unsigned axis) {
  std::vector<Nanos> t;
  for (const rt::Edge& e : r.edges[axis]) {
    if (e.dpos != 0) t.push_back(e.t);
  }
  return t;
}

struct LineCase {
  std::int64_t dx, dy;
  double vs, vp, a, d;
  AccelShape shape;
};

TEST(PathProfile, LineStepsFollowTheProfileOnThePathLength) {
  for (const LineCase c :
       {LineCase{30'000, -12'000, 1'000, 20'000, 200'000, 100'000, AccelShape::kConstant},
        LineCase{-5'000, 7'000, 500, 40'000, 400'000, 400'000, AccelShape::kTriangularS},
        LineCase{9'000, 9'001, 800, 30'000, 300'000, 300'000, AccelShape::kTrapezoidalS},
        LineCase{600, 250, 1'000, 50'000, 100'000, 100'000, AccelShape::kConstant}}) {
    SCOPED_TRACE(::testing::Message() << "line " << c.dx << ", " << c.dy);
    PathSpec p = test::line(c.dx, c.dy, c.vs, c.vp, c.a, c.d);
    p.accel.shape = p.decel.shape = c.shape;
    PathRig r;
    ASSERT_TRUE(r.start(p));
    ASSERT_TRUE(r.run_until_done());
    const long double len =
        std::hypot(static_cast<long double>(c.dx), static_cast<long double>(c.dy));
    const test::RefMove ref = ref_path(len, p);
    const std::vector<Nanos> tx = step_times(r, 0);
    ASSERT_EQ(static_cast<std::int64_t>(tx.size()), std::llabs(c.dx));
    // X's step k is where the path length is k L / |dx|: its time on the reference profile.
    const long double per = len / std::llabs(c.dx);
    const Nanos origin = tx[0] - static_cast<Nanos>(std::llround(ref.time_of(per) * 1e9));
    long double worst = 0;
    for (std::size_t k = 1; k <= tx.size(); ++k) {
      const long double want = ref.time_of(per * k) * 1e9L;
      worst = std::max(worst, std::fabs(static_cast<long double>(tx[k - 1] - origin) - want));
    }
    EXPECT_LT(worst, 1'000.0L) << "ns";  // every step within 1 us of the profile
    // Total time within 1 % (it is far closer).
    const long double total = static_cast<long double>(tx.back() - origin) * 1e-9L;
    EXPECT_NEAR(static_cast<double>(total), static_cast<double>(ref.total()),
                0.01 * static_cast<double>(ref.total()));
    if (ref.tp > 0.05L) {
      // Cruise vector speed: the middle of the cruise, from X's steps.
      const auto k0 = static_cast<std::size_t>((ref.up.dist() + 0.25L * ref.vpk * ref.tp) / per);
      const auto k1 = static_cast<std::size_t>((ref.up.dist() + 0.75L * ref.vpk * ref.tp) / per);
      const double v = static_cast<double>((k1 - k0) * per) /
                       (static_cast<double>(tx[k1 - 1] - tx[k0 - 1]) * 1e-9);
      EXPECT_NEAR(v, c.vp, 0.01 * c.vp);
    }
  }
}

TEST(PathProfile, ArcCruiseVectorSpeedAndTotalTimeFollowTheProfile) {
  const double rad = 3'000.25;
  for (const double sweep : {1.5 * kPi, -2 * kPi}) {
    SCOPED_TRACE(::testing::Message() << "sweep " << sweep);
    const PathSpec p = test::arc(0.0, -rad, sweep, 1'000, 25'000, 250'000, 250'000);
    PathRig r;
    ASSERT_TRUE(r.start(p));
    ASSERT_TRUE(r.run_until_done());
    const std::vector<test::PathPoint> pts = test::rebuild(r);
    // The arc's length: the mean radius times the sweep.
    const long double r1 = std::hypot(static_cast<double>(p.end_x), p.end_y + rad);
    const long double len = (rad + r1) / 2 * std::fabs(sweep);
    const test::RefMove ref = ref_path(len, p);
    ASSERT_GT(ref.tp, 0.1L);
    // Time 0 from the first step: it lies where the path has run the first point's arc length.
    const auto arc_to = [&](const test::PathPoint& q) {
      // The start point is at pi/2 about the centre (0, -rad).
      double a = std::atan2(static_cast<double>(q.y) + rad, static_cast<double>(q.x)) - kPi / 2;
      a = std::fmod(a * (sweep > 0 ? 1 : -1) + 4 * kPi, 2 * kPi);
      return a * rad;
    };
    // Cruise: between 30 % and 70 % of the cruise time, the angle swept per second.
    const Nanos t_first = pts.front().t;
    const long double t_of_first = ref.time_of(arc_to(pts.front()));
    const Nanos origin = t_first - static_cast<Nanos>(std::llround(t_of_first * 1e9L));
    const Nanos ta = origin + static_cast<Nanos>((ref.up.t + 0.3L * ref.tp) * 1e9L);
    const Nanos tb = origin + static_cast<Nanos>((ref.up.t + 0.7L * ref.tp) * 1e9L);
    std::size_t ia = 0;
    while (pts[ia].t < ta) ++ia;
    std::size_t ib = ia;
    while (pts[ib].t < tb) ++ib;
    const double v =
        (arc_to(pts[ib]) - arc_to(pts[ia])) / (static_cast<double>(pts[ib].t - pts[ia].t) * 1e-9);
    EXPECT_NEAR(v, p.vp, 0.01 * p.vp);
    const double total = static_cast<double>(pts.back().t - origin) * 1e-9;
    EXPECT_NEAR(total, static_cast<double>(ref.total()), 0.01 * static_cast<double>(ref.total()));
  }
}

}  // namespace
}  // namespace stepmod::planner
