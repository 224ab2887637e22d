#pragma once
// The pulse thread's wake-up, measured: a thread set up as the pulse thread is (rt/thread_setup:
// memory locked, SCHED_FIFO at [rt] priority, pinned to [rt] cpu) sleeps to an absolute deadline
// with the pulse thread's own sleep (rt/deadline_sleep: a futex wait on CLOCK_MONOTONIC) every
// `interval` for `duration`, and records how late each wake-up came: what cyclictest measures,
// through stepmod's code path. The worst of them is the longest pause an edge can suffer here.
#include <cstdint>
#include <vector>

#include "core/clock.hpp"
#include "rt/output_thread.hpp"

namespace stepmod::doctor {

struct WakeProbeOptions {
  rt::OutputThreadOptions thread;  // priority, cpu, lock_memory as the daemon's pulse thread
  Nanos duration = 5 * kNsPerSec;
  Nanos interval = 200 * kNsPerUs;
};

class WakeLatencies {
 public:
  static constexpr unsigned kBuckets = 20'000;  // 1 us each; the last holds everything longer

  WakeLatencies() : counts_(kBuckets, 0) {}
  void add(Nanos late) noexcept;
  std::uint64_t count() const noexcept { return count_; }
  Nanos worst() const noexcept { return worst_; }
  // The smallest bucket bound (ns) that `fraction` of the wake-ups did not exceed; 0 if empty.
  Nanos percentile(double fraction) const noexcept;

 private:
  std::vector<std::uint64_t> counts_;  // sized before the loop runs: no allocation in it
  std::uint64_t count_ = 0;
  Nanos worst_ = 0;
};

struct WakeProbeResult {
  rt::OutputThreadStatus status;  // what the setup obtained (FIFO refused: not the daemon's case)
  WakeLatencies late;
};

// Blocks for `duration`. A thread that could not be started leaves status.started false.
WakeProbeResult run_wake_probe(const WakeProbeOptions& options);

}  // namespace stepmod::doctor
