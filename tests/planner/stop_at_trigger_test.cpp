// Controlled stops start at their trigger (issue 12 item 9): the planner and the pulse engine
// together, in virtual time, as the daemon runs them: the planner fills the ring ~4 ms ahead, the
// pulse engine writes each edge at its time. A stop with a trigger time replaces the queued
// edges from the trigger on (rt/edge_cut.hpp); the count stays exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../rt/fake_backend.hpp"
#include "planner/motion_port.hpp"
#include "planner/planner.hpp"
#include "planner/profile.hpp"
#include "planner_test_util.hpp"

namespace stepmod::planner {
namespace {

constexpr Nanos kUs = kNsPerUs;
constexpr Nanos kMs = kNsPerMs;

// One axis: planner -> ring -> pulse engine -> fake backend, driven by a virtual clock.
struct Loop {
  Loop() : rig(1) {
    PlannerAxis a{&rig.ring(0), &rig.ctl(0), {}};
    planner = std::make_unique<Planner>(std::span<const PlannerAxis>(&a, 1));
    port = std::make_unique<MotionPort>(0, *planner, rig.fb(0), rig.ctl(0), rig.history(0));
  }
  // Advances to `end`: the planner runs when it asked to (and every 250 us at least), the pulse
  // engine writes every edge at exactly its due time.
  void run_to(Nanos end) {
    while (now < end) {
      if (now >= next_service) next_service = std::min(planner->service(now), now + 250 * kUs);
      const Nanos due = rig.engine->next_due();
      const Nanos step = std::min({end, next_service, due});
      if (due <= now) {
        const rt::Edge* e = rig.ring(0).peek();  // the edge next_due() chose (one axis)
        if (e->dpos != 0) executed_steps.push_back(*e);
        rig.engine->execute_one(due);
        continue;
      }
      now = std::max(now + 1, step);
    }
  }
  // A command wakes the planner (Planner::submit rings its wake counter in the daemon).
  bool stop(Ramp decel, Nanos trigger) {
    next_service = now;
    return port->stop(decel, trigger);
  }
  bool stop(Ramp decel) {
    next_service = now;
    return port->stop(decel);
  }
  // Leading-edge write times of the steps.
  std::vector<Nanos> steps() const {
    std::vector<Nanos> out;
    bool high = false;
    for (const auto& w : rig.backend.writes()) {
      if (w.line != OutputLine::kStep) continue;
      if (w.level && !high) out.push_back(w.t);
      high = w.level;
    }
    return out;
  }
  std::int64_t count_after(Nanos t) const {
    const std::vector<Nanos> s = steps();
    return std::count_if(s.begin(), s.end(), [t](Nanos x) { return x > t; });
  }

