// Profile math against worked values of the manuals' profile equations (ch. 2) and the shapes'
// definitions.
#include "planner/profile.hpp"

#include <gtest/gtest.h>

#include "planner_test_util.hpp"

namespace stepmod::planner {
namespace {

using test::move;

struct Worked {
  AccelShape shape;
  double t_ramp, d_ramp, dp_20k, tt_20k, vpk_5k, tt_5k;
};

class ProfileWorkedValues : public ::testing::TestWithParam<Worked> {};

TEST_P(ProfileWorkedValues, MatchWorkedTable) {
  const Worked w = GetParam();
  const Ramp r{10'000, w.shape};
  EXPECT_NEAR(ramp_time(1'000, 10'000, r), w.t_ramp, 1e-12);
  EXPECT_NEAR(ramp_distance(1'000, 10'000, r), w.d_ramp, 1e-9);
  EXPECT_NEAR(ramp_distance(10'000, 1'000, r), w.d_ramp, 1e-9);

  const MoveProfile big = classify_move(move(20'000, 1'000, 10'000, 10'000, 10'000, w.shape));
  EXPECT_EQ(big.kind, ProfileKind::kTrapezoid);
  EXPECT_NEAR(big.ta, w.t_ramp, 1e-12);
  EXPECT_NEAR(big.td, w.t_ramp, 1e-12);
  EXPECT_NEAR(big.da, w.d_ramp, 1e-9);
  EXPECT_NEAR(big.dp, w.dp_20k, 1e-9);
  EXPECT_NEAR(big.tt, w.tt_20k, 1e-9);

  const MoveProfile small = classify_move(move(5'000, 1'000, 10'000, 10'000, 10'000, w.shape));
  EXPECT_EQ(small.kind, ProfileKind::kTriangle);
  EXPECT_NEAR(small.vpk, w.vpk_5k, 0.05);
  EXPECT_NEAR(small.tt, w.tt_5k, 0.0005);
  EXPECT_NEAR(small.da, 2'500, 1e-6);  // a = d, same type: each ramp covers N/2
  EXPECT_NEAR(small.da + small.dd, 5'000, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(
    ProfileEquations, ProfileWorkedValues,
    ::testing::Values(Worked{AccelShape::kConstant, 0.9, 4'950, 10'100, 2.81, 7'141.4, 1.228},
                      Worked{AccelShape::kTriangularS, 1.8, 9'900, 200, 3.62, 5'099.0, 1.640},
                      Worked{AccelShape::kTrapezoidalS, 1.2, 6'600, 6'800, 3.08, 6'204.8, 1.388}),
    [](const auto& info) {
      switch (info.param.shape) {
        case AccelShape::kTriangularS:
          return std::string("TriangularS");
        case AccelShape::kTrapezoidalS:
          return std::string("TrapezoidalS");
        default:
          return std::string("Constant");
      }
    });

TEST(Profile, UnequalRatesWorkedValues) {
  const MoveProfile p = classify_move(move(5'000, 1'000, 10'000, 20'000, 5'000));
  EXPECT_EQ(p.kind, ProfileKind::kTriangle);
  EXPECT_NEAR(p.vpk, 6'403.1, 0.05);
  EXPECT_NEAR(p.da, 1'000, 1e-6);
  EXPECT_NEAR(p.dd, 4'000, 1e-6);
  EXPECT_NEAR(p.ta, (p.vpk - 1'000) / 20'000, 1e-12);
  EXPECT_NEAR(p.td, (p.vpk - 1'000) / 5'000, 1e-12);
}

TEST(Profile, ClassifiesTrapezoidTouchAndTriangle) {
  // Constant type, Da = Dd = 4950: N = 9900 touches Vp exactly.
  EXPECT_EQ(classify_move(move(9'901, 1'000, 10'000, 10'000, 10'000)).kind,
            ProfileKind::kTrapezoid);
  const MoveProfile touch = classify_move(move(9'900, 1'000, 10'000, 10'000, 10'000));
  EXPECT_EQ(touch.kind, ProfileKind::kTouch);
  EXPECT_DOUBLE_EQ(touch.vpk, 10'000);
  EXPECT_NEAR(touch.tt, 1.8, 1e-12);
  EXPECT_EQ(classify_move(move(9'899, 1'000, 10'000, 10'000, 10'000)).kind, ProfileKind::kTriangle);
  // vp <= vs: constant speed, no ramps.
  const MoveProfile c = classify_move(move(100, 2'000, 500, 10'000, 10'000));
  EXPECT_EQ(c.kind, ProfileKind::kConstantSpeed);
  EXPECT_DOUBLE_EQ(c.vpk, 500);
  EXPECT_NEAR(c.tt, 0.2, 1e-12);
  // vp = 0 (one-shot): at vs.
  EXPECT_DOUBLE_EQ(classify_move(move(1, 2'000, 0, 10'000, 10'000)).vpk, 2'000);
}

TEST(Profile, TriangleRampsMeetAtThePeak) {
  for (AccelShape s :
       {AccelShape::kConstant, AccelShape::kTriangularS, AccelShape::kTrapezoidalS}) {
    const MoveSpec m = move(3'333, 700, 50'000, 12'000, 31'000, s);
    const MoveProfile p = classify_move(m);
    ASSERT_EQ(p.kind, ProfileKind::kTriangle);
    EXPECT_NEAR(p.da + p.dd, 3'333, 1e-6);
    EXPECT_NEAR(p.da, ramp_distance(700, p.vpk, m.accel), 1e-9);
  }
}

TEST(Profile, SCurvePeakAccelerationIsTheProgrammedRate) {
  // Triangular S: acceleration 0 -> A at T/2 -> 0; trapezoidal S: A over the middle half.
  PhaseList l;
  l.reset(0, 0, 1'000);
  l.add_ramp(10'000, Ramp{10'000, AccelShape::kTriangularS});
  ASSERT_EQ(l.size(), 2u);
  EXPECT_DOUBLE_EQ(l[0].a0, 0.0);
  EXPECT_NEAR(l[0].accel(l[0].dur), 10'000, 1e-6);
  EXPECT_NEAR(l.velocity_at(0.9), 5'500, 1e-6);                                // v(T/2) = V1 + dV/2
  EXPECT_NEAR(l.velocity_at(0.45), 1'000 + 10'000 * 0.45 * 0.45 / 1.8, 1e-6);  // V1 + A t^2/T
  EXPECT_NEAR(l.end_time(), 1.8, 1e-12);
  EXPECT_NEAR(l.end_position(), 9'900, 1e-6);

  l.reset(0, 0, 1'000);
  l.add_ramp(10'000, Ramp{10'000, AccelShape::kTrapezoidalS});
  ASSERT_EQ(l.size(), 3u);
  EXPECT_NEAR(l[0].dur, 0.3, 1e-12);
  EXPECT_NEAR(l[1].dur, 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(l[1].a0, 10'000);
  EXPECT_DOUBLE_EQ(l[1].j, 0.0);
  EXPECT_NEAR(l.end_time(), 1.2, 1e-12);
  EXPECT_NEAR(l.end_position(), 6'600, 1e-6);

  // Deceleration mirrors it.
  l.reset(0, 0, 10'000);
  l.add_ramp(1'000, Ramp{10'000, AccelShape::kTrapezoidalS});
  EXPECT_NEAR(l[1].a0, -10'000, 1e-9);
  EXPECT_NEAR(l.end_position(), 6'600, 1e-6);
  EXPECT_NEAR(l.velocity_at(l.end_time()), 1'000, 1e-6);
}

TEST(Profile, BuiltMoveEndsAtNAndTt) {
  for (AccelShape s :
       {AccelShape::kConstant, AccelShape::kTriangularS, AccelShape::kTrapezoidalS}) {
    for (std::int64_t n : {5'000, 20'000}) {
      PhaseList l;
      const MoveProfile p = build_move(move(n, 1'000, 10'000, 10'000, 10'000, s), l);
      EXPECT_NEAR(l.end_position(), static_cast<double>(n), 1e-6);
      EXPECT_NEAR(l.end_time(), p.tt, 1e-12);
      EXPECT_NEAR(l.velocity_at(l.end_time()), 1'000, 1e-6);
    }
  }
}

TEST(Profile, BlendWorkedExample) {
  // A blend (manuals 3601/3202 ch. 4-5, 3602 ch. 9): (10000 steps, 5000/s, 10000/s^2), (10000,
  // 8000, 10000), final decel 10000.
  BlendSpec b;
  b.vs = 1'000;
  b.count = 2;
  b.segments[0] = BlendSegment{10'000, 5'000, Ramp{10'000, AccelShape::kConstant}};
  b.segments[1] = BlendSegment{10'000, 8'000, Ramp{10'000, AccelShape::kConstant}};
  b.final_decel = Ramp{10'000, AccelShape::kConstant};
  EXPECT_EQ(blend_length(b), 20'000);
  PhaseList l;
  build_blend(b, l);
  EXPECT_NEAR(l.end_position(), 20'000, 1e-6);
  EXPECT_NEAR(ramp_distance(1'000, 5'000, b.segments[0].ramp), 1'200, 1e-9);
  EXPECT_NEAR(ramp_distance(5'000, 8'000, b.segments[1].ramp), 1'950, 1e-9);
  EXPECT_NEAR(ramp_distance(8'000, 1'000, b.final_decel), 3'150, 1e-9);
  // Speed at the end of segment 1 is 5000, at the start of the final decel 8000.
  double t_seg1 = 0, t_decel = 0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    if (l[i].s1 <= 10'000 + 1e-6) t_seg1 = l[i].t0 + l[i].dur;
    if (l[i].s0 <= 20'000 - 3'150 + 1e-6) t_decel = l[i].t0;
  }
  EXPECT_NEAR(l.velocity_at(t_seg1), 5'000, 1e-6);
  EXPECT_NEAR(l.velocity_at(t_decel), 8'000, 1e-6);
  EXPECT_NEAR(l.position_at(t_decel), 20'000 - 3'150, 1e-6);
}

}  // namespace
}  // namespace stepmod::planner
