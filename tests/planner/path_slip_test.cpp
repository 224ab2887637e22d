// A path's two axes on their shared slip (rt/slip.hpp): the planner fills both rings to one
// horizon on the path's time base, however the pulse thread's publication of the group's slip
// to each member was caught (issue 18: an axis that read a smaller slip planned further ahead
// and, with the planner then held off, ran ahead of the other).
#include <gtest/gtest.h>

#include <algorithm>

#include "path_test_util.hpp"
#include "rt/slip.hpp"

namespace stepmod::planner {
namespace {

using test::line;
using test::PathRig;

Nanos newest(const PathRig& r, unsigned axis) {
  Nanos t = 0;
  for (const rt::Edge& e : r.edges[axis]) t = std::max(t, e.t);
  return t;
}

TEST(PathSlip, BothAxesFillToOneHorizonWhicheverSlipEachRead) {
  PathRig r;
  // Constant 20,000 steps/s along the line: X steps every ~54 us, Y every ~135 us.
  ASSERT_TRUE(r.start(line(30'000, -12'000, 20'000, 20'000)));
  // The pulse thread slipped the path by 3 ms and has published it to axis 1 but not yet to
  // axis 0 (it stores the members' words one after the other), for every service here.
  constexpr Nanos kSlip = 3 * kNsPerMs;
  r.feedback[0].slip.store(rt::pack_epoch(r.ports[0]->epoch(), 0));
  r.feedback[1].slip.store(rt::pack_epoch(r.ports[1]->epoch(), rt::slip_us(kSlip)));
  r.run_for(30 * kNsPerMs);
  const Nanos last_service = r.now - kNsPerMs;
  const Nanos horizon = last_service - kSlip + r.planner->options().lookahead_ns;
  ASSERT_GT(newest(r, 1), horizon - kNsPerMs);  // the path is under way and planned ahead
  // Neither axis planned beyond the group's horizon (axis 0 alone would have gone 3 ms further:
  // ~55 of its steps the other axis' ring does not yet hold).
  EXPECT_LE(newest(r, 0), horizon);
  EXPECT_LE(newest(r, 1), horizon);
}

}  // namespace
}  // namespace stepmod::planner
