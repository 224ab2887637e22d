// The cut protocol between the planner (request / poll / withdraw) and the pulse engine (decide,
// drop the replaced edges), driven through PulseEngine in virtual time.
#include "rt/edge_cut.hpp"

#include <gtest/gtest.h>

#include "tests/rt/fake_backend.hpp"

namespace stepmod::rt {
namespace {

using test::push_step;
using test::Rig;

constexpr Nanos kUs = kNsPerUs;
constexpr std::uint8_t kRepl = edge_flag::kReplacement;

// Runs the engine's edges up to time `until` (each on time); returns how many ran.
std::size_t run_until(Rig& r, Nanos until) {
  std::size_t n = 0;
  for (Nanos t = r.engine->next_due(); t != kNever && t <= until; t = r.engine->next_due()) {
    r.engine->execute_one(t);
    ++n;
  }
  return n;
}

// Ten steps of motion 1 at 100, 200, ... 1000 us, 2 us wide.
void ten_steps(Rig& r) {
  for (int i = 1; i <= 10; ++i) push_step(r.ring(0), i * 100 * kUs, 2 * kUs, 1, 1, 0, i == 10);
}

TEST(EdgeCut, AcceptedDropsTheMotionsEdgesAfterTheCutAndKeepsTheReplacements) {
  Rig r(1);
  ten_steps(r);
  run_until(r, 250 * kUs);  // steps 1 and 2 ran
  EdgeCut& cut = r.ctl(0).cut;
  ASSERT_TRUE(cut.request(1, 400 * kUs));  // keep steps 3 and 4 (leading edge of 4 at 400 us)
  EXPECT_EQ(cut.poll(), EdgeCut::Outcome::kPending);
  EXPECT_FALSE(cut.request(1, 500 * kUs)) << "one open request at a time";
  r.engine->next_due();  // the pulse thread decides at its next loop
  EXPECT_EQ(cut.poll(), EdgeCut::Outcome::kAccepted);
  EXPECT_EQ(cut.poll(), EdgeCut::Outcome::kNone) << "reported once";
  // The planner's replacement: the trailing edge of step 4, then one last, slower step.
  r.ring(0).try_push(
      test::make_edge(402 * kUs, 1, OutputLine::kStep, false, 0, edge_flag::kMotion | kRepl));
  push_step(r.ring(0), 700 * kUs, 2 * kUs, 1, 1, kRepl, true);
  run_until(r, 10'000 * kUs);
  // Steps 1-4 of the old plan and the replacement's step; every pulse whole.
  EXPECT_EQ(r.fb(0).steps.load(), 5);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 1u);
  ASSERT_EQ(r.backend.writes().size(), 10u);
  EXPECT_EQ(r.backend.writes()[8].t, 700 * kUs);
}

TEST(EdgeCut, RefusedWhenAnEdgeAfterTheCutHasRun) {
  Rig r(1);
  ten_steps(r);
  run_until(r, 450 * kUs);  // step 4's edges ran, and step 5 is next
  EdgeCut& cut = r.ctl(0).cut;
  ASSERT_TRUE(cut.request(1, 300 * kUs));
  r.engine->next_due();
  EXPECT_EQ(cut.poll(), EdgeCut::Outcome::kRefused);
  run_until(r, 10'000 * kUs);
  EXPECT_EQ(r.fb(0).steps.load(), 10) << "nothing dropped";
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 1u);
}

TEST(EdgeCut, WithdrawnBeforeTheDecisionDropsNothing) {
  Rig r(1);
  ten_steps(r);
  EdgeCut& cut = r.ctl(0).cut;
  ASSERT_TRUE(cut.request(1, 300 * kUs));
  EXPECT_TRUE(cut.withdraw());
  EXPECT_EQ(cut.poll(), EdgeCut::Outcome::kNone);
  run_until(r, 10'000 * kUs);
  EXPECT_EQ(r.fb(0).steps.load(), 10);
  // Decided first: the withdraw fails and poll tells the decision.
  Rig r2(1);
  ten_steps(r2);
  EdgeCut& cut2 = r2.ctl(0).cut;
  ASSERT_TRUE(cut2.request(1, 300 * kUs));
  r2.engine->next_due();
  EXPECT_FALSE(cut2.withdraw());
  EXPECT_EQ(cut2.poll(), EdgeCut::Outcome::kAccepted);
}

TEST(EdgeCut, ReplacementEdgesAndOtherMotionsAreNeverDropped) {
  Rig r(1);
  ten_steps(r);
  EdgeCut& cut = r.ctl(0).cut;
  ASSERT_TRUE(cut.request(1, 200 * kUs));
  r.engine->next_due();
  ASSERT_EQ(cut.poll(), EdgeCut::Outcome::kAccepted);
  // Replacement: trailing edge of step 2, three more steps, the last one ends the motion.
  r.ring(0).try_push(
      test::make_edge(202 * kUs, 1, OutputLine::kStep, false, 0, edge_flag::kMotion | kRepl));
  for (int i = 1; i <= 3; ++i) {
    push_step(r.ring(0), 200 * kUs + i * 150 * kUs, 2 * kUs, 1, 1, kRepl, i == 3);
  }
  // A newer motion after it, with edges late enough to have been "after the cut" by time.
  for (int i = 1; i <= 2; ++i) push_step(r.ring(0), 2'000 * kUs + i * 100 * kUs, 2 * kUs, 2);
  run_until(r, 10'000 * kUs);
  EXPECT_EQ(r.fb(0).steps.load(), 2 + 3 + 2);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 1u);
  EXPECT_EQ(r.backend.writes().size(), 2u * 7u);  // every pulse whole
}

}  // namespace
}  // namespace stepmod::rt
