// The interpolated path's hold and resume (PathHold, PathResume): both axes stop at one point of
// the path and resume from it to the exact end point; anything else started on either axis, or
// an abort of either, discards the held path.
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
using test::line;
using test::PathRig;

constexpr Ramp kHoldRamp{100'000, AccelShape::kConstant};
constexpr Ramp kResumeRamp{200'000, AccelShape::kConstant};  // accel and decel of a resume

std::int64_t net(const PathRig& r, unsigned axis) {
  std::int64_t n = 0;
  for (const rt::Edge& e : r.edges[axis]) n += e.dpos;
  return n;
}

TEST(PathHold, HoldMidArcStopsBothAxesOnThePathAndResumeEndsExactly) {
  PathRig r;
  const PathSpec p = arc(-800.3, 310.7, 1.5 * kPi, 500, 20'000, 100'000, 100'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(60 * kNsPerMs);  // well into the cruise
  ASSERT_TRUE(r.ports[1]->hold_path(kHoldRamp));
  ASSERT_TRUE(r.run_until_done());
  // Stopped before the end, both at one point within a step of the arc.
  const std::vector<test::PathPoint> held = test::rebuild(r);
  ASSERT_FALSE(held.empty());
  const double d =
      test::IdealPath(p).distance(static_cast<double>(net(r, 0)), static_cast<double>(net(r, 1)));
  EXPECT_LT(d, 1.0);
  EXPECT_TRUE(net(r, 0) != p.end_x || net(r, 1) != p.end_y);
  // The deceleration: the last steps come slower than the cruise's.
  const std::size_t n = held.size();
  ASSERT_GT(n, 20u);
  EXPECT_GT(held[n - 1].t - held[n - 3].t, 2 * (held[n / 2].t - held[n / 2 - 2].t));

  ASSERT_TRUE(
      r.resume(30'000, Ramp{200'000, AccelShape::kConstant}, Ramp{200'000, AccelShape::kConstant}));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_GT(test::steps_of(r, 0, 2) + test::steps_of(r, 1, 2), 0);
  EXPECT_EQ(net(r, 0), p.end_x);
  EXPECT_EQ(net(r, 1), p.end_y);
  // Across the hold: exactly the arc's crossings, every point within a step of the arc.
  EXPECT_EQ(test::steps_of(r, 0, 1) + test::steps_of(r, 0, 2), test::arc_crossings(p, false));
  EXPECT_EQ(test::steps_of(r, 1, 1) + test::steps_of(r, 1, 2), test::arc_crossings(p, true));
  EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
}

TEST(PathHold, HoldDuringALineAndResumeCruisesAtTheNewSpeed) {
  PathRig r;
  const PathSpec p = line(30'000, -12'000, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(300 * kNsPerMs);
  ASSERT_TRUE(r.ports[0]->hold_path(kHoldRamp));
  ASSERT_TRUE(r.run_until_done());
  const std::int64_t hx = net(r, 0);
  const std::int64_t hy = net(r, 1);
  EXPECT_GT(hx, 0);
  EXPECT_LT(hx, 30'000);
  ASSERT_TRUE(
      r.resume(40'000, Ramp{400'000, AccelShape::kConstant}, Ramp{400'000, AccelShape::kConstant}));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(net(r, 0), 30'000);
  EXPECT_EQ(net(r, 1), -12'000);
  EXPECT_EQ(test::steps_of(r, 0, 1) + test::steps_of(r, 0, 2), 30'000);
  EXPECT_EQ(test::steps_of(r, 1, 1) + test::steps_of(r, 1, 2), 12'000);
  EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
  // The resumed motion cruises at its own vp: X's steps in the middle of the resumed part.
  std::vector<Nanos> tx;
  for (const rt::Edge& e : r.edges[0]) {
    if (e.dpos != 0 && e.epoch == 2) tx.push_back(e.t);
  }
  ASSERT_GT(tx.size(), 4'000u);
  const std::size_t a = tx.size() / 2 - 1'000, b = tx.size() / 2 + 1'000;
  const double ds = static_cast<double>(b - a) * std::hypot(30'000.0, 12'000.0) / 30'000.0;
  const double v = ds / (static_cast<double>(tx[b] - tx[a]) * 1e-9);
  EXPECT_NEAR(v, 40'000.0, 400.0);
  (void)hy;
}

TEST(PathHold, AStopOfOneAxisHoldsTheWholePath) {
  PathRig r;
  const PathSpec p = line(20'000, 20'000, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(200 * kNsPerMs);
  ASSERT_TRUE(r.ports[0]->stop(kHoldRamp));  // a plain controlled stop on X only
  ASSERT_TRUE(r.run_until_done());
  EXPECT_LT(net(r, 0), 20'000);
  EXPECT_EQ(net(r, 0), net(r, 1));  // the diagonal: both stopped at the same point
}

TEST(PathHold, AnotherMoveAfterTheHoldDiscardsThePath) {
  PathRig r;
  const PathSpec p = arc(500.5, 0.0, kPi, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(40 * kNsPerMs);
  ASSERT_TRUE(r.ports[0]->hold_path(kHoldRamp));
  ASSERT_TRUE(r.run_until_done());
  const std::int64_t hy = net(r, 1);
  // A plain move on X: the path cannot be resumed on either axis any more.
  ASSERT_NE(r.ports[0]->start_move(test::move(10, 1'000, 1'000, 1e4, 1e4)), 0u);
  ASSERT_TRUE(r.run_until_done());
  ASSERT_TRUE(r.resume(20'000, kResumeRamp, kResumeRamp));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(test::steps_of(r, 0, r.ports[0]->epoch()), 0);
  EXPECT_EQ(test::steps_of(r, 1, r.ports[1]->epoch()), 0);
  EXPECT_EQ(net(r, 1), hy);
}

TEST(PathHold, AnAbortOfOneAxisMidPathDiscardsThePath) {
  PathRig r;
  const PathSpec p = line(40'000, 10'000, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(200 * kNsPerMs);
  r.ports[0]->immediate_stop();
  r.run_for(10 * kNsPerMs);
  const std::int64_t x_at_abort = test::steps_of(r, 0, 1);
  EXPECT_LT(x_at_abort, 40'000);
  // Y still runs (the module aborts both; here only X was): a hold stops it, but the path is
  // gone: a resume makes no step on either axis.
  ASSERT_TRUE(r.ports[1]->hold_path(kHoldRamp));
  r.run_for(500 * kNsPerMs);
  EXPECT_TRUE(r.done(1, 1));
  EXPECT_EQ(test::steps_of(r, 0, 1), x_at_abort);  // X planned nothing after its abort
  ASSERT_TRUE(r.resume(20'000, kResumeRamp, kResumeRamp));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(test::steps_of(r, 0, 2), 0);
  EXPECT_EQ(test::steps_of(r, 1, 2), 0);
}

TEST(PathHold, AResumeWithoutAHeldPathEndsAtOnceWithoutAStep) {
  PathRig r;
  ASSERT_TRUE(r.start(line(100, 50)));
  ASSERT_TRUE(r.run_until_done());  // ran to its end: nothing to resume
  ASSERT_TRUE(r.resume(20'000, kResumeRamp, kResumeRamp));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(test::steps_of(r, 0, 2), 0);
  EXPECT_EQ(test::steps_of(r, 1, 2), 0);
  EXPECT_EQ(net(r, 0), 100);
  EXPECT_EQ(net(r, 1), 50);
}

TEST(PathHold, AResumeBeforeTheHoldHasStoppedBothAxesGivesThePathUp) {
  PathRig r;
  const PathSpec p = line(40'000, 30'000, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(300 * kNsPerMs);
  ASSERT_TRUE(r.ports[0]->hold_path(Ramp{20'000, AccelShape::kConstant}));  // a 1 s ramp
  r.run_for(20 * kNsPerMs);
  ASSERT_FALSE(r.done(0, 1));  // still decelerating
  ASSERT_TRUE(r.resume(20'000, kResumeRamp, kResumeRamp));
  ASSERT_TRUE(r.run_until_done());
  // No jump to the stop point: the resumed motions make no step, the held ones end where they
  // were, and no two steps of an axis share an instant.
  EXPECT_EQ(test::steps_of(r, 0, 2), 0);
  EXPECT_EQ(test::steps_of(r, 1, 2), 0);
  for (unsigned a = 0; a < 2; ++a) {
    Nanos prev = 0;
    for (const rt::Edge& e : r.edges[a]) {
      if (e.dpos == 0) continue;
      EXPECT_GT(e.t, prev);
      prev = e.t;
    }
  }
  EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
}

TEST(PathHold, AHoldBeforeTheFirstStepStopsAtTheStartAndResumeRunsTheWholePath) {
  PathRig r;
  const PathSpec p = arc(-90.5, -20.25, 3.0, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  ASSERT_TRUE(r.ports[0]->hold_path(kHoldRamp));  // the same scan as the start
  ASSERT_TRUE(r.run_until_done());
  const std::int64_t before = test::steps_of(r, 0, 1) + test::steps_of(r, 1, 1);
  EXPECT_LE(before, 2);  // at most the step or two planned before the hold's time
  ASSERT_TRUE(r.resume(20'000, kResumeRamp, kResumeRamp));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(net(r, 0), p.end_x);
  EXPECT_EQ(net(r, 1), p.end_y);
  EXPECT_EQ(test::steps_of(r, 0, 1) + test::steps_of(r, 0, 2), test::arc_crossings(p, false));
  EXPECT_EQ(test::steps_of(r, 1, 1) + test::steps_of(r, 1, 2), test::arc_crossings(p, true));
  EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
}

TEST(PathHold, AnAxisWithoutStepsIsHeldAndResumedWithTheOther) {
  PathRig r;
  const PathSpec p = line(0, -20'000, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(200 * kNsPerMs);
  ASSERT_TRUE(r.ports[0]->hold_path(kHoldRamp));  // sent on X, which has nothing to do
  ASSERT_TRUE(r.run_until_done());
  EXPECT_GT(net(r, 1), -20'000);
  ASSERT_TRUE(r.resume(20'000, kResumeRamp, kResumeRamp));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(net(r, 0), 0);
  EXPECT_EQ(net(r, 1), -20'000);
  EXPECT_GT(test::steps_of(r, 1, 2), 0);
}

TEST(PathHold, AnAxisWhoseNextCrossingIsFarAwayMakesNoStepAfterTheHold) {
  // Y's only step is the end point's: with the path held halfway, Y must not make it until the
  // resume (a step planned long before its time could not be replanned by the hold).
  PathRig r;
  const PathSpec p = line(4'000, 1, 1'000, 20'000, 200'000, 200'000);
  ASSERT_TRUE(r.start(p));
  r.run_for(100 * kNsPerMs);
  ASSERT_TRUE(r.ports[0]->hold_path(kHoldRamp));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_LT(net(r, 0), 4'000);
  EXPECT_EQ(test::steps_of(r, 1, 1), 0);
  ASSERT_TRUE(r.resume(20'000, kResumeRamp, kResumeRamp));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(test::steps_of(r, 1, 2), 1);
  EXPECT_EQ(net(r, 0), 4'000);
  // Every pulse keeps its width, also the ones followed by a long wait.
  for (unsigned a = 0; a < 2; ++a) {
    Nanos rise = -1;
    for (const rt::Edge& e : r.edges[a]) {
      if (e.line != OutputLine::kStep) continue;
      if (e.level == 1) rise = e.t;
      if (e.level == 0 && rise >= 0) {
        EXPECT_LE(e.t - rise, AxisTiming{}.step_pulse_ns) << "axis " << a;
        rise = -1;
      }
    }
  }
}

TEST(PathHold, RandomHoldsAndResumesEndExactlyWithinOneStep) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int i = 0; i < 60; ++i) {
    SCOPED_TRACE(::testing::Message() << "case " << i);
    const double rad = 2 + 800 * uni(rng);
    const double a0 = 2 * kPi * uni(rng);
    const double sweep = (uni(rng) < 0.5 ? -1 : 1) * 2 * kPi * std::max(0.02, uni(rng));
    const PathSpec p =
        i % 4 == 0 ? line(std::llround(3'000 * (uni(rng) - 0.5)),
                          std::llround(3'000 * (uni(rng) - 0.5)), 500, 30'000, 3e5, 3e5)
                   : arc(-rad * std::cos(a0), -rad * std::sin(a0), sweep, 500, 30'000, 3e5, 3e5);
    PathRig r;
    ASSERT_TRUE(r.start(p));
    for (int h = 0; h < 1 + i % 3; ++h) {
      r.run_for(static_cast<Nanos>(uni(rng) * 80) * kNsPerMs);
      ASSERT_TRUE(r.ports[h % 2]->hold_path(Ramp{1e5 + 1e6 * uni(rng), AccelShape::kConstant}));
      ASSERT_TRUE(r.run_until_done());
      ASSERT_TRUE(r.resume(10'000 + 40'000 * uni(rng), Ramp{3e5, AccelShape::kTriangularS},
                           Ramp{3e5, AccelShape::kTrapezoidalS}));
    }
    ASSERT_TRUE(r.run_until_done());
    EXPECT_EQ(net(r, 0), p.end_x);
    EXPECT_EQ(net(r, 1), p.end_y);
    EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
    if (p.shape == PathShape::kArc) {
      std::int64_t sx = 0, sy = 0;
      for (const rt::Edge& e : r.edges[0]) sx += e.dpos != 0;
      for (const rt::Edge& e : r.edges[1]) sy += e.dpos != 0;
      EXPECT_EQ(sx, test::arc_crossings(p, false));
      EXPECT_EQ(sy, test::arc_crossings(p, true));
    }
  }
}

TEST(PathHold, TwoHoldsAndResumesOfAFullCircleEndExactlyOnItsStart) {
  PathRig r;
  const PathSpec p = arc(0.0, 2'000.4, -2 * kPi, 1'000, 30'000, 300'000, 300'000);
  ASSERT_EQ(p.end_x, 0);
  ASSERT_EQ(p.end_y, 0);
  ASSERT_TRUE(r.start(p));
  for (int i = 0; i < 2; ++i) {
    r.run_for(150 * kNsPerMs);
    ASSERT_TRUE(r.ports[i]->hold_path(kHoldRamp));
    ASSERT_TRUE(r.run_until_done());
    ASSERT_TRUE(r.resume(30'000, Ramp{300'000, AccelShape::kConstant},
                         Ramp{300'000, AccelShape::kConstant}));
  }
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(net(r, 0), 0);
  EXPECT_EQ(net(r, 1), 0);
  std::int64_t sx = 0, sy = 0;
  for (std::uint32_t ep = 1; ep <= 3; ++ep) {
    sx += test::steps_of(r, 0, ep);
    sy += test::steps_of(r, 1, ep);
  }
  EXPECT_EQ(sx, test::arc_crossings(p, false));
  EXPECT_EQ(sy, test::arc_crossings(p, true));
  EXPECT_LT(test::max_path_error(test::rebuild(r), p), 1.0);
}

}  // namespace
}  // namespace stepmod::planner
