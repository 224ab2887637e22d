// Follow motions (FollowStart / FollowUpdate commands, the encoder follower's planner side): the
// exact count, the ramp limits while catching up, reversal, the instant mode's speed, stop and
// abort, in virtual time.
#include <gtest/gtest.h>

#include <cmath>

#include "planner/axis_planner.hpp"
#include "planner_test_util.hpp"

namespace stepmod::planner {
namespace {

using rt::Edge;
using test::Harness;
namespace ef = rt::edge_flag;

constexpr Nanos kMs = kNsPerMs;
constexpr Nanos kUs = kNsPerUs;

FollowSpec spec(std::int64_t target, double accel, double decel, double speed = 1'000.0,
                double vs = 500.0) {
  FollowSpec f;
  f.target = target;
  f.vs = vs;
  f.vmax = 1'000'000.0;
  f.speed = speed;
  f.accel = accel;
  f.decel = decel;
  return f;
}

std::uint32_t start_follow(Harness& h, const FollowSpec& f) {
  Command c;
  c.what = FollowStart{f};
  return h.start(c);
}

void update(Harness& h, const FollowSpec& f) {
  h.send(FollowUpdate{f});
}

std::int64_t net(const std::vector<Edge>& steps) {
  std::int64_t n = 0;
  for (const Edge& e : steps) n += e.dpos;
  return n;
}

// Edges in time order, every step pulse ended on its own line before the line's next pulse.
void expect_ordered_pulses(const std::vector<Edge>& all) {
  int high[2] = {0, 0};
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i > 0) {
      ASSERT_LE(all[i - 1].t, all[i].t) << "edge " << i;
    }
    const auto line = static_cast<unsigned>(all[i].line);
    if (all[i].dpos != 0) {
      ASSERT_EQ(high[line], 0) << "pulse " << i << " starts before the previous one ended";
      high[line] = 1;
    } else if (all[i].level == 0 && line < 2) {
      high[line] = 0;
    }
  }
}

