// The interpolated path, lines (planner/path_source.hpp): both axes on one time base, exact end
// point and counts, every step point within one step of the line, the crossings' order.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "path_test_util.hpp"

namespace stepmod::planner {
namespace {

using test::line;
using test::PathRig;

struct LineCase {
  std::int64_t dx, dy;
};

void expect_line(const LineCase& c) {
  SCOPED_TRACE(::testing::Message() << "line " << c.dx << ", " << c.dy);
  PathRig r;
  const PathSpec p = line(c.dx, c.dy);
  ASSERT_TRUE(r.start(p));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(test::steps_of(r, 0, 1), std::llabs(c.dx));
  EXPECT_EQ(test::steps_of(r, 1, 1), std::llabs(c.dy));
  const std::vector<test::PathPoint> pts = test::rebuild(r);
  ASSERT_FALSE(pts.empty());
  EXPECT_EQ(pts.back().x, c.dx);
  EXPECT_EQ(pts.back().y, c.dy);
  EXPECT_LT(test::max_path_error(pts, p), 1.0);
  // A line never turns: every step of an axis goes one way.
  for (unsigned a = 0; a < 2; ++a) {
    for (const rt::Edge& e : r.edges[a]) {
      const int want = a == 0 ? (c.dx > 0 ? 1 : -1) : (c.dy > 0 ? 1 : -1);
      if (e.dpos != 0) {
        ASSERT_EQ(e.dpos, want);
      }
    }
  }
}

TEST(PathLine, AllEightOctantsEndExactlyWithinOneStepOfTheLine) {
  for (const LineCase c : {LineCase{1'000, 370}, LineCase{370, 1'000}, LineCase{-370, 1'000},
                           LineCase{-1'000, 370}, LineCase{-1'000, -370}, LineCase{-370, -1'000},
                           LineCase{370, -1'000}, LineCase{1'000, -370}}) {
    expect_line(c);
  }
}

TEST(PathLine, AxisAlignedAndDiagonalLinesEndExactly) {
  for (const LineCase c :
       {LineCase{500, 0}, LineCase{0, 500}, LineCase{-500, 0}, LineCase{0, -500},
        LineCase{700, 700}, LineCase{-700, 700}, LineCase{-700, -700}, LineCase{700, -700},
        LineCase{1, 0}, LineCase{1, 1}, LineCase{2, -1}, LineCase{1'000, 1}}) {
    expect_line(c);
  }
}

TEST(PathLine, DiagonalAxesStepAtTheSameInstants) {
  PathRig r;
  ASSERT_TRUE(r.start(line(300, -300)));
  ASSERT_TRUE(r.run_until_done());
  std::vector<Nanos> tx, ty;
  for (const rt::Edge& e : r.edges[0])
    if (e.dpos != 0) tx.push_back(e.t);
  for (const rt::Edge& e : r.edges[1])
    if (e.dpos != 0) ty.push_back(e.t);
  ASSERT_EQ(tx.size(), 300u);
  EXPECT_EQ(tx, ty);  // one time base: the same s(t), the same crossings
}

TEST(PathLine, StepsInterleaveInTheOrderOfTheCrossings) {
  // (3, 2): X reaches 1 at a third of the line, Y 1 at half, X 2 at two thirds, both the end.
  PathRig r;
  ASSERT_TRUE(r.start(line(3, 2, 100, 100)));  // constant speed: s = 100 t
  ASSERT_TRUE(r.run_until_done());
  const std::vector<test::PathPoint> pts = test::rebuild(r);
  ASSERT_EQ(pts.size(), 5u);
  EXPECT_EQ(pts[0].axis, 0u);
  EXPECT_EQ(pts[1].axis, 1u);
  EXPECT_EQ(pts[2].axis, 0u);
  EXPECT_EQ(pts[3].t, pts[4].t);  // the end point: both last steps at the profile's end
  // Crossing times on s(t) = 100 t, L = sqrt(13): s = L/3, L/2, 2L/3, L.
  const double l = std::sqrt(13.0);
  const Nanos t0 = pts[0].t - static_cast<Nanos>(std::llround(l / 3 / 100 * 1e9));
  EXPECT_NEAR(static_cast<double>(pts[1].t - t0), l / 2 / 100 * 1e9, 2.0);
  EXPECT_NEAR(static_cast<double>(pts[2].t - t0), 2 * l / 3 / 100 * 1e9, 2.0);
  EXPECT_NEAR(static_cast<double>(pts[4].t - t0), l / 100 * 1e9, 2.0);
}

TEST(PathLine, AnAxisWithoutStepsEndsCleanlyAtOnce) {
  PathRig r;
  ASSERT_TRUE(r.start(line(400, 0)));
  ASSERT_TRUE(r.run_until_done());
  EXPECT_EQ(test::steps_of(r, 1, 1), 0);
  EXPECT_TRUE(r.done(1, 1));
  EXPECT_EQ(test::steps_of(r, 0, 1), 400);
}

TEST(PathLine, LongLineEndsExactly) {
  PathRig r;
  const PathSpec p = line(600'001, -377'777, 1'000, 400'000, 2e6, 2e6);
  ASSERT_TRUE(r.start(p));
  ASSERT_TRUE(r.run_until_done());
  const std::vector<test::PathPoint> pts = test::rebuild(r);
  EXPECT_EQ(test::steps_of(r, 0, 1), 600'001);
  EXPECT_EQ(test::steps_of(r, 1, 1), 377'777);
  EXPECT_EQ(pts.back().x, 600'001);
  EXPECT_EQ(pts.back().y, -377'777);
  EXPECT_LT(test::max_path_error(pts, p, 7), 1.0);
}

}  // namespace
}  // namespace stepmod::planner
