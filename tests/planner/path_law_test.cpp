// The path's geometry for one coordinate (planner/path_law.hpp): length, position, the
// coordinate's reversals and segments, and the point where it reaches an integer.
#include "planner/path_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "path_test_util.hpp"

namespace stepmod::planner {
namespace {

using test::kPi;

TEST(PathLaw, LineLengthPositionAndOneSegment) {
  const PathSpec p = test::line(300, -400);
  PathLaw x, y;
  x.init(p, PathCoordinate::kX);
  y.init(p, PathCoordinate::kY);
  EXPECT_DOUBLE_EQ(x.length(), 500.0);
  EXPECT_DOUBLE_EQ(y.length(), 500.0);
  EXPECT_DOUBLE_EQ(x.position(0.5), 150.0);
  EXPECT_DOUBLE_EQ(y.position(0.25), -100.0);
  ASSERT_EQ(x.segments(), 1u);
  EXPECT_EQ(x.extremes(), 0u);
  EXPECT_EQ(x.direction(0), 1);
  EXPECT_EQ(y.direction(0), -1);
  EXPECT_EQ(y.target(0), -400);
  EXPECT_NEAR(x.solve(0, 120.0, 0.0), 0.4, 1e-15);
  EXPECT_NEAR(y.solve(0, -100.0, 0.0), 0.25, 1e-15);
}

TEST(PathLaw, FullCircleLengthAndTheSOfEachReversal) {
  // Centre (r, 0): S is the circle's leftmost point; CCW, X peaks at half the circle, Y bottoms
  // out at a quarter and peaks at three quarters.
  const double r = 1'000.25;
  const PathSpec p = test::arc(r, 0.0, 2 * kPi);
  PathLaw x, y;
  x.init(p, PathCoordinate::kX);
  y.init(p, PathCoordinate::kY);
  const double len = 2 * kPi * r;
  EXPECT_NEAR(x.length(), len, 1e-9);
  ASSERT_EQ(x.extremes(), 1u);
  EXPECT_NEAR(x.extreme_s(0), len / 2, 1e-6);
  ASSERT_EQ(y.extremes(), 2u);
  EXPECT_NEAR(y.extreme_s(0), len / 4, 1e-6);
  EXPECT_NEAR(y.extreme_s(1), 3 * len / 4, 1e-6);
  // Targets: X up to floor(2r) then back to 0; Y down to ceil(-r), up to floor(r), back to 0.
  EXPECT_EQ(x.target(0), 2'000);
  EXPECT_EQ(x.target(1), 0);
  EXPECT_EQ(y.target(0), -1'000);
  EXPECT_EQ(y.target(1), 1'000);
  EXPECT_EQ(y.target(2), 0);
  EXPECT_EQ(y.direction(0), -1);
  EXPECT_EQ(y.direction(1), 1);
  EXPECT_EQ(y.direction(2), -1);
}

TEST(PathLaw, ArcLengthIsTheMeanRadiusTimesTheSweep) {
  // The end point rounded to integers: |E - C| differs from |S - C| by a fraction of a step.
  const PathSpec p = test::arc(-37.3, 81.9, -2.0);
  PathLaw x;
  x.init(p, PathCoordinate::kX);
  const double r0 = std::hypot(p.centre_x, p.centre_y);
  const double r1 = std::hypot(p.end_x - p.centre_x, p.end_y - p.centre_y);
  EXPECT_NE(r0, r1);
  EXPECT_NEAR(x.length(), (r0 + r1) / 2 * std::fabs(p.sweep), 1e-9);
  // Through both ends exactly (the spiral's radius runs from r0 to r1).
  EXPECT_NEAR(x.position(0.0), 0.0, 1e-12);
  EXPECT_NEAR(x.position(1.0), static_cast<double>(p.end_x), 1e-9);
}

TEST(PathLaw, SolveFindsThePointWhereTheCoordinateReachesAnInteger) {
  const PathSpec p = test::arc(0.0, 500.5, -1.7 * kPi);
  for (const PathCoordinate c : {PathCoordinate::kX, PathCoordinate::kY}) {
    PathLaw law;
    law.init(p, c);
    double u = 0.0;
    std::int64_t n = 0;
    for (std::size_t i = 0; i < law.segments(); ++i) {
      while (n != law.target(i)) {
        n += law.target(i) > n ? 1 : -1;
        const double un = law.solve(i, static_cast<double>(n), u);
        ASSERT_GE(un, u);
        ASSERT_LE(un, law.segment_end(i));
        // The last step of the path is taken at its end point; every other one where q = n (to
        // 1e-4 step: on a spiral, one Newton step after the acos leaves ~1e-5 next to a reversal).
        if (!(i + 1 == law.segments() && n == law.target(i))) {
          ASSERT_NEAR(law.position(un), static_cast<double>(n), 1e-4) << "n " << n;
        }
        u = un;
      }
    }
    EXPECT_EQ(n, c == PathCoordinate::kX ? p.end_x : p.end_y);
  }
}

TEST(PathLaw, ReachedCountsTheLastIntegerPassedInTheSegmentsDirection) {
  const PathSpec p = test::line(-10, 4);
  PathLaw x;
  x.init(p, PathCoordinate::kX);
  EXPECT_EQ(x.reached(0, 0.0), 0);
  EXPECT_EQ(x.reached(0, 0.35), -3);  // q = -3.5: -3 passed, -4 not yet
  EXPECT_EQ(x.reached(0, 0.4), -4);   // exactly on -4
  EXPECT_EQ(x.reached(0, 1.0), -10);
}

}  // namespace
}  // namespace stepmod::planner