TEST(Follow, TargetFedCountByCountIsReachedExactly) {
  Harness h;
  FollowSpec f = spec(0, 0.0, 0.0, 10'000.0);
  const std::uint32_t ep = start_follow(h, f);
  // A master counting at 10 kHz, the target raised every 100 us; the planner serviced each 50 us.
  std::vector<Nanos> asked;
  for (int i = 1; i <= 2'000; ++i) {
    f.target = i;
    update(h, f);
    asked.push_back(h.now);
    h.run_for(100 * kUs, 50 * kUs);
  }
  h.send(StopSpec{});
  ASSERT_TRUE(h.run_until_finished(ep, 100 * kMs, 50 * kUs));
  const auto steps = h.steps(ep);
  EXPECT_EQ(steps.size(), 2'000u);
  EXPECT_EQ(net(steps), 2'000);
  expect_ordered_pulses(h.motion_edges(ep));
  // Instant mode: each step follows its target within the planner's start delay (150 us).
  for (std::size_t i = 0; i < steps.size(); ++i) {
    ASSERT_GE(steps[i].t, asked[i]) << i;
    ASSERT_LE(steps[i].t - asked[i], 200 * kUs) << i;
  }
}

TEST(Follow, RampedCatchUpRespectsAccelAndDecelAndEndsOnTarget) {
  Harness h;
  const double a = 200'000.0, d = 100'000.0, vs = 500.0;
  const std::uint32_t ep = start_follow(h, spec(0, a, d, 1.0, vs));
  h.run_for(kMs);
  update(h, spec(20'000, a, d, 1.0, vs));  // the target jumps: the axis ramps up, then down
  h.run_for(2'000 * kMs, 200 * kUs);
  h.send(StopSpec{});
  ASSERT_TRUE(h.run_until_finished(ep, kNsPerSec));
  const auto steps = h.steps(ep);
  ASSERT_EQ(steps.size(), 20'000u);
  EXPECT_EQ(net(steps), 20'000);  // never past the target: no step back
  // Speed between consecutive steps: never above what a and d allow (1 % for rounding).
  double v_prev = 0.0, v_peak = 0.0;
  for (std::size_t i = 1; i < steps.size(); ++i) {
    const double v = 1e9 / static_cast<double>(steps[i].t - steps[i - 1].t);
    if (v_prev > 0.0) {
      ASSERT_LE(v * v, (v_prev * v_prev + 4.0 * a) * 1.01 + 1.0) << "step " << i;
      ASSERT_GE(v * v, (v_prev * v_prev - 4.0 * d) * 0.99 - 1.0) << "step " << i;
    }
    v_peak = std::max(v_peak, v);
    v_prev = v;
  }
  // Triangle: accel and decel distances share 20,000 steps: vpk^2 = vs^2 + 2 n a d / (a + d).
  const double vpk = std::sqrt(vs * vs + 2.0 * 20'000 * a * d / (a + d));
  EXPECT_NEAR(v_peak, vpk, vpk * 0.03);
  // It lands slowly: the last interval is about 1/vs.
  const double v_last = 1e9 / static_cast<double>(steps.back().t - steps[steps.size() - 2].t);
  EXPECT_LT(v_last, 2.0 * vs);
}

TEST(Follow, TargetBehindTheAxisDeceleratesReversesAndEndsExactly) {
  Harness h;
  const double a = 1'000'000.0, d = 1'000'000.0;
  FollowSpec f = spec(5'000, a, d, 1.0, 1'000.0);
  const std::uint32_t ep = start_follow(h, f);
  h.run_for(30 * kMs, 200 * kUs);  // part-way, moving CW
  f.target = -1'000;
  update(h, f);
  h.run_for(200 * kMs, 200 * kUs);
  h.send(StopSpec{});
  ASSERT_TRUE(h.run_until_finished(ep, kNsPerSec));
  const auto steps = h.steps(ep);
  EXPECT_EQ(net(steps), -1'000);
  // One reversal: CW steps, then CCW steps, with a direction edge settled dir_setup before.
  std::size_t first_ccw = 0;
  while (first_ccw < steps.size() && steps[first_ccw].dpos > 0) ++first_ccw;
  ASSERT_LT(first_ccw, steps.size());
  for (std::size_t i = first_ccw; i < steps.size(); ++i) ASSERT_EQ(steps[i].dpos, -1);
  EXPECT_TRUE((steps[first_ccw].flags & ef::kCcw) != 0);
  const auto all = h.motion_edges(ep);
  Nanos dir_t = -1;
  for (const Edge& e : all) {
    if (e.line == OutputLine::kDir && e.level == kDirLevelCcw && e.t <= steps[first_ccw].t) {
      dir_t = e.t;
    }
  }
  ASSERT_GE(dir_t, steps[first_ccw - 1].t);
  EXPECT_GE(steps[first_ccw].t - dir_t, AxisTiming{}.dir_setup_ns);
  expect_ordered_pulses(all);
}

TEST(Follow, InstantModeSpreadsPendingStepsAtTheMastersSpeed) {
  Harness h;
  FollowSpec f = spec(0, 0.0, 0.0, 20'000.0);
  const std::uint32_t ep = start_follow(h, f);
  h.run_for(kMs);
  f.target = 100;  // 100 steps owed at once, to go out at 20 kHz (50 us apart)
  update(h, f);
  h.run_for(20 * kMs, 100 * kUs);
  const auto steps = h.steps(ep);
  ASSERT_EQ(steps.size(), 100u);
  for (std::size_t i = 1; i < steps.size(); ++i) {
    EXPECT_NEAR(static_cast<double>(steps[i].t - steps[i - 1].t), 50'000.0, 2.0);
  }
  EXPECT_FALSE(h.finished(ep));  // a follow motion waits for more until it is stopped
  h.send(StopSpec{});
  EXPECT_TRUE(h.run_until_finished(ep, 10 * kMs));
}

TEST(Follow, CwCcwFormatUsesThePulseLineOfEachDirection) {
  Harness h;
  h.send(PulseFormatSpec{false});  // CW + CCW pulse outputs
  h.run_for(kMs);
  FollowSpec f = spec(10, 0.0, 0.0, 10'000.0);
  const std::uint32_t ep = start_follow(h, f);
  h.run_for(10 * kMs);
  f.target = 4;
  update(h, f);
  h.run_for(10 * kMs);
  const auto steps = h.steps(ep);
  ASSERT_EQ(steps.size(), 16u);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(steps[i].line, i < 10 ? OutputLine::kStep : OutputLine::kDir) << i;
  }
  EXPECT_EQ(net(steps), 4);
}

TEST(Follow, AbortCutsItAndStopWhileAtRestEndsAtOnce) {
  Harness h;
  const std::uint32_t ep = start_follow(h, spec(1'000'000, 1'000'000.0, 1'000'000.0));
  h.run_for(10 * kMs);
  const std::size_t before = h.steps(ep).size();
  ASSERT_GT(before, 0u);
  h.control.abort_epoch.store(ep);
  h.send(AbortSpec{});
  h.run_for(10 * kMs);
  // Nothing planned after the abort (edges already in the ring are the pulse thread's to drop).
  const std::size_t after = h.steps(ep).size();
  h.run_for(50 * kMs);
  EXPECT_EQ(h.steps(ep).size(), after);

  const std::uint32_t ep2 = start_follow(h, spec(0, 0.0, 0.0));
  h.run_for(5 * kMs);
  EXPECT_FALSE(h.finished(ep2));
  h.send(StopSpec{});
  EXPECT_TRUE(h.run_until_finished(ep2, 5 * kMs));
  EXPECT_TRUE(h.steps(ep2).empty());
}

}  // namespace
}  // namespace stepmod::planner