  rt::test::Rig rig;
  std::unique_ptr<Planner> planner;
  std::unique_ptr<MotionPort> port;
  Nanos now = test::kT0;
  Nanos next_service = test::kT0;
  std::vector<rt::Edge> executed_steps;  // leading edges as the engine wrote them
};

RunSpec cruise_run(double vs, double vp, double a, double d, AccelShape shape) {
  RunSpec r;
  r.vs = vs;
  r.vp = vp;
  r.accel = Ramp{a, shape};
  r.decel = Ramp{d, shape};
  return r;
}

// The manuals' ramp distance D = k (V1^2 - V2^2) / (2A), written here from ch. 2 (not profile.cpp).
std::int64_t ramp_steps(double v1, double v2, double a, AccelShape shape) {
  const double k = shape == AccelShape::kTriangularS    ? 2.0
                   : shape == AccelShape::kTrapezoidalS ? 4.0 / 3.0
                                                        : 1.0;
  return std::llround(k * (v1 * v1 - v2 * v2) / (2.0 * a));
}

// The case: 10,000 steps/s, vs 1,000, decel 20 steps/ms/s, stopped 1 s in.
struct Case {
  AccelShape shape;
  Nanos delivered_after;  // when the planner gets the stop, after the trigger
};

class StopAtTrigger : public ::testing::TestWithParam<Case> {};

TEST_P(StopAtTrigger, DecelerationStartsWithin250usAndTheCountIsTheRampFromThere) {
  const Case c = GetParam();
  Loop l;
  const RunSpec run = cruise_run(1'000, 10'000, 20'000, 20'000, c.shape);
  ASSERT_NE(l.port->start_run(run), 0u);
  const Nanos trigger = test::kT0 + kNsPerSec;
  l.run_to(trigger + c.delivered_after);
  ASSERT_TRUE(l.stop(run.decel, trigger));
  l.run_to(trigger + 2 * kNsPerSec);
  ASSERT_FALSE(l.port->busy());

  const std::vector<Nanos> s = l.steps();
  ASSERT_EQ(static_cast<std::int64_t>(s.size()), l.rig.fb(0).steps.load());
  // Where the deceleration begins: the last step planned as cruise.
  Nanos ramp_start = 0;
  for (const rt::Edge& e : l.executed_steps) {
    if (e.phase() == rt::Phase::kDecel) break;
    ramp_start = e.t;
  }
  ASSERT_GT(ramp_start, trigger - kMs);
  EXPECT_LE(ramp_start - trigger, 250 * kUs);
  // Steps after the trigger: the cruise steps up to the ramp's start, then the ramp from 10,000
  // down to vs.
  const std::int64_t cruise_after =
      std::count_if(s.begin(), s.end(), [&](Nanos x) { return x > trigger && x <= ramp_start; });
  EXPECT_EQ(l.count_after(trigger), cruise_after + ramp_steps(10'000, 1'000, 20'000, c.shape));
  std::printf(
      "stop at trigger (shape %d, stop seen %lld us after it): %lld steps after it, ramp "
      "from %lld us after it\n",
      static_cast<int>(c.shape), static_cast<long long>(c.delivered_after / kUs),
      static_cast<long long>(l.count_after(trigger)),
      static_cast<long long>((ramp_start - trigger) / kUs));
  // It ends at vs.
  EXPECT_NEAR(static_cast<double>(s.back() - s[s.size() - 2]), 1e6, 0.02e6);
  // Pulses stay whole: as many falling as rising step edges, each after its rise.
  std::size_t rises = 0, falls = 0;
  for (const auto& w : l.rig.backend.writes()) {
    if (w.line != OutputLine::kStep) continue;
    (w.level ? rises : falls) += 1;
  }
  EXPECT_EQ(rises, falls);
}

INSTANTIATE_TEST_SUITE_P(Shapes, StopAtTrigger,
                         ::testing::Values(Case{AccelShape::kConstant, 0},
                                           Case{AccelShape::kConstant, 60 * kUs},
                                           Case{AccelShape::kTriangularS, 0},
                                           Case{AccelShape::kTrapezoidalS, 30 * kUs}));

TEST(StopAtTrigger, KnownBeforeItHappensTheRampStartsAtTheTriggerItself) {
  // A Hold seen by the planner before its time (trigger >= now + margin): exactly the ramp.
  Loop l;
  const RunSpec run = cruise_run(1'000, 10'000, 20'000, 20'000, AccelShape::kConstant);
  ASSERT_NE(l.port->start_run(run), 0u);
  const Nanos trigger = test::kT0 + kNsPerSec;
  l.run_to(trigger - 2 * kMs);
  ASSERT_TRUE(l.stop(run.decel, trigger));
  l.run_to(trigger + 2 * kNsPerSec);
  EXPECT_EQ(l.count_after(trigger), ramp_steps(10'000, 1'000, 20'000, AccelShape::kConstant));
  EXPECT_EQ(l.count_after(trigger), 2'475);
}

TEST(StopAtTrigger, WithoutATriggerTheStopStillStartsAfterTheQueuedEdges) {
  // The old API keeps its meaning: from the newest planned step, a lookahead after now.
  Loop l;
  const RunSpec run = cruise_run(1'000, 10'000, 20'000, 20'000, AccelShape::kConstant);
  ASSERT_NE(l.port->start_run(run), 0u);
  const Nanos trigger = test::kT0 + kNsPerSec;
  l.run_to(trigger);
  ASSERT_TRUE(l.stop(run.decel));
  l.run_to(trigger + 2 * kNsPerSec);
  const std::int64_t ramp = ramp_steps(10'000, 1'000, 20'000, AccelShape::kConstant);
  const std::int64_t lookahead_steps = PlannerOptions{}.lookahead_ns * 10'000 / kNsPerSec;
  EXPECT_GE(l.count_after(trigger), ramp + lookahead_steps / 2);
  EXPECT_LE(l.count_after(trigger), ramp + lookahead_steps + 2);
  std::printf("stop without a trigger time: %lld steps after the stop\n",
              static_cast<long long>(l.count_after(trigger)));
}

TEST(StopAtTrigger, AMoveThatEndsSoonerAnywayIsNotCut) {
  Loop l;
  MoveSpec m = test::move(2'000, 1'000, 10'000, 20'000, 20'000);
  ASSERT_NE(l.port->start_move(m), 0u);
  l.run_to(test::kT0 + 300 * kMs);  // decelerating by now
  ASSERT_TRUE(l.stop(m.decel, l.now));
  l.run_to(test::kT0 + 2 * kNsPerSec);
  EXPECT_EQ(l.rig.fb(0).steps.load(), 2'000);
}

TEST(StopAtTrigger, ConstantSpeedEndsOnTheStepAtTheTrigger) {
  Loop l;
  const RunSpec run = cruise_run(5'000, 2'000, 10'000, 10'000, AccelShape::kConstant);
  ASSERT_NE(l.port->start_run(run), 0u);  // vp <= vs: 2,000 steps/s, no ramps
  const Nanos trigger = test::kT0 + 500 * kMs + 123 * kUs;
  l.run_to(trigger - kMs);
  ASSERT_TRUE(l.stop(run.decel, trigger));
  l.run_to(trigger + kNsPerSec);
  EXPECT_FALSE(l.port->busy());
  EXPECT_EQ(l.count_after(trigger), 0);
}

TEST(StopAtTrigger, ImmediateStopWhileTheCutIsOpenStillStops) {
  Loop l;
  const RunSpec run = cruise_run(1'000, 10'000, 20'000, 20'000, AccelShape::kConstant);
  ASSERT_NE(l.port->start_run(run), 0u);
  l.run_to(test::kT0 + kNsPerSec);
  ASSERT_TRUE(l.stop(run.decel, l.now));
  l.planner->service(l.now);  // the cut is requested; the pulse engine has not answered yet
  l.port->immediate_stop();
  l.run_to(l.now + 100 * kMs);
  EXPECT_FALSE(l.port->busy());
  const std::int64_t n = l.rig.fb(0).steps.load();
  l.run_to(l.now + 100 * kMs);
  EXPECT_EQ(l.rig.fb(0).steps.load(), n);
}

}  // namespace
}  // namespace stepmod::planner
