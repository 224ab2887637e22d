#pragma once
// How the thread of a step output runs on this machine (rt/step_output.hpp, StepOutput::start),
// and what its setup obtained. Every step output on Linux has one: the pulse thread writes the
// edges itself; an output whose edges a peripheral times (a PIO, DMA or SPI-timed output, a
// microcontroller) has a feeder thread that keeps the peripheral's queue filled and its progress
// read. The scheduling fields apply to both; the timing fields are the pulse thread's loop
// (rt/pulse_thread.hpp explains them) and an output that does not wake per edge ignores them.
#include <cstddef>

#include "core/clock.hpp"

namespace stepmod::rt {

struct OutputThreadOptions {
  // --- Scheduling (every output's thread) ---
  int priority = 80;  // SCHED_FIFO priority (1 ... 99); <= 0: stay SCHED_OTHER
  int cpu = -1;       // CPU to pin to; -1 = not pinned
  // mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT): pages stay resident once touched; nothing
  // is populated that nobody uses (PulseThread::setup()).
  bool lock_memory = true;
  std::size_t stack_bytes = std::size_t{256} * 1024;          // this thread's whole stack
  std::size_t prefault_stack_bytes = std::size_t{64} * 1024;  // stack touched before the loop
  // --- The pulse thread's loop (rt/pulse_thread.hpp) ---
  Nanos spin_ns = 100 * kNsPerUs;        // wake at most this long before an edge and spin to it
  Nanos min_spin_ns = 10 * kNsPerUs;     // ... and at least this long (= spin_ns: fixed spin)
  Nanos max_sleep_ns = 50 * kNsPerUs;    // longest sleep without looking for new work
  Nanos quiet_sleep_ns = 50 * kNsPerUs;  // longest sleep when no ring() is recent
  Nanos awake_ns = 20 * kNsPerMs;        // how long a ring() keeps the max_sleep_ns poll on
  // Off-CPU share the thread keeps, per mille, on balance; 0 = off.
  unsigned min_off_cpu_permille = 70;
};

// What the setup obtained; valid once start() has returned. errno values are 0 on success or
// when the step was not requested.
struct OutputThreadStatus {
  bool started = false;
  bool memory_locked = false;
  int mlock_errno = 0;
  bool fifo = false;  // SCHED_FIFO at OutputThreadOptions::priority
  int sched_errno = 0;
  bool pinned = false;
  int affinity_errno = 0;
};

}  // namespace stepmod::rt
