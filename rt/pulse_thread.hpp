#pragma once
// The pulse thread: owns the real-time loop around a PulseEngine. Sleeps (clock_nanosleep,
// absolute) to shortly before the next edge, spins on the clock to it, writes it. The sleep is
// bounded so that an edge that becomes due earlier (another axis starts, the planner refills) or
// an immediate stop is noticed within max_sleep_ns even though nothing wakes the thread.
//
// Setup that may be refused (mlockall, SCHED_FIFO, affinity) is attempted, recorded in Status
// and never fatal: the caller decides whether to warn. Nothing logs inside the thread.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>

#include "rt/clock.hpp"
#include "rt/pulse_engine.hpp"

namespace stepmod::rt {

// Outside PulseThread so that `Options{}` can be a default argument of its constructor.
struct PulseThreadOptions {
  int priority = 80;                   // SCHED_FIFO priority (1 ... 99); <= 0: stay SCHED_OTHER
  int cpu = -1;                        // CPU to pin to; -1 = not pinned
  Nanos spin_ns = 30 * kNsPerUs;       // wake this long before an edge and spin to it
  Nanos max_sleep_ns = 50 * kNsPerUs;  // longest sleep without looking for new work
  bool lock_memory = true;             // mlockall(MCL_CURRENT | MCL_FUTURE)
  std::size_t prefault_stack_bytes = std::size_t{64} * 1024;  // stack touched before the loop
};

class PulseThread {
 public:
  using Options = PulseThreadOptions;

  // What the setup obtained; valid once start() has returned. errno values are 0 on success or
  // when the step was not requested.
  struct Status {
    bool started = false;
    bool memory_locked = false;
    int mlock_errno = 0;
    bool fifo = false;  // SCHED_FIFO at Options::priority
    int sched_errno = 0;
    bool pinned = false;
    int affinity_errno = 0;
  };

  // The engine must outlive the thread, and belongs to it between start() and join().
  explicit PulseThread(PulseEngine& engine, Options options = Options{});
  ~PulseThread();  // stop() + join()
  PulseThread(const PulseThread&) = delete;
  PulseThread& operator=(const PulseThread&) = delete;

  // Starts the thread and waits until its setup is done (so status() is final). False if the
  // thread could not be created or was already started.
  bool start();
  // Any thread: asks the loop to end; it does within about max_sleep_ns.
  void stop() noexcept { stop_.store(true, std::memory_order_release); }
  // Waits for the thread to end (no-op if not running). Call stop() first.
  void join();

  const Status& status() const noexcept { return status_; }
  const Options& options() const noexcept { return options_; }
  bool running() const noexcept { return thread_.joinable(); }
  // Any thread: loop iterations and edges written so far (for tests and diagnostics).
  std::uint64_t loops() const noexcept { return loops_.load(std::memory_order_relaxed); }
  std::uint64_t edges() const noexcept { return edges_.load(std::memory_order_relaxed); }

 private:
  void body() noexcept;
  void setup() noexcept;
  void loop() noexcept;

  PulseEngine& engine_;
  const Options options_;
  Status status_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> ready_{false};
  std::atomic<std::uint64_t> loops_{0};
  std::atomic<std::uint64_t> edges_{0};
};

}  // namespace stepmod::rt
