// The step-output contract's running half (docs/ARCHITECTURE.md, "Adding a step output"), for
// every output in the factory's table through rt::StepOutput alone: start, ring, a move on the
// output's own thread with an exact count, stop, restart.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "rt/step_output.hpp"
#include "rt/step_output_factory.hpp"
#include "tests/rt/step_output_rig.hpp"

namespace stepmod::rt {
namespace {

using test::OutputRig;
using test::push_step;

StepOutput::Options unprivileged() {
  StepOutput::Options o;
  o.priority = 0;         // the tests run without CAP_SYS_NICE too
  o.lock_memory = false;  // and under the sanitizers
  return o;
}

// Polls `done` until it holds or 10 s have passed (a loaded CI machine).
template <typename Done>
bool wait_for(Done done) {
  const Nanos deadline = monotonic_now() + 10 * kNsPerSec;
  while (!done()) {
    if (monotonic_now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

TEST(StepOutputThread, RunsAMoveOnItsOwnThreadWithAnExactCountUntilStopped) {
  for (const std::string_view name : step_output_names()) {
    SCOPED_TRACE(std::string(name));
    OutputRig r(name, 1);
    EXPECT_FALSE(r.output->running());
    ASSERT_TRUE(r.output->start(unprivileged()));
    EXPECT_TRUE(r.output->running());
    EXPECT_TRUE(r.output->status().started);
    EXPECT_FALSE(r.output->start(unprivileged())) << "it runs already";
    const Nanos t0 = monotonic_now() + 2 * kNsPerMs;
    for (int i = 0; i < 200; ++i) push_step(r.ring(0), t0 + i * 20'000, 2'000, 1, +1, 0, i == 199);
    r.output->ring();
    ASSERT_TRUE(wait_for([&] { return r.fb(0).finished_epoch.load() >= 1; }));
    EXPECT_EQ(r.fb(0).steps.load(), 200);
    EXPECT_GT(r.output->loops(), 0u);
    r.output->stop();
    EXPECT_FALSE(r.output->running());
    EXPECT_EQ(r.output->stats().snapshot().count, 400u);
    EXPECT_EQ(r.backend.writes().size(), 400u);
    // Started again, it takes the next motion.
    ASSERT_TRUE(r.output->start(unprivileged()));
    push_step(r.ring(0), monotonic_now() + kNsPerMs, 2'000, 2, -1, 0, true);
    r.output->ring();
    ASSERT_TRUE(wait_for([&] { return r.fb(0).finished_epoch.load() >= 2; }));
    r.output->stop();
    EXPECT_EQ(r.fb(0).steps.load(), 199);
  }
}

}  // namespace
}  // namespace stepmod::rt
