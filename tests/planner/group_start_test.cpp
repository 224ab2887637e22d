// Group start (several axes' motions on one time base) and the blend slot (a blend's segment
// table handed to the planner beside its command), through MotionPort as the module uses them.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "planner/motion_port.hpp"
#include "planner/planner.hpp"
#include "planner_test_util.hpp"
#include "rt/slip.hpp"

namespace stepmod::planner {
namespace {

using rt::Edge;
using test::move;

// Two axes, each with its ring, feedback and MotionPort; the pulse thread's side only collects.
struct TwoAxes {
  explicit TwoAxes(PlannerOptions opt = {}) {
    for (unsigned i = 0; i < 2; ++i) {
      rings[i] = std::make_unique<SpscRing<Edge>>(1u << 16);
      axes[i] = PlannerAxis{rings[i].get(), &control[i], {}};
    }
    planner = std::make_unique<Planner>(std::span<const PlannerAxis>(axes), opt);
    for (unsigned i = 0; i < 2; ++i) {
      ports[i] = std::make_unique<MotionPort>(i, *planner, feedback[i], control[i], history[i]);
    }
  }
  void service() {
    planner->service(now);
    for (unsigned i = 0; i < 2; ++i) {
      Edge e;
      while (rings[i]->try_pop(e)) edges[i].push_back(e);
    }
  }
  void run_for(Nanos d) {
    for (const Nanos end = now + d; now < end; now += kNsPerMs) service();
  }
  std::vector<Edge> steps(unsigned axis) const {
    std::vector<Edge> out;
    for (const Edge& e : edges[axis]) {
      if (e.dpos != 0) out.push_back(e);
    }
    return out;
  }

