// The step output's doorbell rings on a submit and again once the planner has planned it
// (planner/output_doorbell.hpp). Without the second ring, a planner that serviced the 3602's GPO
// command after the output's awake time left the edge in the ring until the output's next quiet
// wake-up: the VM's "both-off: GPO lines 25/15 read 0/1" (issue 33).
#include "planner/output_doorbell.hpp"

#include <gtest/gtest.h>

#include "core/spsc_ring.hpp"
#include "planner/motion_request.hpp"
#include "tests/planner/planner_test_util.hpp"

namespace stepmod::planner {
namespace {

Command gpo(bool on) {
  Command c;
  c.axis = 0;
  c.epoch = 1;
  c.what = GpoSpec{on};
  return c;
}

TEST(OutputDoorbell, RingsOnASubmitAndAgainOnceThePlannerHasPlannedIt) {
  SpscRing<rt::Edge> ring(1u << 10);
  rt::AxisControl control;
  PlannerAxis axis{&ring, &control, {}};
  Planner planner(std::span<const PlannerAxis>(&axis, 1));
  OutputDoorbell bell(planner);
  EXPECT_FALSE(bell.due());

  ASSERT_TRUE(planner.submit(gpo(true)));
  EXPECT_TRUE(bell.due());    // the scan that submitted it: the output polls for a while
  EXPECT_FALSE(bell.due());   // nothing new
  EXPECT_TRUE(ring.empty());  // ... and finds nothing until the planner has run

  planner.service(test::kT0);
  rt::Edge e;
  ASSERT_TRUE(ring.try_pop(e));
  EXPECT_EQ(e.line, OutputLine::kGpo);
  EXPECT_TRUE(bell.due());  // the edge is there now: rung again, however late the planner ran
  EXPECT_FALSE(bell.due());

  planner.service(test::kT0 + kNsPerMs);  // a service with nothing new: no ring
  EXPECT_FALSE(bell.due());
}

TEST(OutputDoorbell, ACommandSubmittedDuringAServiceIsNotCountedServedByIt) {
  SpscRing<rt::Edge> ring(1u << 10);
  rt::AxisControl control;
  PlannerAxis axis{&ring, &control, {}};
  Planner planner(std::span<const PlannerAxis>(&axis, 1));
  ASSERT_TRUE(planner.submit(gpo(true)));
  planner.service(test::kT0);
  EXPECT_EQ(planner.served(), planner.wakes());
  ASSERT_TRUE(planner.submit(gpo(false)));
  EXPECT_NE(planner.served(), planner.wakes());  // submitted, not yet planned
  planner.service(test::kT0 + kNsPerMs);
  EXPECT_EQ(planner.served(), planner.wakes());
}

}  // namespace
}  // namespace stepmod::planner
