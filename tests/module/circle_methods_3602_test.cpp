// The 3602's interpolated-move geometry (3602 manual Ch.3 "Interpolated Move Profiles"
// and its test vectors, A35, A36, A38): the circle methods, the integer-world check, the
// sweep and the PathSpec they hand the planner.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "module_types/m3602/circle_methods.hpp"

namespace stepmod::module::m3602 {
namespace {

constexpr double kPi = std::numbers::pi;

InterpolatedCommand centre(bool ccw, std::int32_t ex, std::int32_t ey, std::int32_t cx,
                           std::int32_t cy, bool absolute = true) {
  InterpolatedCommand c;
  c.method = InterpolationMethod::kCentre;
  c.absolute = absolute;
  c.ccw = ccw;
  c.end_x = ex;
  c.end_y = ey;
  c.point_x = cx;
  c.point_y = cy;
  return c;
}
InterpolatedCommand radius(bool ccw, std::int32_t ex, std::int32_t ey, std::int32_t r) {
  InterpolatedCommand c;
  c.method = InterpolationMethod::kRadius;
  c.ccw = ccw;
  c.end_x = ex;
  c.end_y = ey;
  c.radius = r;
  return c;
}
InterpolatedCommand via(std::int32_t vx, std::int32_t vy, std::int32_t ex, std::int32_t ey,
                        bool absolute = false) {
  InterpolatedCommand c;
  c.method = InterpolationMethod::kViaPoint;
  c.absolute = absolute;
  c.end_x = ex;
  c.end_y = ey;
  c.point_x = vx;
  c.point_y = vy;
  return c;
}

TEST(Circle3602, RoundedLengthRoundsHalfUp) {
  EXPECT_EQ(rounded_length(3, 4), 5);
  EXPECT_EQ(rounded_length(-3, -4), 5);
  EXPECT_EQ(rounded_length(1, 1), 1);  // 1.414
  EXPECT_EQ(rounded_length(3, 3), 4);  // 4.243
  // Around 8.5 (8.5^2 = 72.25): sqrt(72) = 8.485 -> 8, sqrt(73) = 8.544 -> 9.
  EXPECT_EQ(rounded_length(6, 6), 8);
  EXPECT_EQ(rounded_length(8, 3), 9);
  // Beyond 64 bits of square: (2^32, 2^32) -> 2^32 * sqrt(2) = 6,074,000,999.95 -> 6,074,001,000.
  EXPECT_EQ(rounded_length(std::int64_t{1} << 32, std::int64_t{1} << 32), 6'074'001'000);
}

// 3602 manual ch. 3 "Rounding, reject": radii 1,828.65 -> 1,829 and 1,828.21 -> 1,828.
TEST(Circle3602, CE_I7_CentreMethodRadiiDifferAfterRounding) {
  const PathGeometry g = path_geometry(centre(true, 1'562, 950, 0, 0), -1'000, 1'531);
  EXPECT_EQ(g.fault, GeometryFault::kRadiiDiffer);
}

// "Rounding, accept": E = (1,563, 950): radii 1,829 and 1,829.06 -> both 1,829.
TEST(Circle3602, CentreMethodRadiiEqualAfterRoundingRuns) {
  const PathGeometry g = path_geometry(centre(true, 1'563, 950, 0, 0), -1'000, 1'531);
  ASSERT_EQ(g.fault, GeometryFault::kNone);
  EXPECT_EQ(g.spec.shape, planner::PathShape::kArc);
  EXPECT_EQ(g.spec.end_x, 2'563);
  EXPECT_EQ(g.spec.end_y, -581);
  EXPECT_DOUBLE_EQ(g.spec.centre_x, 1'000.0);
  EXPECT_DOUBLE_EQ(g.spec.centre_y, -1'531.0);
  // CCW from theta_S = atan2(1531, -1000) to theta_E = atan2(950, 1563).
  const double expected = std::atan2(950.0, 1563.0) - std::atan2(1531.0, -1000.0) + 2 * kPi;
  EXPECT_NEAR(g.spec.sweep, expected, 1e-12);
  EXPECT_GT(g.spec.sweep, 0.0);
}

// Fig. 3.4 (A38: the absolute coordinates): radii 4,273,218.58 and 4,273,219.36 -> 4,273,219.
TEST(Circle3602, Fig3_4CentreMethodAcceptedCcw) {
  const PathGeometry g =
      path_geometry(centre(true, 3'442'815, 1'883'000, -358'000, -70'000), -2'932'000, 3'341'000);
  ASSERT_EQ(g.fault, GeometryFault::kNone);
  EXPECT_NEAR(g.radius, 4'273'218.58, 0.01);
  EXPECT_EQ(g.spec.end_x, 6'374'815);
  EXPECT_EQ(g.spec.end_y, -1'458'000);
  EXPECT_DOUBLE_EQ(g.spec.centre_x, 2'574'000.0);  // A38: not the figure's 1,500,000
  EXPECT_GT(g.spec.sweep, 0.0);
  // S is up-left of C, E right of it: counter-clockwise the long way round (more than a half).
  EXPECT_GT(g.spec.sweep, kPi);
  EXPECT_LT(g.spec.sweep, 2 * kPi);
}

// Fig. 3.6: S -> V -> E turns clockwise (z < 0), the arc passes through V.
TEST(Circle3602, Fig3_6ViaPointIsClockwise) {
  const std::int64_t sx = -2'728'000, sy = 3'815'000;
  const PathGeometry g =
      path_geometry(via(-1'305'000, 4'006'000, 497'000, 3'697'000, true), sx, sy);
  ASSERT_EQ(g.fault, GeometryFault::kNone);
  EXPECT_LT(g.spec.sweep, 0.0);
  EXPECT_GT(g.spec.sweep, -kPi);  // the short arc over the top
  // C is equidistant from S, V and E.
  const double vx = -1'305'000.0 - sx, vy = 4'006'000.0 - sy;
  const double rs = std::hypot(g.spec.centre_x, g.spec.centre_y);
  const double rv = std::hypot(vx - g.spec.centre_x, vy - g.spec.centre_y);
  const double re = std::hypot(static_cast<double>(g.spec.end_x) - g.spec.centre_x,
                               static_cast<double>(g.spec.end_y) - g.spec.centre_y);
  EXPECT_NEAR(rs, rv, 1e-6);
  EXPECT_NEAR(rs, re, 1e-6);
  // V lies on the swept part: its angle from S, in the sweep's sense, is inside the sweep.
  const double ts = std::atan2(-g.spec.centre_y, -g.spec.centre_x);
  const double tv = std::atan2(vy - g.spec.centre_y, vx - g.spec.centre_x);
  double to_v = std::fmod(ts - tv, 2 * kPi);
  if (to_v < 0) to_v += 2 * kPi;
  EXPECT_LT(to_v, -g.spec.sweep);
}

TEST(Circle3602, CentreMethodEndAtStartIsAFullCircle) {
  const PathGeometry cw = path_geometry(centre(false, 0, 0, 500, 0, false), 0, 0);
  ASSERT_EQ(cw.fault, GeometryFault::kNone);
  EXPECT_DOUBLE_EQ(cw.spec.sweep, -2 * kPi);
  const PathGeometry ccw = path_geometry(centre(true, 0, 0, 0, -700, false), 0, 0);
  ASSERT_EQ(ccw.fault, GeometryFault::kNone);
  EXPECT_DOUBLE_EQ(ccw.spec.sweep, 2 * kPi);
}

TEST(Circle3602, CentreMethodQuarterCircleSenses) {
  // S = (0, 0), C = (1000, 0), E = (1000, 1000): CW a quarter (over the top), CCW three quarters.
  const PathGeometry cw = path_geometry(centre(false, 1'000, 1'000, 1'000, 0, false), 0, 0);
  ASSERT_EQ(cw.fault, GeometryFault::kNone);
  EXPECT_NEAR(cw.spec.sweep, -kPi / 2, 1e-12);
  const PathGeometry ccw = path_geometry(centre(true, 1'000, 1'000, 1'000, 0, false), 0, 0);
  EXPECT_NEAR(ccw.spec.sweep, 3 * kPi / 2, 1e-12);
}

// Radius method: E = (2000, 0), |R| = 2000: the four paths A..D (3602 manual ch. 3).
TEST(Circle3602, RadiusMethodShortAndLongArcsInBothSenses) {
  const double h = std::sqrt(2000.0 * 2000.0 - 1000.0 * 1000.0);
  struct Case {
    bool ccw;
    std::int32_t r;
    double cy;     // the centre's side of the chord
    double sweep;  // signed
  };
  const double short_angle = 2 * std::asin(1000.0 / 2000.0);  // 60 degrees
  const Case cases[] = {
      {false, 2'000, -h, -short_angle},              // B: CW short, centre below the chord
      {false, -2'000, h, -(2 * kPi - short_angle)},  // A: CW long, centre above
      {true, 2'000, h, short_angle},                 // C: CCW short, centre above
      {true, -2'000, -h, 2 * kPi - short_angle},     // D: CCW long, centre below
  };
  for (const Case& k : cases) {
    const PathGeometry g = path_geometry(radius(k.ccw, 2'000, 0, k.r), 0, 0);
    ASSERT_EQ(g.fault, GeometryFault::kNone) << k.ccw << " " << k.r;
    EXPECT_NEAR(g.spec.centre_x, 1'000.0, 1e-9);
    EXPECT_NEAR(g.spec.centre_y, k.cy, 1e-9) << k.ccw << " " << k.r;
    EXPECT_NEAR(g.spec.sweep, k.sweep, 1e-12) << k.ccw << " " << k.r;
    EXPECT_NEAR(g.radius, 2'000.0, 1e-9);
  }
}

TEST(Circle3602, RadiusMethodHalfChordIsASemicircle) {
  const PathGeometry g = path_geometry(radius(true, 0, 3'000, 1'500), 0, 0);
  ASSERT_EQ(g.fault, GeometryFault::kNone);
  EXPECT_NEAR(g.spec.centre_x, 0.0, 1e-9);
  EXPECT_NEAR(g.spec.centre_y, 1'500.0, 1e-9);
  EXPECT_NEAR(std::fabs(g.spec.sweep), kPi, 1e-12);
}

TEST(Circle3602, CE_I7_RadiusSmallerThanHalfTheChord) {
  EXPECT_EQ(path_geometry(radius(false, 3'001, 0, 1'500), 0, 0).fault,
            GeometryFault::kRadiusTooSmall);
  EXPECT_EQ(path_geometry(radius(false, 3'000, 0, -1'499), 0, 0).fault,
            GeometryFault::kRadiusTooSmall);
  EXPECT_EQ(path_geometry(radius(true, 10, 10, 0), 0, 0).fault, GeometryFault::kRadiusTooSmall);
}

TEST(Circle3602, CE_I7_RadiusMethodEndAtStart) {
  EXPECT_EQ(path_geometry(radius(false, 0, 0, 1'000), 0, 0).fault, GeometryFault::kStartIsEnd);
}

TEST(Circle3602, CE_I7_ViaPointsCollinearOrNotDistinct) {
  EXPECT_EQ(path_geometry(via(1'000, 1'000, 2'000, 2'000), 0, 0).fault, GeometryFault::kCollinear);
  EXPECT_EQ(path_geometry(via(1'000, 0, 1'000, 0), 0, 0).fault, GeometryFault::kCollinear);
  EXPECT_EQ(path_geometry(via(0, 0, 1'000, 500), 0, 0).fault, GeometryFault::kCollinear);
  EXPECT_EQ(path_geometry(via(1'000, 500, 0, 0), 0, 0).fault, GeometryFault::kStartIsEnd);
  // Absolute: V equal to the start point S.
  EXPECT_EQ(path_geometry(via(70, 80, 1'070, 580, true), 70, 80).fault, GeometryFault::kCollinear);
}

TEST(Circle3602, ViaPointSenseFromOrientation) {
  // S = (0, 0), V = (1000, 1000), E = (2000, 0): over the top, clockwise; V below: CCW.
  const PathGeometry cw = path_geometry(via(1'000, 1'000, 2'000, 0), 0, 0);
  ASSERT_EQ(cw.fault, GeometryFault::kNone);
  EXPECT_NEAR(cw.spec.sweep, -kPi, 1e-12);
  EXPECT_NEAR(cw.spec.centre_x, 1'000.0, 1e-9);
  EXPECT_NEAR(cw.spec.centre_y, 0.0, 1e-9);
  const PathGeometry ccw = path_geometry(via(1'000, -1'000, 2'000, 0), 0, 0);
  EXPECT_NEAR(ccw.spec.sweep, kPi, 1e-12);
}

// A35: the geometric radius is at most 2,147,483,647.
TEST(Circle3602, CE_I7_RadiusAboveInt32) {
  // Centre 1,073,741,823 away on each axis: |S - C| = 1.518e9 is fine.
  const PathGeometry ok =
      path_geometry(centre(true, 0, 0, 1'073'741'823, 1'073'741'823, false), 0, 0);
  EXPECT_EQ(ok.fault, GeometryFault::kNone);
  // E and C at opposite corners of the box, 3,037,000,496 apart; S as far from C on C's row,
  // which relative moves can reach (a position anywhere in int32): equal radii above 2^31 - 1.
  const std::int32_t m = 1'073'741'823;
  const std::int64_t r = rounded_length(2 * std::int64_t{m}, 2 * std::int64_t{m});
  const PathGeometry big = path_geometry(centre(true, m, m, -m, -m), -m + r, -m);
  EXPECT_EQ(big.fault, GeometryFault::kRadiusTooLarge);
  EXPECT_EQ(path_geometry(radius(true, 1'000, 0, 2'147'483'647), 0, 0).fault, GeometryFault::kNone);
}

// A32: an absolute end point more than 2^31 - 1 steps from the start does not fit the module's
// 32-bit registers.
TEST(Circle3602, IP_03_AbsoluteEndPointOverflowsTheStepCount) {
  InterpolatedCommand c;
  c.absolute = true;
  c.end_x = -1'073'741'823;
  c.end_y = 0;
  EXPECT_EQ(path_geometry(c, 1'073'741'825, 0).fault, GeometryFault::kOverflow);
  EXPECT_EQ(path_geometry(c, 1'073'741'824, 0).fault, GeometryFault::kNone);
}

TEST(Circle3602, LinearPathRelativeAndAbsolute) {
  InterpolatedCommand c;
  c.end_x = 3'000;
  c.end_y = -4'000;
  PathGeometry g = path_geometry(c, 100, 200);
  ASSERT_EQ(g.fault, GeometryFault::kNone);
  EXPECT_EQ(g.spec.shape, planner::PathShape::kLine);
  EXPECT_EQ(g.spec.end_x, 3'000);
  EXPECT_EQ(g.spec.end_y, -4'000);
  c.absolute = true;
  g = path_geometry(c, 100, 200);
  EXPECT_EQ(g.spec.end_x, 2'900);
  EXPECT_EQ(g.spec.end_y, -4'200);
}

}  // namespace
}  // namespace stepmod::module::m3602
