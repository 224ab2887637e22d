// Tests that start threads (ctest label "threading": they also run under ThreadSanitizer). The
// machine may be a loaded 2-core VM: timing assertions are deliberately wide.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "rt/pulse_thread.hpp"
#include "tests/rt/fake_backend.hpp"

namespace stepmod::rt {
namespace {

using test::make_edge;
using test::push_step;
using test::Rig;
using test::Write;

#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer) || __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

PulseThread::Options test_options() {
  PulseThread::Options o;
  o.priority = 10;  // SCHED_FIFO if granted, but below anything else real-time on the box
  // A sanitizer's shadow memory is terabytes of reserved address space: never mlockall it.
  o.lock_memory = !kSanitized;
  return o;
}

// Polls `pred` every 100 us until it holds or `timeout` passes; returns whether it held.
template <typename Pred>
bool wait_for(Pred pred, Nanos timeout) {
  const Nanos end = monotonic_now() + timeout;
  while (!pred()) {
    if (monotonic_now() > end) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  return true;
}

TEST(SpscRingThreads, TransfersMillionItemsInOrder) {
  constexpr std::uint64_t kItems = 1'000'000;
  SpscRing<std::uint64_t> ring(1024);
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kItems;) {
      if (ring.try_push(i)) {
        ++i;
      } else {
        std::this_thread::yield();
      }
    }
  });
  std::uint64_t expected = 0;
  std::uint64_t out_of_order = 0;
  while (expected < kItems) {
    std::uint64_t v = 0;
    if (ring.try_pop(v)) {
      if (v != expected) ++out_of_order;
      expected = v + 1;
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_EQ(out_of_order, 0u);
  EXPECT_TRUE(ring.empty());
}

TEST(StepHistoryThreads, ConcurrentReaderGetsExactCountsOrRefusal) {
  // Step i at time 10 i with count i: the count at time t is t / 10 exactly.
  auto h = std::make_unique<StepHistory>();
  std::atomic<std::int64_t> written{0};
  std::atomic<bool> done{false};
  constexpr std::int64_t kSteps = 200'000;
  // The writer keeps going until the reader has answered enough queries: in an optimised build
  // it would otherwise finish before the reader thread is even scheduled.
  std::atomic<std::uint64_t> answered{0};
  std::thread writer([&] {
    for (std::int64_t i = 1; i <= kSteps || answered.load(std::memory_order_relaxed) < 1000; ++i) {
      h->record(i * 10, i);
      written.store(i, std::memory_order_release);
    }
    done.store(true, std::memory_order_release);
  });
  std::uint64_t wrong = 0;
  std::uint64_t k = 0;
  while (!done.load(std::memory_order_acquire)) {
    const std::int64_t n = written.load(std::memory_order_acquire);
    if (n < 10) continue;
    // Look back between 0 and ~3/4 of the history, off the step instants.
    const std::int64_t back = static_cast<std::int64_t>((k++ * 7919) % 3000);
    if (back >= n) continue;
    const Nanos t = (n - back) * 10 + 5;
    std::int64_t out = -1;
    if (h->steps_at(t, n, out)) {
      answered.fetch_add(1, std::memory_order_relaxed);
      if (out != t / 10) ++wrong;
    }
  }
  writer.join();
  EXPECT_EQ(wrong, 0u);
  EXPECT_GE(answered.load(), 1000u);
}

TEST(LatenessStatsThreads, SnapshotsWhileRecording) {
  auto s = std::make_unique<LatenessStats>();
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int i = 0; i < 200'000; ++i) s->record(100 + i % 900);
    done.store(true, std::memory_order_release);
  });
  auto snap = std::make_unique<LatenessStats::Snapshot>();
  std::uint64_t last = 0;
  bool monotonic = true;
  while (!done.load(std::memory_order_acquire)) {
    s->snapshot(*snap);
    if (snap->count < last) monotonic = false;
    last = snap->count;
    if (snap->count > 0) {
      const Nanos p50 = snap->percentile(0.5);
      EXPECT_GE(p50, 100);
      EXPECT_LE(p50, 999);
    }
  }
  writer.join();
  EXPECT_TRUE(monotonic);
  s->snapshot(*snap);
  EXPECT_EQ(snap->count, 200'000u);
  EXPECT_EQ(snap->min, 100);
  EXPECT_EQ(snap->max, 999);
}

TEST(PulseThread, ExecutesScheduleAtAboutTheRightTimes) {
  Rig rig(2);
  struct Due {
    Nanos t;
    unsigned axis;
    bool level;
  };
  std::vector<Due> schedule;
  const Nanos t0 = monotonic_now() + 20 * kNsPerMs;
  constexpr Nanos kWidth = 2 * kNsPerUs;
  for (int i = 0; i < 100; ++i) {
    const Nanos t = t0 + i * 500 * kNsPerUs;
    push_step(rig.ring(0), t, kWidth, 1, +1, 0, i == 99);
    schedule.push_back({t, 0, true});
    schedule.push_back({t + kWidth, 0, false});
  }
  for (int i = 0; i < 70; ++i) {
    const Nanos t = t0 + 250 * kNsPerUs + i * 700 * kNsPerUs;
    push_step(rig.ring(1), t, kWidth, 1, +1, 0, i == 69);
    schedule.push_back({t, 1, true});
    schedule.push_back({t + kWidth, 1, false});
  }
  std::sort(schedule.begin(), schedule.end(), [](const Due& a, const Due& b) { return a.t < b.t; });

  PulseThread thread(*rig.engine, test_options());
  ASSERT_TRUE(thread.start());
  const PulseThread::Status& st = thread.status();
  EXPECT_TRUE(st.started);
  EXPECT_EQ(st.fifo, st.sched_errno == 0);
  if (test_options().lock_memory) {
    EXPECT_EQ(st.memory_locked, st.mlock_errno == 0);
  }
  EXPECT_TRUE(wait_for(
      [&] { return rig.fb(0).finished_epoch.load() == 1 && rig.fb(1).finished_epoch.load() == 1; },
      10 * kNsPerSec));
  thread.stop();
  thread.join();

  const auto& w = rig.backend.writes();
  ASSERT_EQ(w.size(), schedule.size());
  // Per axis, the writes are that axis' schedule in order, never early. Across axes only the
  // write times are ordered: a late rise delays its own fall (full pulse width), which may then
  // come after the other axis' next edge.
  std::vector<Nanos> due(w.size(), 0);  // each write's scheduled time
  for (unsigned axis = 0; axis < 2; ++axis) {
    std::vector<Due> mine;
    for (const Due& d : schedule) {
      if (d.axis == axis) mine.push_back(d);
    }
    std::size_t k = 0;
    for (std::size_t i = 0; i < w.size(); ++i) {
      if (w[i].axis != axis) continue;
      ASSERT_LT(k, mine.size());
      EXPECT_EQ(w[i].level, mine[k].level) << axis << ":" << k;
      EXPECT_GE(w[i].t, mine[k].t) << axis << ":" << k;       // never stamped early
      EXPECT_GE(w[i].real_t, mine[k].t) << axis << ":" << k;  // and never actually early
      due[i] = mine[k].t;
      ++k;
    }
    EXPECT_EQ(k, mine.size());
  }
  for (std::size_t i = 1; i < w.size(); ++i) EXPECT_GE(w[i].t, w[i - 1].t) << i;
  EXPECT_EQ(rig.fb(0).steps.load(), 100);
  EXPECT_EQ(rig.fb(1).steps.load(), 70);
  const auto s = rig.engine->stats().snapshot();
  EXPECT_EQ(s.count, schedule.size());
  EXPECT_EQ(s.early, 0u);
  // On time, measured so that a loaded machine cannot fail it: how long each write took beyond
  // the later of its due time and the write before it. A thread that keeps its deadlines has
  // a few us of this per edge; a stall adds to the one edge whose wait spans it (the late edges
  // after it are written back to back), where lateness from the schedule counts it on every
  // edge due in it: a TSan run beside daemon tests once started this 50 ms schedule with a
  // p50 lateness of 53 ms. A deadline bug (a wrong sleep target, a unit) is late on every edge.
  std::vector<Nanos> excess;
  for (std::size_t i = 0; i < w.size(); ++i) {
    excess.push_back(w[i].real_t - std::max(due[i], i == 0 ? due[i] : w[i - 1].real_t));
  }
  std::nth_element(excess.begin(), excess.begin() + excess.size() / 2, excess.end());
  EXPECT_LT(excess[excess.size() / 2], 2 * kNsPerMs);
  // For the record (--gtest_output=xml): what this machine achieved.
  RecordProperty("lateness_p50_ns", std::to_string(s.percentile(0.5)));
  RecordProperty("lateness_p99_ns", std::to_string(s.percentile(0.99)));
  RecordProperty("lateness_max_ns", std::to_string(s.max));
  RecordProperty("sched_fifo", st.fifo ? "yes" : "no");
  RecordProperty("memory_locked", st.memory_locked ? "yes" : "no");
  EXPECT_GT(thread.loops(), 0u);
  EXPECT_EQ(thread.edges(), schedule.size());
}

TEST(PulseThread, ImmediateStopTakesEffectWithoutPlanner) {
  Rig rig(1);
  // A long motion queued ahead, as if the planner had filled the ring and then stalled.
  const Nanos t0 = monotonic_now() + 5 * kNsPerMs;
  for (int i = 0; i < 2000; ++i) {
    push_step(rig.ring(0), t0 + i * kNsPerMs, 500 * kNsPerUs, 1, +1, 0, i == 1999);
  }
  PulseThread thread(*rig.engine, test_options());
  ASSERT_TRUE(thread.start());
  ASSERT_TRUE(wait_for([&] { return rig.fb(0).steps.load() >= 5; }, 5 * kNsPerSec));
  // Stop while (with luck) a pulse is high: steps are 1 ms apart, pulses 0.5 ms wide.
  const Nanos asked = monotonic_now();
  rig.ctl(0).abort_epoch.store(1, std::memory_order_release);
  ASSERT_TRUE(wait_for([&] { return rig.fb(0).finished_epoch.load() >= 1; }, kNsPerSec));
  const Nanos acked = monotonic_now();
  EXPECT_LT(acked - asked, 200 * kNsPerMs);  // typically ~50 us; wide for a loaded VM
  const std::int64_t steps = rig.fb(0).steps.load();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(rig.fb(0).steps.load(), steps);
  EXPECT_LT(steps, 1000);
  EXPECT_TRUE(rig.ring(0).empty());
  EXPECT_EQ(rig.fb(0).output_levels.load(), 0u);
  thread.stop();
  thread.join();
  const auto& w = rig.backend.writes();
  ASSERT_FALSE(w.empty());
  EXPECT_FALSE(w.back().level);  // the step line rests low
  std::size_t highs = 0;
  for (const Write& x : w) highs += x.level ? 1 : 0;
  EXPECT_EQ(static_cast<std::int64_t>(highs), steps);
}

TEST(PulseThread, NoticesEarlierEdgeWhileSleepingAndStopsPromptly) {
  Rig rig(2);
  const Nanos far = monotonic_now() + 60 * kNsPerSec;
  rig.ring(0).try_push(make_edge(far, 0, OutputLine::kGpo, true, 0, 0));
  PulseThread thread(*rig.engine, test_options());
  ASSERT_TRUE(thread.start());
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  // Another axis starts while the thread is sleeping toward the far edge.
  const Nanos soon = monotonic_now() + 2 * kNsPerMs;
  push_step(rig.ring(1), soon, 2 * kNsPerUs, 1, +1, 0, true);
  EXPECT_TRUE(wait_for([&] { return rig.fb(1).finished_epoch.load() == 1; }, 2 * kNsPerSec));
  const Nanos asked = monotonic_now();
  thread.stop();
  thread.join();
  EXPECT_LT(monotonic_now() - asked, 500 * kNsPerMs);
  const auto& w = rig.backend.writes();
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].axis, 1u);
  EXPECT_GE(w[0].t, soon);
  EXPECT_FALSE(rig.ring(0).empty());  // the far edge is still pending
}

TEST(PulseThread, StartTwiceIsRefusedAndRestartAfterJoinWorks) {
  Rig rig(1);
  PulseThread thread(*rig.engine, test_options());
  ASSERT_TRUE(thread.start());
  EXPECT_FALSE(thread.start());
  thread.stop();
  thread.join();
  EXPECT_FALSE(thread.running());
  ASSERT_TRUE(thread.start());
  push_step(rig.ring(0), monotonic_now() + kNsPerMs, 2 * kNsPerUs, 1, +1, 0, true);
  EXPECT_TRUE(wait_for([&] { return rig.fb(0).finished_epoch.load() == 1; }, 2 * kNsPerSec));
}

}  // namespace
}  // namespace stepmod::rt
