// The step-output contract (docs/ARCHITECTURE.md, "Adding a step output"), checked for every
// output in the factory's table through rt::StepOutput alone, in virtual time: exact step counts,
// slip never burst (docs/slip.md), groups slip together, the late-edge guard's cut and report,
// immediate stop, the step cap, the cut handshake, pulse width and direction set-up.
#include "rt/step_output.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "rt/slip.hpp"
#include "rt/step_output_factory.hpp"
#include "tests/rt/step_output_rig.hpp"

namespace stepmod::rt {
namespace {

using test::make_edge;
using test::OutputRig;
using test::push_step;
using test::Write;

constexpr std::uint8_t kMotion = edge_flag::kMotion;
constexpr Nanos kWidth = 2'000;

Nanos g_now = 0;
Nanos virtual_now() noexcept {
  return g_now;
}

class StepOutputContract : public ::testing::TestWithParam<std::string_view> {};

// `n` steps of motion `epoch` every `interval` from `t0`, the last one ending the motion.
void steps(SpscRing<Edge>& ring, std::uint32_t epoch, int n, Nanos t0, Nanos interval,
           int dpos = +1) {
  for (int i = 0; i < n; ++i)
    push_step(ring, t0 + i * interval, kWidth, epoch, dpos, 0, i == n - 1);
}

TEST_P(StepOutputContract, ExactStepCountsInBothDirectionsAndEveryMotionEnds) {
  OutputRig r(GetParam(), 1);
  r.ring(0).try_push(make_edge(0, 1, OutputLine::kDir, false, 0, kMotion | edge_flag::kFirst));
  steps(r.ring(0), 1, 25, 10'000, 10'000);
  r.run_all();
  EXPECT_EQ(r.fb(0).steps.load(), 25);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 1u);
  EXPECT_EQ(r.rises(0).size(), 25u);
  r.ring(0).try_push(make_edge(400'000, 2, OutputLine::kDir, true, 0, kMotion | edge_flag::kFirst));
  steps(r.ring(0), 2, 7, 410'000, 10'000, -1);
  r.run_all();
  EXPECT_EQ(r.fb(0).steps.load(), 18);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 2u);
  std::int64_t at = 0;
  ASSERT_TRUE(r.history(0).steps_at(410'000, 18, at));  // the first CCW step's write
  EXPECT_EQ(at, 24);
}

TEST_P(StepOutputContract, ALateEdgeSlipsTheRestOfItsMotionAndNeverStartsABurst) {
  OutputRig r(GetParam(), 1);
  r.output->set_late_limit(200 * kNsPerMs);
  steps(r.ring(0), 1, 20, 100'000, 50'000);
  for (int i = 0; i < 8; ++i) r.run_one();   // four whole pulses on time
  ASSERT_EQ(r.run_one(1'000'000), 300'000);  // the fifth step's rise 1 ms late
  r.run_all();
  const std::vector<Nanos> rises = r.rises(0);
  ASSERT_EQ(rises.size(), 20u);
  for (std::size_t i = 1; i < rises.size(); ++i)
    EXPECT_GE(rises[i] - rises[i - 1], 50'000 - kSlipFreeNs) << i;
  const std::vector<Write>& w = r.backend.writes();
  for (std::size_t i = 1; i < w.size(); i += 2) EXPECT_GE(w[i].t - w[i - 1].t, kWidth) << i;
  EXPECT_EQ(rises.back(), 100'000 + 19 * 50'000 + 1'000'000 - kSlipFreeNs);
  EXPECT_EQ(packed_epoch(r.fb(0).slip.load()), 1u);
  EXPECT_EQ(packed_value(r.fb(0).slip.load()), slip_us(1'000'000 - kSlipFreeNs));
  EXPECT_EQ(r.fb(0).late_faults.load(), 0u);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 1u);
}

TEST_P(StepOutputContract, TheAxesOfAGroupSlipTogether) {
  OutputRig r(GetParam(), 2);
  for (unsigned a = 0; a < 2; ++a) {
    r.ctl(a).motion_group.store(pack_epoch(1, 5));  // before the motion's first edge
    steps(r.ring(a), 1, 10, 100'000, 50'000);
  }
  for (int i = 0; i < 4; ++i) r.run_one();  // one whole step of each axis
  ASSERT_EQ(r.run_one(500'000), 150'000);   // axis 0's second rise 0.5 ms late
  r.run_all();
  const std::vector<Nanos> a = r.rises(0);
  const std::vector<Nanos> b = r.rises(1);
  ASSERT_EQ(a.size(), 10u);
  ASSERT_EQ(b.size(), 10u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LE(std::abs(a[i] - b[i]), kSlipFreeNs) << i;
  EXPECT_EQ(r.fb(0).slip.load(), r.fb(1).slip.load());
}

TEST_P(StepOutputContract, APauseBeyondTheLateLimitCutsTheMotionAndIsReported) {
  OutputRig r(GetParam(), 1);
  r.output->set_late_limit(kNsPerMs);
  steps(r.ring(0), 7, 10, 100'000, 50'000);
  for (int i = 0; i < 6; ++i) r.run_one();
  ASSERT_EQ(r.run_one(4'800'000), 250'000);  // stalled: the fourth rise would be 4.8 ms late
  EXPECT_EQ(r.backend.writes().size(), 6u);  // not written
  EXPECT_EQ(r.output->next_due(), kNever);   // the rest of the motion dropped
  const AxisFeedback& fb = r.fb(0);
  EXPECT_EQ(fb.steps.load(), 3);
  EXPECT_EQ(fb.late_faults.load(), 1u);
  EXPECT_EQ(fb.fault_epoch.load(), 7u);
  EXPECT_EQ(fb.fault_step.load(), 3);
  EXPECT_EQ(fb.fault_late_ns.load(), 4'800'000);
  EXPECT_EQ(fb.worst_fault_late_ns.load(), 4'800'000);
  EXPECT_EQ(fb.finished_epoch.load(), 7u);
  EXPECT_EQ(fb.output_levels.load(), 0u);
}

TEST_P(StepOutputContract, ALagAboveVsBeyondTheAxisLimitIsAFaultAndAShorterOneSlips) {
  for (const Nanos pause : {Nanos{600'000}, Nanos{300'000}}) {  // 12 and 6 steps of 50 us
    OutputRig r(GetParam(), 1);
    r.output->set_late_limit(200 * kNsPerMs);
    r.output->set_lag_limit(0, 8);
    steps(r.ring(0), 3, 20, 100'000, 50'000);  // Vs unknown: every step counts as above it
    for (int i = 0; i < 6; ++i) r.run_one();
    r.run_one(pause);
    r.run_all();
    const bool fault = pause > 8 * 50'000;
    EXPECT_EQ(r.fb(0).late_faults.load(), fault ? 1u : 0u) << pause;
    EXPECT_EQ(r.fb(0).steps.load(), fault ? 3 : 20) << pause;
    if (fault) {
      EXPECT_EQ(r.fb(0).fault_lag.load(), 12);
      EXPECT_EQ(r.fb(0).fault_interval_ns.load(), 50'000);
    }
    EXPECT_EQ(r.fb(0).finished_epoch.load(), 3u);
  }
}

TEST_P(StepOutputContract, AnImmediateStopEndsThePulseUnderWayAndIsAlwaysAcknowledged) {
  OutputRig r(GetParam(), 1);
  r.output->set_clock(&virtual_now);
  steps(r.ring(0), 1, 5, 10'000, 10'000);
  r.run_one();  // the first rise: the step line is high
  r.ctl(0).abort_epoch.store(1);
  g_now = 11'000;
  EXPECT_EQ(r.output->next_due(), kNever);
  const Write& low = r.backend.writes().back();
  EXPECT_EQ(low.line, OutputLine::kStep);
  EXPECT_FALSE(low.level);
  EXPECT_EQ(low.t, 11'000);  // stamped with the output's clock
  EXPECT_EQ(r.fb(0).output_levels.load(), 0u);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 1u);
  EXPECT_EQ(r.fb(0).steps.load(), 1);
  // With nothing queued (the planner had not started it) a stop is acknowledged too, and the
  // stopped motion's edges pushed afterwards never run; the next motion does.
  r.ctl(0).abort_epoch.store(7);
  EXPECT_EQ(r.output->next_due(), kNever);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 7u);
  steps(r.ring(0), 7, 3, 100'000, 10'000);
  steps(r.ring(0), 8, 2, 200'000, 10'000);
  r.run_all();
  EXPECT_EQ(r.fb(0).steps.load(), 3);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 8u);
}

TEST_P(StepOutputContract, AStepCapKeepsARegistrationCountExactWithWholePulses) {
  OutputRig r(GetParam(), 1);
  steps(r.ring(0), 3, 10, 0, 10'000);  // planned past the count already
  r.ctl(0).limit_steps.store(4);
  r.ctl(0).limit_epoch.store(3);
  r.run_all();
  EXPECT_EQ(r.fb(0).steps.load(), 4);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 3u);
  ASSERT_EQ(r.backend.writes().size(), 8u);
  EXPECT_FALSE(r.backend.writes().back().level);
}

TEST_P(StepOutputContract, ACutIsAcceptedOnlyIfNothingAfterItRanAndDropsOnlyTheReplacedEdges) {
  OutputRig r(GetParam(), 1);
  steps(r.ring(0), 1, 10, 100'000, 100'000);
  for (int i = 0; i < 4; ++i) r.run_one();  // steps 1 and 2
  EdgeCut& cut = r.ctl(0).cut;
  ASSERT_TRUE(cut.request(1, 400'000));  // keep steps 3 and 4
  r.output->next_due();                  // decided at the output's next look
  ASSERT_EQ(cut.poll(), EdgeCut::Outcome::kAccepted);
  r.ring(0).try_push(
      make_edge(402'000, 1, OutputLine::kStep, false, 0, kMotion | edge_flag::kReplacement));
  push_step(r.ring(0), 700'000, kWidth, 1, +1, edge_flag::kReplacement, true);
  r.run_all();
  EXPECT_EQ(r.fb(0).steps.load(), 5);
  EXPECT_EQ(r.fb(0).finished_epoch.load(), 1u);
  EXPECT_EQ(r.rises(0).back(), 700'000);
  // Refused once an edge after the cut's time has run: nothing is dropped.
  OutputRig late(GetParam(), 1);
  steps(late.ring(0), 1, 10, 100'000, 100'000);
  for (int i = 0; i < 8; ++i) late.run_one();  // steps 1..4
  EdgeCut& refused = late.ctl(0).cut;
  ASSERT_TRUE(refused.request(1, 300'000));
  late.output->next_due();
  EXPECT_EQ(refused.poll(), EdgeCut::Outcome::kRefused);
  late.run_all();
  EXPECT_EQ(late.fb(0).steps.load(), 10);
}

TEST_P(StepOutputContract, ALateDirectionEdgeKeepsItsWholeSetUpTime) {
  OutputRig r(GetParam(), 1);
  constexpr Nanos kSetup = 5'000;
  r.ring(0).try_push(make_edge(0, 1, OutputLine::kDir, true, 0, kMotion | edge_flag::kFirst));
  steps(r.ring(0), 1, 2, kSetup, 10'000);
  r.run_one(4'000);  // the direction 4 us late
  r.run_all();
  const std::vector<Write>& w = r.backend.writes();
  ASSERT_EQ(w.size(), 5u);
  EXPECT_EQ(w[0].line, OutputLine::kDir);
  EXPECT_GE(w[1].t - w[0].t, kSetup);
  EXPECT_EQ(r.fb(0).steps.load(), 2);
}

INSTANTIATE_TEST_SUITE_P(EveryOutput, StepOutputContract, ::testing::ValuesIn(step_output_names()),
                         [](const auto& info) { return std::string(info.param); });

TEST(StepOutputFactory, MakesThePulseThreadByNameAndRefusesAnUnknownNameClearly) {
  test::FakeBackend backend(1);
  const std::vector<AxisLink> links(1);
  EXPECT_EQ(step_output_names().front(), kPulseThreadOutput);
  try {
    make_step_output("rp1_pio", {backend, links, nullptr});
    FAIL() << "an unknown output was made";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"rp1_pio\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"pulse_thread\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stepmod::rt
