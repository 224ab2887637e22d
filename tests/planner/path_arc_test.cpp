// The interpolated path, arcs (planner/path_source.hpp, path_law.hpp): exact end point, exactly
// the integer crossings on each axis, every step point within one step of the arc, reversals at
// the extremes; quarter, half and full circles both ways, quadrant crossings, tiny and huge radii.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "path_test_util.hpp"

namespace stepmod::planner {
namespace {

using test::arc;
using test::kPi;
using test::PathRig;

// Runs `p` to its end and checks the end point, the counts and the one-step bound.
void expect_arc(const PathSpec& p, std::size_t stride = 1) {
  SCOPED_TRACE(::testing::Message() << "arc C=(" << p.centre_x << ", " << p.centre_y << ") sweep "
                                    << p.sweep << " E=(" << p.end_x << ", " << p.end_y << ")");
  PathRig r;
  ASSERT_TRUE(r.start(p));
  ASSERT_TRUE(r.run_until_done());
  const std::vector<test::PathPoint> pts = test::rebuild(r);
  const std::int64_t ex = pts.empty() ? 0 : pts.back().x;
  const std::int64_t ey = pts.empty() ? 0 : pts.back().y;
  // The final counts: the net steps of each axis.
  std::int64_t nx = 0, ny = 0;
  for (const rt::Edge& e : r.edges[0]) nx += e.dpos;
  for (const rt::Edge& e : r.edges[1]) ny += e.dpos;
  EXPECT_EQ(nx, p.end_x);
  EXPECT_EQ(ny, p.end_y);
  if (!pts.empty()) {
    EXPECT_EQ(ex, p.end_x);
    EXPECT_EQ(ey, p.end_y);
  }
  EXPECT_EQ(test::steps_of(r, 0, 1), test::arc_crossings(p, false));
  EXPECT_EQ(test::steps_of(r, 1, 1), test::arc_crossings(p, true));
  EXPECT_LT(test::max_path_error(pts, p, stride), 1.0);
}

TEST(PathArc, QuarterHalfAndFullCirclesBothWaysEndExactlyOnTheirCrossings) {
  for (const double sweep : {kPi / 2, kPi, 2 * kPi}) {
    for (const double sense : {1.0, -1.0}) {
      expect_arc(arc(100.0, 0.0, sense * sweep));    // centre on the X axis
      expect_arc(arc(0.0, -250.0, sense * sweep));   // centre below
      expect_arc(arc(-73.4, 51.2, sense * sweep));   // off-grid centre
      expect_arc(arc(300.5, 300.5, sense * sweep));  // a half-integer diagonal
    }
  }
}

TEST(PathArc, ArcsCrossingQuadrantBoundariesReverseAtTheExtremes) {
  // From 30 degrees, 200 degrees CCW: X passes its minimum, Y its maximum.
  const double r = 400.0;
  const double a0 = kPi / 6;
  const PathSpec p = arc(-r * std::cos(a0), -r * std::sin(a0), 200.0 * kPi / 180.0);
  expect_arc(p);
  PathRig rig;
  ASSERT_TRUE(rig.start(p));
  ASSERT_TRUE(rig.run_until_done());
  // Each axis turns exactly once: X at 180 degrees, Y at 90 degrees.
  for (unsigned a = 0; a < 2; ++a) {
    int turns = 0;
    int dir = 0;
    for (const rt::Edge& e : rig.edges[a]) {
      if (e.dpos == 0) continue;
      if (dir != 0 && e.dpos != dir) ++turns;
      dir = e.dpos;
    }
    EXPECT_EQ(turns, 1) << "axis " << a;
  }
  // At X's turn the count is the circle's minimum rounded toward the start side (hysteresis):
  // the smallest x of any step point is ceil(cx - r).
  const std::vector<test::PathPoint> pts = test::rebuild(rig);
  std::int64_t xmin = 0;
  for (const auto& q : pts) xmin = std::min(xmin, q.x);
  EXPECT_EQ(xmin, static_cast<std::int64_t>(std::ceil(p.centre_x - r)));
}

TEST(PathArc, ArcsFromEveryOctantBothWays) {
  for (int k = 0; k < 8; ++k) {
    const double a0 = k * kPi / 4 + 0.1;
    for (const double sweep : {1.3, -1.3, 4.0, -4.0}) {
      expect_arc(arc(-157.3 * std::cos(a0), -157.3 * std::sin(a0), sweep));
    }
  }
}

TEST(PathArc, TinyRadiiOfOneToThreeStepsEndExactly) {
  for (const double rad : {1.0, 2.0, 3.0, 1.5, 2.7}) {
    for (const double sweep : {2 * kPi, -2 * kPi, kPi, -kPi / 2}) {
      expect_arc(arc(rad, 0.0, sweep, 100, 100));
      expect_arc(arc(0.0, rad, sweep, 100, 100));
    }
  }
}

TEST(PathArc, ShortArcOfAHugeRadiusEndsExactlyWithinOneStep) {
  // Radius 5,000,000: 0.01 rad is a 50,000-step arc.
  for (const double a0 : {0.3, 1.7, 3.9}) {
    for (const double sweep : {0.01, -0.01}) {
      expect_arc(arc(-5e6 * std::cos(a0), -5e6 * std::sin(a0), sweep, 1'000, 200'000, 2e6, 2e6), 3);
    }
  }
}

TEST(PathArc, FullCircleOfAMillionStepsEndsExactlyOnItsStart) {
  // Radius 125,000.3: 4 r steps on each axis, 1,000,000 in all; off the grid, so neither
  // coordinate's extremes are integers.
  const double rad = 125'000.3;
  const PathSpec p = arc(rad, 0.0, 2 * kPi, 1'000, 500'000, 2e6, 2e6);
  ASSERT_EQ(p.end_x, 0);
  ASSERT_EQ(p.end_y, 0);
  PathRig r;
  ASSERT_TRUE(r.start(p));
  ASSERT_TRUE(r.run_until_done());
  std::int64_t nx = 0, ny = 0;
  for (const rt::Edge& e : r.edges[0]) nx += e.dpos;
  for (const rt::Edge& e : r.edges[1]) ny += e.dpos;
  EXPECT_EQ(nx, 0);
  EXPECT_EQ(ny, 0);
  // X runs 0 -> floor(2r) -> 0; Y 0 -> -floor(r) -> floor(r) -> 0.
  const std::int64_t fx = static_cast<std::int64_t>(std::floor(2 * rad));
  const std::int64_t fy = static_cast<std::int64_t>(std::floor(rad));
  EXPECT_EQ(test::steps_of(r, 0, 1), 2 * fx);
  EXPECT_EQ(test::steps_of(r, 1, 1), 4 * fy);
  EXPECT_GE(test::steps_of(r, 0, 1) + test::steps_of(r, 1, 1), 1'000'000);
  const std::vector<test::PathPoint> pts = test::rebuild(r);
  EXPECT_LT(test::max_path_error(pts, p, 101), 1.0);
  // The last 1,000 points of both axes, one by one: the end closes the circle within a step.
  const std::vector<test::PathPoint> tail(pts.end() - 1'000, pts.end());
  EXPECT_LT(test::max_path_error(tail, p), 1.0);
}

// Checks every turn of both axes: the direction line changed after the previous pulse ended and
// at least the set-up time before the turned step, at the level of the new direction.
void expect_turns_set_up(const PathRig& r, const AxisTiming& timing) {
  for (unsigned a = 0; a < 2; ++a) {
    int dir = 0;
    int level = 0;  // lines idle low: CCW
    Nanos dir_t = 0;
    Nanos prev_trailing = 0;
    int turns = 0;
    for (const rt::Edge& e : r.edges[a]) {
      if (e.line == OutputLine::kDir) {
        dir_t = e.t;
        level = e.level;
        EXPECT_GE(e.t, prev_trailing) << "direction changed under a pulse";
        continue;
      }
      if (e.dpos == 0) {
        prev_trailing = e.t;
        continue;
      }
      if (dir != 0 && e.dpos != dir) {
        ++turns;
        EXPECT_GE(e.t - dir_t, timing.dir_setup_ns) << "axis " << a;
      }
      EXPECT_EQ(level, e.dpos > 0 ? 1 : 0) << "axis " << a << " at " << e.t;  // 1 = CW
      dir = e.dpos;
    }
    EXPECT_GE(turns, 1) << "axis " << a;
  }
}

TEST(PathArc, ATurnWritesTheDirectionLineASetUpTimeBeforeTheTurnedStep) {
  const AxisTiming timing{2'000, 20'000};
  {
    // Three quarters of a circle: both axes turn; 50 us per step of path.
    PathRig r({}, timing);
    const PathSpec p = arc(0.0, 40.5, -1.5 * kPi, 20'000, 20'000);
    ASSERT_TRUE(r.start(p));
    ASSERT_TRUE(r.run_until_done());
    expect_turns_set_up(r, timing);
    EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
  }
  {
    // A radius of 1.5 steps at 200,000 steps/s: a turn comes sooner than the set-up time allows,
    // the turned step waits for it (and the end point is still exact).
    PathRig r({}, timing);
    const PathSpec p = arc(0.0, 1.5, 2 * kPi, 200'000, 200'000);
    ASSERT_TRUE(r.start(p));
    ASSERT_TRUE(r.run_until_done());
    expect_turns_set_up(r, timing);
    EXPECT_EQ(test::steps_of(r, 0, 1), test::arc_crossings(p, false));
    EXPECT_EQ(test::steps_of(r, 1, 1), test::arc_crossings(p, true));
  }
}

TEST(PathArc, CwCcwPulseFormatTurnsOnTheOtherLine) {
  PathRig r;
  ASSERT_TRUE(r.ports[0]->set_pulse_format(false));
  ASSERT_TRUE(r.ports[1]->set_pulse_format(false));
  r.service();
  const PathSpec p = arc(60.5, 0.0, 2 * kPi, 1'000, 1'000);
  ASSERT_TRUE(r.start(p));
  ASSERT_TRUE(r.run_until_done());
  // CW steps pulse the step line, CCW steps the direction line (the CCW pulse line).
  for (unsigned a = 0; a < 2; ++a) {
    for (const rt::Edge& e : r.edges[a]) {
      if (e.dpos != 0) {
        EXPECT_EQ(e.line, e.dpos > 0 ? OutputLine::kStep : OutputLine::kDir);
      }
    }
  }
  EXPECT_EQ(test::steps_of(r, 0, 1), test::arc_crossings(p, false));
  EXPECT_EQ(test::steps_of(r, 1, 1), test::arc_crossings(p, true));
  EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
}

TEST(PathArc, RandomLinesAndArcsEndExactlyWithinOneStep) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const double rad = 1.0 + 3'000.0 * uni(rng) * uni(rng);
    const double a0 = 2 * kPi * uni(rng);
    const double sweep = (uni(rng) < 0.5 ? -1 : 1) * (0.05 + (2 * kPi - 0.05) * uni(rng));
    if (i % 3 == 0) {
      const auto dx = static_cast<std::int64_t>(std::llround((uni(rng) - 0.5) * 6'000));
      const auto dy = static_cast<std::int64_t>(std::llround((uni(rng) - 0.5) * 6'000));
      PathRig r;
      const PathSpec p = test::line(dx, dy, 1'000, 40'000, 400'000, 400'000);
      ASSERT_TRUE(r.start(p));
      ASSERT_TRUE(r.run_until_done());
      const std::vector<test::PathPoint> pts = test::rebuild(r);
      EXPECT_EQ(test::steps_of(r, 0, 1), std::llabs(dx));
      EXPECT_EQ(test::steps_of(r, 1, 1), std::llabs(dy));
      if (!pts.empty()) {
        EXPECT_EQ(pts.back().x, dx);
        EXPECT_EQ(pts.back().y, dy);
      }
      EXPECT_LT(test::max_path_error(pts, p), 1.0);
    } else {
      expect_arc(
          arc(-rad * std::cos(a0), -rad * std::sin(a0), sweep, 1'000, 40'000, 400'000, 400'000));
    }
  }
}

TEST(PathArc, ShortStronglySpiralledArcsEndExactlyWithinOneStep) {
  // End points a few steps from the start, centres up to 60 steps away whose distances to S and
  // E round alike (the module's integer world): |r1 - r0| up to a step over a short sweep, both
  // the short and the long way round.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int n = 0; n < 200;) {
    const double cx = 60 * uni(rng), cy = 60 * uni(rng);
    const std::int64_t ex = std::llround(4 * uni(rng)), ey = std::llround(4 * uni(rng));
    const double r0 = std::hypot(cx, cy);
    const double r1 = std::hypot(static_cast<double>(ex) - cx, static_cast<double>(ey) - cy);
    if (std::llround(r0) != std::llround(r1) || (ex == 0 && ey == 0)) continue;
    double sweep =
        std::remainder(std::atan2(static_cast<double>(ey) - cy, static_cast<double>(ex) - cx) -
                           std::atan2(-cy, -cx),
                       2 * kPi);
    if (n % 2 == 1) sweep += sweep > 0 ? -2 * kPi : 2 * kPi;
    PathSpec p = arc(cx, cy, sweep, 1'000, 50'000, 500'000, 500'000);
    p.end_x = ex;
    p.end_y = ey;
    p.sweep = sweep;
    expect_arc(p);
    ++n;
  }
}

}  // namespace
}  // namespace stepmod::planner
