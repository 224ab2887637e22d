// rt::AxisControl::refill_at: the time the planner names, after each pass, before which no edge
// of its next refill lies (the pulse thread does not poll an empty ring before then). Run as the
// planner thread runs it: each pass at the time the previous one asked for, no command between.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>

#include "path_test_util.hpp"

namespace stepmod::planner {
namespace {

using test::arc;
using test::kPi;
using test::PathRig;

struct RefillCheck {
  std::array<std::int64_t, 2> early_edges{};  // edges pushed before the time named for them
  std::array<std::int64_t, 2> named{};        // passes after which an axis named a time
  std::array<std::int64_t, 2> steps{};
  std::int64_t passes = 0;
};

// Services `r` at the times the planner asks for until both axes' motions have ended.
RefillCheck run_checking_refill_times(PathRig& r) {
  RefillCheck c;
  std::array<Nanos, 2> named{0, 0};
  for (int guard = 0; guard < 1'000'000; ++guard) {
    const Nanos next = r.planner->service(r.now);
    ++c.passes;
    bool ended = true;
    for (unsigned a = 0; a < 2; ++a) {
      rt::Edge e;
      while (r.rings[a]->try_pop(e)) {
        if (named[a] != 0 && e.t < named[a]) ++c.early_edges[a];
        c.steps[a] += e.dpos != 0;
        if ((e.flags & rt::edge_flag::kLast) != 0) r.finished[a].push_back(e.epoch);
      }
      named[a] = r.control[a].refill_at.load(std::memory_order_acquire);
      c.named[a] += named[a] != 0;
      ended = ended && r.done(a, r.ports[a]->epoch());
    }
    if (ended) break;
    r.now = std::max(next, r.now + 1);
  }
  return c;
}

TEST(PlannerRefillTime, PathAxesWaitingForTheirNextCrossingNameItAndNoEdgeComesSooner) {
  PathRig r;
  // The VM's circle (issue 11): radius 200 around (200, 0), 1,000 steps/s along the path.
  ASSERT_TRUE(r.start(arc(200, 0, 2 * kPi, 100, 1'000, 20'000, 20'000)));
  const RefillCheck c = run_checking_refill_times(r);
  EXPECT_EQ(c.steps[0], 800);
  EXPECT_EQ(c.steps[1], 800);
  for (unsigned a = 0; a < 2; ++a) {
    EXPECT_EQ(c.early_edges[a], 0) << "axis " << a;
    // Between two crossings the axis names its next one: in most passes.
    EXPECT_GT(c.named[a], c.passes / 2) << "axis " << a << ", passes " << c.passes;
  }
}

TEST(PlannerRefillTime, MovesNameTheirFirstStagedEdgeAndNoEdgeComesSooner) {
  PathRig r;
  // 200 steps/s: a step period (5 ms) longer than the lookahead, so each ring runs empty
  // between refills.
  MoveSpec m;
  m.steps = 100;
  m.vs = 200;
  m.vp = 200;
  m.accel = Ramp{20'000, AccelShape::kConstant};
  m.decel = m.accel;
  ASSERT_NE(r.ports[0]->start_move(m), 0u);
  m.dir = Direction::kCcw;
  ASSERT_NE(r.ports[1]->start_move(m), 0u);
  const RefillCheck c = run_checking_refill_times(r);
  EXPECT_EQ(c.steps[0], 100);
  EXPECT_EQ(c.steps[1], 100);
  for (unsigned a = 0; a < 2; ++a) {
    EXPECT_EQ(c.early_edges[a], 0) << "axis " << a;
    EXPECT_GT(c.named[a], c.passes / 2) << "axis " << a << ", passes " << c.passes;
  }
}

}  // namespace
}  // namespace stepmod::planner
