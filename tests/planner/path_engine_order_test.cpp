// The planner and the pulse engine together, in virtual time, unloaded: a path's edges go out in
// planned order across its axes (rt::PulseEngine::waits_for_group) without ever waiting when
// nothing is late: every edge is written at its planned time and the group never slips. (A
// circle's axis waits with an empty ring for its next crossing near its turns: an engine that
// held the other axis' edges back against anything but that promised crossing would make them
// late here.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>

#include "path_test_util.hpp"
#include "rt/pulse_engine.hpp"
#include "tests/rt/fake_backend.hpp"

namespace stepmod::planner {
namespace {

using test::arc;
using test::kPi;
using test::line;
using test::PathRig;

Nanos g_now = 0;
Nanos virtual_now() noexcept {
  return g_now;
}

struct Outcome {
  std::int64_t late_writes = 0;  // edges written after their due time
  std::int64_t steps[2] = {0, 0};
  Nanos slip = 0;
  bool ended = false;
};

// Runs the planner at the times it asks for and each edge at its due time, whichever comes first.
Outcome run_path(PathRig& r, rt::test::FakeBackend& backend) {
  std::array<rt::AxisLink, 2> links{};
  for (unsigned a = 0; a < 2; ++a) {
    links[a] = rt::AxisLink{r.rings[a].get(), &r.feedback[a], &r.control[a], &r.history[a]};
  }
  rt::PulseEngine engine(backend, links, nullptr);
  engine.set_clock(&virtual_now);
  Outcome o;
  g_now = r.now;
  Nanos plan_at = r.now;
  for (int guard = 0; guard < 10'000'000; ++guard) {
    const Nanos due = engine.next_due();
    if (due != rt::kNever && due <= plan_at) {
      g_now = std::max(g_now, due);
      o.late_writes += g_now > due;
      engine.execute_one(g_now);
      continue;
    }
    if (r.feedback[0].finished_epoch.load() >= r.ports[0]->epoch() &&
        r.feedback[1].finished_epoch.load() >= r.ports[1]->epoch() && r.ports[0]->epoch() != 0) {
      o.ended = true;
      break;
    }
    g_now = std::max(g_now, plan_at);
    plan_at = std::max(r.planner->service(g_now), g_now + 1);
  }
  o.steps[0] = r.feedback[0].steps.load();
  o.steps[1] = r.feedback[1].steps.load();
  o.slip = engine.slip(0);
  return o;
}

TEST(PathEngineOrder, ALineRunsWithoutWaitingWhenNothingIsLate) {
  PathRig r;
  rt::test::FakeBackend backend(2, 1 << 20);
  ASSERT_TRUE(r.start(line(12'000, -7'000, 1'000, 10'000, 20'000, 20'000)));
  const Outcome o = run_path(r, backend);
  EXPECT_TRUE(o.ended);
  EXPECT_EQ(o.steps[0], 12'000);
  EXPECT_EQ(o.steps[1], -7'000);
  EXPECT_EQ(o.late_writes, 0);
  EXPECT_EQ(o.slip, 0);
}

TEST(PathEngineOrder, ACircleRunsWithoutWaitingWhenNothingIsLate) {
  PathRig r;
  rt::test::FakeBackend backend(2, 1 << 20);
  ASSERT_TRUE(r.start(arc(2'000, 0, 2 * kPi, 1'000, 10'000, 20'000, 20'000)));
  const Outcome o = run_path(r, backend);
  EXPECT_TRUE(o.ended);
  EXPECT_EQ(o.late_writes, 0);
  EXPECT_EQ(o.slip, 0);
}

}  // namespace
}  // namespace stepmod::planner
