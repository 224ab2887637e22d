// Races between the pulse thread and the threads around it, run for real (ctest label
// "threading": they also run under ThreadSanitizer).
//
// The head of a ring is checked (immediate stop, step cap) before it is executed, while the
// planner keeps pushing. An edge pushed into an empty ring while the checks run must not become
// the head unchecked: a stale edge of a stopped or faulted motion would be written (or faulted a
// second time), a step beyond a registration cap would make the count inexact. The first tests
// push into an empty ring from a second thread as fast as the engine drains it, so that pushes
// land inside that window many times; none of the edges may ever be written.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <thread>

#include "tests/rt/fake_backend.hpp"

namespace stepmod::rt {
namespace {

using test::make_edge;
using test::Rig;

constexpr std::uint32_t kEpoch = 5;
// Idle, both threads run at once and the pushes reach kPushes in ~10 ms; on a loaded machine
// that time-slices them onto one CPU, a push lands only where the engine's thread is preempted,
// a few hundred in kRunAtMost. Enough either way: before the fix, ~1 push in 5 was written.
constexpr std::uint64_t kPushes = 20'000;
constexpr std::uint64_t kEnoughPushes = 100;
constexpr auto kRunAtMost = std::chrono::seconds(3);

struct Counts {
  std::uint64_t pushed = 0;
  std::uint64_t polls = 0;
};

// A producer pushes leading step edges of motion kEpoch, one at a time into the empty ring,
// while this thread runs the engine; until kPushes, at most kRunAtMost.
Counts race_pushes_against_the_engine(Rig& rig) {
  SpscRing<Edge>& ring = rig.ring(0);
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> pushed{0};
  std::thread producer([&] {
    const Edge e =
        make_edge(0, kEpoch, OutputLine::kStep, true, +1, edge_flag::kMotion | edge_flag::kFirst);
    while (!stop.load(std::memory_order_relaxed)) {
      if (ring.empty() && ring.try_push(e)) pushed.fetch_add(1, std::memory_order_relaxed);
    }
  });
  Counts c;
  const auto end = std::chrono::steady_clock::now() + kRunAtMost;
  while (pushed.load(std::memory_order_relaxed) < kPushes &&
         std::chrono::steady_clock::now() < end) {
    for (int i = 0; i < 1'000; ++i) {
      const Nanos t = rig.engine->next_due();
      if (t != kNever) rig.engine->execute_one(t);
      ++c.polls;
    }
  }
  stop.store(true, std::memory_order_relaxed);
  producer.join();
  c.pushed = pushed.load();
  return c;
}

TEST(PulseEngineHeadRace, EdgesOfAStoppedMotionPushedWhileTheHeadIsCheckedAreNeverWritten) {
  Rig rig(1);
  rig.engine->set_late_limit(kNsPerMs);  // a stale edge let through would also be faulted
  rig.ctl(0).abort_epoch.store(kEpoch);
  ASSERT_EQ(rig.engine->next_due(), kNever);  // the stop is applied before the race starts
  const Counts c = race_pushes_against_the_engine(rig);
  ASSERT_GE(c.pushed, kEnoughPushes) << "the producer hardly ran: nothing was tested";
  EXPECT_TRUE(rig.backend.writes().empty())
      << rig.backend.writes().size() << " writes of " << c.pushed << " stale edges";
  EXPECT_EQ(rig.fb(0).steps.load(), 0);
  EXPECT_EQ(rig.fb(0).late_faults.load(), 0u);
}

TEST(PulseEngineHeadRace, StepsBeyondARegistrationCapPushedWhileTheHeadIsCheckedAreNeverWritten) {
  Rig rig(1);
  rig.ctl(0).limit_steps.store(0);
  rig.ctl(0).limit_epoch.store(kEpoch);  // motion kEpoch may not step past 0: every step is beyond
  const Counts c = race_pushes_against_the_engine(rig);
  ASSERT_GE(c.pushed, kEnoughPushes) << "the producer hardly ran: nothing was tested";
  EXPECT_TRUE(rig.backend.writes().empty())
      << rig.backend.writes().size() << " writes of " << c.pushed << " capped steps";
  EXPECT_EQ(rig.fb(0).steps.load(), 0);
}

// A reader asking for the count at a time after a step's stamp, while the pulse thread is
// between the clock read that stamped it and its record (here: preempted there for 200 us), gets
// the count with that step (it waits for the record): a registration is not one step short.
TEST(StepHistoryStamp, AReaderAfterAStepsStampWaitsForItsRecord) {
  auto h = std::make_unique<StepHistory>();
  h->record(1'000, 1);
  std::atomic<Nanos> stamp{0};
  std::atomic<bool> reading{false};
  std::thread pulse([&] {
    h->announce();
    const Nanos t = monotonic_now();
    stamp.store(t);
    while (!reading.load()) std::this_thread::yield();
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    h->record(t, 2);
  });
  while (stamp.load() == 0) std::this_thread::yield();
  const Nanos event = monotonic_now();  // an input edge after the step's stamp
  ASSERT_GT(event, stamp.load());
  reading.store(true);
  std::int64_t at_event = -1;
  EXPECT_TRUE(h->steps_at(event, 2, at_event));
  pulse.join();
  EXPECT_EQ(at_event, 2);
  EXPECT_FALSE(h->stamping());
}

}  // namespace
}  // namespace stepmod::rt
