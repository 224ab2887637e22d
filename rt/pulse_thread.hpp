#pragma once
// The pulse thread: owns the real-time loop around a PulseEngine. Sleeps (absolute
// CLOCK_MONOTONIC deadline) to shortly before the next edge, spins on the clock to it, writes it.
// The sleep is bounded so that an edge that becomes due earlier (another axis starts, the planner
// refills) or an immediate stop is noticed within max_sleep_ns even though nothing wakes the
// thread.
//
// Two things keep the thread from burning a core (issue 5's figures):
//  * Doorbell. The sleep is a futex wait on a counter with the same absolute deadline (the one
//    system call the loop makes besides the line write and the clock, standing in for
//    clock_nanosleep). A producer that calls ring() after queueing work (the daemon: after a
//    scan that submitted a command) wakes it. With quiet_sleep_ns > max_sleep_ns, the thread
//    only polls every max_sleep_ns for awake_ns after a ring, or while an axis is in a motion
//    whose ring has run dry and the time the planner named for its next edge has come (less the
//    spin; AxisControl::refill_at); otherwise it sleeps up to quiet_sleep_ns (or to its next
//    edge, or to that named time).
//    The default (quiet_sleep_ns = max_sleep_ns) keeps the plain bounded poll for producers that
//    never ring.
//  * Adaptive spin. The thread measures how late its own wake-ups are (the distribution over its
//    last 1,024 sleeps, rt/wake_latency.hpp) and wakes its 99th percentile (plus a margin) before
//    an edge: between min_spin_ns and spin_ns. A fixed or mean-tracking spin below the machine's
//    wake-up latency leaves half the edges late (issue 12: ~40 us mean on a VM, 30 us cap).
//    Spinning through every gap shorter than the spin keeps the thread on the CPU all the time
//    (at 50 kHz on a VM), and the kernel's real-time bandwidth limit (sched_rt_runtime_us, 95 %)
//    then takes the CPU away for 50 ms each second: hence the budget below.
//  * Off-CPU budget. Even sleeping in every gap, at 50 kHz on a VM (wake-ups ~15 us late) the
//    thread is on the CPU ~96 % of the time, and the kernel's starvation guard for normal
//    threads (RT throttling; on 6.12+ the fair server) still takes 50 ms of each second when a
//    normal thread is queued on its CPU. Every 20 ms the thread reads its own CPU time and
//    keeps a running balance of the CPU it used beyond (1000 - min_off_cpu_permille) per mille;
//    while that balance is positive it wakes only min_spin_ns before an edge (sleeping longer,
//    leaving the CPU to others): some edges are late by a wake-up's jitter instead of 2,500
//    edges by 50 ms. It cannot help where
//    edges are closer than min_spin_ns (1 Msteps/s): there the pulse thread needs a CPU of its
//    own (rt.cpu, with no other thread scheduled on it: isolcpus or a cpuset).
//
// Setup that may be refused (mlockall, SCHED_FIFO, affinity) is attempted, recorded in Status
// and never fatal: the caller decides whether to warn. Nothing logs inside the thread.
#include <pthread.h>
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "core/clock.hpp"
#include "rt/output_thread.hpp"
#include "rt/pulse_engine.hpp"
#include "rt/sleep_plan.hpp"

namespace stepmod::rt {

// The options and the setup's status are every step output thread's (rt/output_thread.hpp).
using PulseThreadOptions = OutputThreadOptions;

class PulseThread {
 public:
  using Options = OutputThreadOptions;
  using Status = OutputThreadStatus;

  // The engine must outlive the thread, and belongs to it between start() and join().
  explicit PulseThread(PulseEngine& engine, Options options = Options{});
  ~PulseThread();  // stop() + join()
  PulseThread(const PulseThread&) = delete;
  PulseThread& operator=(const PulseThread&) = delete;

  // Starts the thread and waits until its setup is done (so status() is final). False if the
  // thread could not be created or was already started.
  bool start();
  // Any thread: asks the loop to end; it does within about max_sleep_ns.
  void stop() noexcept {
    stop_.store(true, std::memory_order_release);
    ring();
  }
  // Waits for the thread to end (no-op if not running). Call stop() first.
  void join();
  // Any thread but the pulse thread: new work may be queued (a command was submitted, an
  // immediate stop requested): wakes the thread if it sleeps and keeps it polling for awake_ns.
  void ring() noexcept;

  const Status& status() const noexcept { return status_; }
  const Options& options() const noexcept { return options_; }
  bool running() const noexcept { return joinable_; }
  // Any thread: loop iterations and edges written so far (for tests and diagnostics).
  std::uint64_t loops() const noexcept { return loops_.load(std::memory_order_relaxed); }
  std::uint64_t edges() const noexcept { return edges_.load(std::memory_order_relaxed); }
  // Any thread: sleeps so far and the spin the adaptive estimate uses now (diagnostics).
  std::uint64_t sleeps() const noexcept { return sleeps_.load(std::memory_order_relaxed); }
  // Of those, the short polls (max_sleep_ns) of a starved ring: the planner had not said when
  // its next edge comes, or that time had come (AxisControl::refill_at).
  std::uint64_t starved_polls() const noexcept {
    return starved_polls_.load(std::memory_order_relaxed);
  }
  Nanos spin_now() const noexcept { return spin_now_.load(std::memory_order_relaxed); }
  // Any thread: the 99th percentile of the recent wake-up lateness (0 until measured).
  Nanos wake_p99() const noexcept { return wake_p99_.load(std::memory_order_relaxed); }
  // Edges closer than this are spun through, not slept between: a motion whose edges come at
  // least this often keeps the thread on its CPU (the daemon tells the user it needs a CPU of
  // its own): the early wake-up plus the wake-up's own measured lateness.
  Nanos stay_on_cpu_gap() const noexcept { return spin_now() + wake_p99(); }

 private:
  void body() noexcept;
  void setup() noexcept;
  void loop() noexcept;
  void sleep_as_planned(const SleepPlan& plan, std::uint32_t bell) noexcept;

  // The early wake-up's cap when the thread shares the machine's only CPU (see setup()).
  static constexpr Nanos kSharedSingleCpuSpin = 30 * kNsPerUs;

  PulseEngine& engine_;
  const Options options_;
  bool single_shared_cpu_ = false;  // set by setup(), read by loop() (same thread)
  Status status_;
  pthread_t thread_{};
  bool joinable_ = false;
  std::atomic<std::uint32_t> doorbell_{0};
  std::atomic<bool> stop_{false};
  std::atomic<bool> ready_{false};
  std::atomic<std::uint64_t> loops_{0};
  std::atomic<std::uint64_t> edges_{0};
  std::atomic<std::uint64_t> sleeps_{0};
  std::atomic<std::uint64_t> starved_polls_{0};
  std::atomic<Nanos> spin_now_{0};
  std::atomic<Nanos> wake_p99_{0};
};

}  // namespace stepmod::rt
