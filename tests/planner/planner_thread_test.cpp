// The planner thread sleeps while idle and wakes on submit (label: threading).
#include "planner/planner_thread.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "planner/axis_planner.hpp"
#include "planner/motion_port.hpp"
#include "rt/pulse_thread.hpp"
#include "tests/rt/fake_backend.hpp"

namespace stepmod::planner {
namespace {

// Polls `pred` for up to `limit`: generous, because the machine may be loaded; the idle sleep it
// must beat is kIdleServiceInterval (10 s).
template <typename Pred>
bool eventually(Pred pred, std::chrono::milliseconds limit = std::chrono::milliseconds(3'000)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return pred();
}

TEST(PlannerThread, WakesOnSubmitAndStops) {
  static_assert(kIdleServiceInterval >= 10 * kNsPerSec, "the test relies on a long idle sleep");
  SpscRing<rt::Edge> ring(1u << 16);
  rt::AxisControl control;
  PlannerAxis axis{&ring, &control, {}};
  Planner planner(std::span<const PlannerAxis>(&axis, 1));
  PlannerThread thread(planner);
  thread.start();
  ASSERT_TRUE(thread.running());
  // Let it reach its idle sleep.
  ASSERT_TRUE(eventually([&] { return thread.loops() >= 1; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::uint64_t idle_loops = thread.loops();

  MoveSpec m;
  m.steps = 20;
  m.vs = m.vp = 10'000;
  Command c;
  c.epoch = 1;
  c.what = m;
  ASSERT_TRUE(planner.submit(c));
  // Without the wake-up the thread would sleep for 10 s before seeing the command.
  std::uint64_t leading = 0;
  bool last = false;
  EXPECT_TRUE(eventually([&] {
    rt::Edge e;
    while (ring.try_pop(e)) {
      if (e.dpos != 0) ++leading;
      if ((e.flags & rt::edge_flag::kLast) != 0) last = true;
    }
    return last;
  }));
  EXPECT_EQ(leading, 20u);
  EXPECT_GT(thread.loops(), idle_loops);

  thread.stop();
  EXPECT_FALSE(thread.running());
  thread.stop();  // idempotent
}

// A stop at its trigger with real threads (TSan: the cut's hand-over between the planner thread
// and the pulse thread). Timing is the machine's; the count must be exact whatever it decides.
TEST(PlannerThread, StopAtTriggerWithThePulseThreadKeepsTheCountExact) {
  rt::test::Rig rig(1);
  PlannerAxis axis{&rig.ring(0), &rig.ctl(0), {}};
  Planner planner(std::span<const PlannerAxis>(&axis, 1));
  MotionPort port(0, planner, rig.fb(0), rig.ctl(0), rig.history(0));
  rt::PulseThread::Options o;
  o.priority = 0;  // SCHED_OTHER: a shared CI machine
  o.lock_memory = false;
  rt::PulseThread pulse(*rig.engine, o);
  PlannerThread thread(planner);
  ASSERT_TRUE(pulse.start());
  thread.start();
  RunSpec run;
  run.vs = 500;
  run.vp = 5'000;
  run.accel = run.decel = Ramp{50'000, AccelShape::kConstant};
  ASSERT_NE(port.start_run(run), 0u);
  pulse.ring();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_TRUE(port.stop(run.decel, monotonic_now()));
  pulse.ring();
  EXPECT_TRUE(eventually([&] { return !port.busy(); }));
  thread.stop();
  pulse.stop();
  pulse.join();
  std::size_t rises = 0, falls = 0;
  for (const auto& w : rig.backend.writes()) {
    if (w.line != OutputLine::kStep) continue;
    (w.level ? rises : falls) += 1;
  }
  EXPECT_EQ(static_cast<std::int64_t>(rises), rig.fb(0).steps.load());
  EXPECT_EQ(rises, falls);
  EXPECT_GT(rises, 0u);
}

}  // namespace
}  // namespace stepmod::planner
