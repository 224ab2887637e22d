// Step times: exact counts, and every step within 1 us (target < 50 ns) of the ideal time at
// which the analytic position reaches the step (an independent reference, planner_test_util.hpp).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "planner/axis_planner.hpp"
#include "planner/profile.hpp"
#include "planner_test_util.hpp"

namespace stepmod::planner {
namespace {

using test::Harness;
using test::move;

constexpr Nanos kOrigin = test::kT0 + PlannerOptions{}.start_delay_ns;  // CW, no direction edge

// Runs `m` through the planner and returns its step edges (times relative to the motion origin).
std::vector<Nanos> planned_step_times(const MoveSpec& m) {
  Harness h;
  const std::uint32_t ep = h.start_move(m);
  EXPECT_TRUE(h.run_until_finished(ep));
  std::vector<Nanos> out;
  for (const auto& e : h.steps(ep)) out.push_back(e.t - kOrigin);
  return out;
}

struct Case {
  const char* name;
  MoveSpec m;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

class StepTimesIdeal : public ::testing::TestWithParam<Case> {};

TEST_P(StepTimesIdeal, EveryStepWithin1usOfAnalyticIdeal) {
  const MoveSpec m = GetParam().m;
  const test::RefMove ref = test::ref_move(m);
  const std::vector<Nanos> t = planned_step_times(m);
  ASSERT_EQ(t.size(), static_cast<std::size_t>(m.steps));
  double worst = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const long double ideal = ref.time_of(static_cast<long double>(i + 1)) * 1e9L;
    const double err = static_cast<double>(std::fabs(static_cast<long double>(t[i]) - ideal));
    worst = std::max(worst, err);
    ASSERT_LT(err, 1'000.0) << "step " << i + 1;
  }
  EXPECT_LT(worst, 50.0) << "worst error " << worst << " ns";
  RecordProperty("worst_error_ns", std::to_string(worst));
  std::printf("%s: worst step-time error %.2f ns\n", GetParam().name, worst);
  // The last step is exactly at Tt (A29: the last pulse period counts before the end).
  EXPECT_NEAR(static_cast<double>(t.back()), static_cast<double>(ref.total() * 1e9L), 1.0);
  EXPECT_NEAR(static_cast<double>(t.back()), classify_move(m).tt * 1e9, 1.0);
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, StepTimesIdeal,
    ::testing::Values(Case{"ConstantTrapezoid", move(20'000, 1'000, 10'000, 10'000, 10'000)},
                      Case{"ConstantTriangle", move(5'000, 1'000, 10'000, 10'000, 10'000)},
                      Case{"TriangularSTrapezoid",
                           move(20'000, 1'000, 10'000, 10'000, 10'000, AccelShape::kTriangularS)},
                      Case{"TriangularSTriangle",
                           move(5'000, 1'000, 10'000, 10'000, 10'000, AccelShape::kTriangularS)},
                      Case{"TrapezoidalSTrapezoid",
                           move(20'000, 1'000, 10'000, 10'000, 10'000, AccelShape::kTrapezoidalS)},
                      Case{"TrapezoidalSTriangle",
                           move(5'000, 1'000, 10'000, 10'000, 10'000, AccelShape::kTrapezoidalS)},
                      Case{"UnequalRatesTriangle", move(5'000, 1'000, 10'000, 20'000, 5'000)},
                      Case{"UnequalRatesSCurve",
                           move(30'000, 300, 40'000, 200'000, 37'000, AccelShape::kTrapezoidalS)},
                      Case{"FastTriangularS", move(200'000, 1'000, 500'000, 2'000'000, 1'500'000,
                                                   AccelShape::kTriangularS)}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(StepTimes, ExactCountForManyN) {
  for (AccelShape s :
       {AccelShape::kConstant, AccelShape::kTriangularS, AccelShape::kTrapezoidalS}) {
    for (std::int64_t n : {1, 2, 3, 4, 5, 7, 10, 99, 100, 101, 1'000, 4'949, 4'950, 4'951, 9'899,
                           9'900, 9'901, 12'345}) {
      Harness h;
      const std::uint32_t ep = h.start_move(move(n, 1'000, 10'000, 10'000, 10'000, s));
      ASSERT_TRUE(h.run_until_finished(ep));
      h.run_for(10 * kNsPerMs);  // nothing may follow the end
      std::int64_t pos = 0, leading = 0, last = 0;
      for (const auto& e : h.edges) {
        pos += e.dpos;
        if (e.dpos != 0) ++leading;
        if ((e.flags & rt::edge_flag::kLast) != 0) ++last;
      }
      EXPECT_EQ(leading, n) << "N=" << n;
      EXPECT_EQ(pos, n);
      EXPECT_EQ(last, 1);
      EXPECT_TRUE((h.edges.back().flags & rt::edge_flag::kLast) != 0);
    }
  }
}

TEST(StepTimes, ExactCountHugeMove) {
  // Two million steps at up to 1 MHz, drained through a ring much smaller than the move.
  Harness h({}, {}, 1u << 15);
  const std::int64_t n = 2'000'000;
  const std::uint32_t ep = h.start_move(
      move(n, 1'000, 1'000'000, 2'000'000, 2'000'000, AccelShape::kTrapezoidalS, Direction::kCcw));
  std::int64_t pos = 0, leading = 0;
  bool last = false;
  Nanos prev = 0;
  bool ordered = true;
  for (int i = 0; i < 100'000 && !last; ++i) {
    h.planner->service(h.now);
    rt::Edge e;
    while (h.ring.try_pop(e)) {
      if (e.t < prev) ordered = false;
      prev = e.t;
      pos += e.dpos;
      if (e.dpos != 0) ++leading;
      if (e.epoch == ep && (e.flags & rt::edge_flag::kLast) != 0) last = true;
    }
    h.now += kNsPerMs;
  }
  EXPECT_TRUE(last);
  EXPECT_TRUE(ordered);
  EXPECT_EQ(leading, n);
  EXPECT_EQ(pos, -n);
}

TEST(StepTimes, FirstAndLastPeriodAreOneOverVs) {
  for (AccelShape s :
       {AccelShape::kConstant, AccelShape::kTriangularS, AccelShape::kTrapezoidalS}) {
    const std::vector<Nanos> t = planned_step_times(move(20'000, 1'000, 10'000, 10'000, 10'000, s));
    ASSERT_EQ(t.size(), 20'000u);
    // The first pulse comes one period after time 0 (A29), the last one period after the one
    // before; the ramps meet vs there, so both are only a hair shorter than 1/vs.
    EXPECT_NEAR(static_cast<double>(t[0]), 1e6, 0.01 * 1e6);
    EXPECT_LE(t[0], 1'000'000);
    EXPECT_NEAR(static_cast<double>(t.back() - t[t.size() - 2]), 1e6, 0.01 * 1e6);
    EXPECT_LE(t.back() - t[t.size() - 2], 1'000'000 + 1);
  }
}

TEST(StepTimes, CruiseRateIsVp) {
  const std::vector<Nanos> t = planned_step_times(move(20'000, 1'000, 10'000, 10'000, 10'000));
  // Constant type: cruise between steps 4950 and 15050 at exactly 10000/s.
  for (std::size_t k = 5'000; k < 15'000; ++k) {
    ASSERT_NEAR(static_cast<double>(t[k] - t[k - 1]), 100'000, 1.0) << "step " << k + 1;
  }
}

TEST(StepTimes, ConstantSpeedMoveHasEvenPeriods) {
  const std::vector<Nanos> t = planned_step_times(move(500, 2'000, 400, 10'000, 10'000));
  ASSERT_EQ(t.size(), 500u);
  for (std::size_t k = 0; k < t.size(); ++k) {
    ASSERT_NEAR(static_cast<double>(t[k]), (k + 1) * 2.5e6, 1.0);
  }
}

TEST(StepTimes, SolverIsFastEnough) {
  // Not a timing assertion (shared machines): prints the planner's edge rate for the record.
  Harness h({}, {}, 1u << 20);
  const std::int64_t n = 1'000'000;
  const std::uint32_t ep =
      h.start_move(move(n, 1'000, 1'000'000, 2'000'000, 2'000'000, AccelShape::kTriangularS));
  std::uint64_t edges = 0;
  const auto t0 = std::chrono::steady_clock::now();
  bool last = false;
  while (!last) {
    h.planner->service(h.now);
    h.now += 100 * kNsPerMs;
    rt::Edge e;
    while (h.ring.try_pop(e)) {
      if (e.line == OutputLine::kStep) ++edges;  // not a direction edge
      if (e.epoch == ep && (e.flags & rt::edge_flag::kLast) != 0) last = true;
    }
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(edges, 2u * n);
  std::printf("planner: %.1f M edges/s (this build type)\n", static_cast<double>(edges) / s / 1e6);
}

}  // namespace
}  // namespace stepmod::planner