  std::array<std::unique_ptr<SpscRing<Edge>>, 2> rings;
  std::array<rt::AxisControl, 2> control;
  std::array<rt::AxisFeedback, 2> feedback;
  std::array<rt::StepHistory, 2> history;
  std::array<PlannerAxis, 2> axes;
  std::unique_ptr<Planner> planner;
  std::array<std::unique_ptr<MotionPort>, 2> ports;
  std::array<std::vector<Edge>, 2> edges;
  Nanos now = test::kT0;
};

TEST(GroupStart, TwoAxesFirstStepsAtTheSameInstant) {
  TwoAxes r;
  // Axis 0 is busy for a while, so on its own it would start later than axis 1; axis 1 also
  // writes its direction line first. The group waits for both.
  ASSERT_NE(r.ports[0]->start_move(move(20, 1'000, 1'000, 1e4, 1e4)), 0u);
  r.service();
  GroupIds ids;
  const GroupTag g = ids.next(2);
  const MoveSpec same = move(500, 2'000, 8'000, 40'000, 40'000);
  ASSERT_NE(r.ports[0]->start_move(same, g), 0u);
  r.service();  // only the first member has arrived: nothing of it may be emitted yet
  for (const Edge& e : r.edges[0]) ASSERT_NE(e.epoch, 2u) << "group member emitted alone";
  ASSERT_NE(r.ports[1]->start_move(same, g), 0u);
  r.run_for(2 * kNsPerSec);
  std::vector<Edge> s0;
  std::size_t before = 0;  // steps of axis 0's first motion (it ends at its newest planned step)
  for (const Edge& e : r.steps(0)) {
    if (e.epoch == 2) s0.push_back(e);
    if (e.epoch == 1) ++before;
  }
  const std::vector<Edge> s1 = r.steps(1);
  ASSERT_GT(before, 0u);
  ASSERT_EQ(s0.size(), 500u);
  ASSERT_EQ(s1.size(), 500u);
  EXPECT_EQ(s0.front().t, s1.front().t);
  // One time base all along: the same profile gives the same step times on both axes.
  for (std::size_t k = 0; k < 500; ++k) ASSERT_EQ(s0[k].t, s1[k].t) << "step " << k + 1;
  // Axis 1's direction edge still leads its first step by the set-up time.
  const Edge& dir1 = r.edges[1].front();
  ASSERT_EQ(dir1.line, OutputLine::kDir);
  EXPECT_GE(s1.front().t - dir1.t, AxisTiming{}.dir_setup_ns);
  // The common time 0 is axis 0's (the later one): after its first motion's last edge.
  const Edge last_of_first = r.steps(0)[before - 1];  // a copy: steps() returns a new vector
  EXPECT_GT(s0.front().t, last_of_first.t);
  EXPECT_GT(s1.front().t, test::kT0 + 2 * r.planner->options().start_delay_ns);
}

TEST(GroupStart, DifferentProfilesShareTimeZero) {
  TwoAxes r;
  GroupIds ids;
  const GroupTag g = ids.next(2);
  const MoveSpec a = move(300, 1'000, 1'000, 1e4, 1e4);  // constant 1,000 steps/s
  const MoveSpec b = move(300, 4'000, 4'000, 1e4, 1e4);  // constant 4,000 steps/s
  ASSERT_NE(r.ports[0]->start_move(a, g), 0u);
  ASSERT_NE(r.ports[1]->start_move(b, g), 0u);
  r.run_for(kNsPerSec);
  const std::vector<Edge> s0 = r.steps(0);
  const std::vector<Edge> s1 = r.steps(1);
  ASSERT_EQ(s0.size(), 300u);
  ASSERT_EQ(s1.size(), 300u);
  // Step k at k / v after the common time 0.
  const Nanos origin0 = s0.front().t - 1'000'000;
  const Nanos origin1 = s1.front().t - 250'000;
  EXPECT_EQ(origin0, origin1);
  EXPECT_EQ(s0[3].t - origin0, 4'000'000);
  EXPECT_EQ(s1[15].t - origin1, 4'000'000);
}

TEST(GroupStart, AMemberThatNeverComesHoldsTheOthersOnlyBriefly) {
  const PlannerOptions opt;
  TwoAxes r(opt);
  GroupIds ids;
  const GroupTag g = ids.next(2);
  ASSERT_NE(r.ports[0]->start_move(move(10, 1'000, 1'000, 1e4, 1e4), g), 0u);
  const Nanos sent = r.now;
  r.run_for(100 * kNsPerMs);
  const std::vector<Edge> s0 = r.steps(0);
  ASSERT_EQ(s0.size(), 10u);
  // Held for at most one start delay (plus the 1 ms service tick of this test) beyond a lone
  // start.
  EXPECT_LE(s0.front().t, sent + 2 * opt.start_delay_ns + kNsPerMs + 1'000'000);
}

// Issue 18: on a loaded machine the control thread may be preempted between a group's start
// commands for longer than the start delay; the late member must not start on a time 0 of its
// own (a 3602 path drawn with one axis a delay behind the other), but on its group's.
TEST(GroupStart, AMemberLateForItsGroupStartsOnTheGroupsTimeZero) {
  TwoAxes r;
  GroupIds ids;
  const GroupTag g = ids.next(2);
  const MoveSpec same = move(300, 1'000, 1'000, 1e4, 1e4);
  ASSERT_NE(r.ports[0]->start_move(same, g), 0u);
  r.run_for(5 * kNsPerMs);  // the start delay runs out: axis 0 starts alone
  ASSERT_FALSE(r.steps(0).empty());
  ASSERT_NE(r.ports[1]->start_move(same, g), 0u);
  r.run_for(kNsPerSec);
  const std::vector<Edge> s0 = r.steps(0);
  const std::vector<Edge> s1 = r.steps(1);
  ASSERT_EQ(s0.size(), 300u);
  ASSERT_EQ(s1.size(), 300u);
  // The same plan on both axes: its first steps lie in the past when axis 1 joins (the pulse
  // thread writes them late and slips the whole group by as much: rt/slip.hpp).
  for (std::size_t k = 0; k < 300; ++k) ASSERT_EQ(s0[k].t, s1[k].t) << "step " << k + 1;
  // Only the members that missed the launch join it: a later group of the same size is its own.
  const GroupTag h = ids.next(2);
  ASSERT_NE(r.ports[0]->start_move(same, h), 0u);
  ASSERT_NE(r.ports[1]->start_move(same, h), 0u);
  r.run_for(kNsPerSec);
  ASSERT_EQ(r.steps(0).size(), 600u);
  ASSERT_EQ(r.steps(1).size(), 600u);
  EXPECT_EQ(r.steps(0)[300].t, r.steps(1)[300].t);
  EXPECT_GT(r.steps(0)[300].t, s0.back().t);
}

TEST(GroupStart, AnAbortedMemberDoesNotStopTheOthers) {
  TwoAxes r;
  GroupIds ids;
  const GroupTag g = ids.next(2);
  ASSERT_NE(r.ports[0]->start_move(move(10, 1'000, 1'000, 1e4, 1e4), g), 0u);
  r.ports[0]->immediate_stop();
  ASSERT_NE(r.ports[1]->start_move(move(10, 1'000, 1'000, 1e4, 1e4), g), 0u);
  r.run_for(100 * kNsPerMs);
  EXPECT_EQ(r.steps(0).size(), 0u);
  EXPECT_EQ(r.steps(1).size(), 10u);
}

TEST(BlendSlot, OneBlendInFlightPerAxisAndItsTableArrivesWhole) {
  TwoAxes r;
  BlendSpec b;
  b.vs = 1'000;
  b.count = 2;
  b.segments[0] = BlendSegment{400, 4'000, Ramp{40'000, AccelShape::kConstant}};
  b.segments[1] = BlendSegment{600, 2'000, Ramp{40'000, AccelShape::kConstant}};
  b.final_decel = Ramp{40'000, AccelShape::kConstant};
  ASSERT_NE(r.ports[1]->start_blend(b), 0u);
  // The planner has not taken the first table yet: a second one must not overwrite it.
  BlendSpec other = b;
  other.segments[0].length = 1;
  EXPECT_EQ(r.ports[1]->start_blend(other), 0u);
  r.run_for(2 * kNsPerSec);
  EXPECT_EQ(r.steps(1).size(), 1'000u);
  // Taken: the slot is free again.
  EXPECT_NE(r.ports[1]->start_blend(other), 0u);
  r.run_for(2 * kNsPerSec);
  EXPECT_EQ(r.steps(1).size(), 1'000u + 601u);
}

// A rack: each module's planner numbers its groups from 1, and the pulse thread keys its slip
// cells and late-edge faults by group. The module's domain in the key's top byte keeps two
// modules' groups apart; a motion alone keeps key 0.
TEST(GroupStart, RackDomainKeepsModulesGroupKeysApart) {
  std::array<std::uint32_t, 2> keys{};
  for (const std::uint8_t domain : {0, 5}) {
    PlannerOptions opt;
    opt.group_domain = domain;
    TwoAxes r(opt);
    const GroupTag g = GroupIds{}.next(2);  // id 1 in every module
    const MoveSpec same = move(100, 2'000, 8'000, 40'000, 40'000);
    ASSERT_NE(r.ports[0]->start_move(same, g), 0u);
    ASSERT_NE(r.ports[1]->start_move(same, g), 0u);
    r.run_for(10 * kNsPerMs);
    const std::uint32_t k0 = rt::packed_value(r.control[0].motion_group.load());
    EXPECT_EQ(k0, rt::packed_value(r.control[1].motion_group.load()));  // one group
    keys[domain == 0 ? 0 : 1] = k0;
  }
  EXPECT_EQ(keys[0], 1u);  // a lone module's keys are its group ids
  EXPECT_EQ(keys[1], (5u << 24) | 1u);
  TwoAxes alone;
  ASSERT_NE(alone.ports[0]->start_move(move(100, 2'000, 8'000, 40'000, 40'000)), 0u);
  alone.run_for(10 * kNsPerMs);
  EXPECT_EQ(rt::packed_value(alone.control[0].motion_group.load()), 0u);
}

TEST(Command, IsSmallAndTriviallyCopyable) {
  static_assert(std::is_trivially_copyable_v<Command>);
  EXPECT_LE(sizeof(Command), 128u);
}

}  // namespace
}  // namespace stepmod::planner
