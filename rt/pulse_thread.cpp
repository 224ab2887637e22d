#include "rt/pulse_thread.hpp"

#include "rt/adaptive_spin.hpp"
#include "rt/deadline_sleep.hpp"
#include "rt/off_cpu_budget.hpp"
#include "rt/thread_setup.hpp"

#include <pthread.h>

#include <algorithm>

namespace stepmod::rt {


PulseThread::PulseThread(PulseEngine& engine, Options options)
    : engine_(engine), options_(options) {}

PulseThread::~PulseThread() {
  stop();
  join();
}

bool PulseThread::start() {
  if (joinable_) return false;
  stop_.store(false, std::memory_order_relaxed);
  ready_.store(false, std::memory_order_relaxed);
  status_ = Status{};
  // A small stack of our own: mlockall(MCL_CURRENT) makes all of it resident, and the default
  // (RLIMIT_STACK, 8 MB) would all be.
  pthread_attr_t attr;
  if (pthread_attr_init(&attr) != 0) return false;
  if (options_.stack_bytes > 0) {
    pthread_attr_setstacksize(
        &attr, std::max<std::size_t>(options_.stack_bytes, options_.prefault_stack_bytes + 65536));
  }
  const int rc = pthread_create(
      &thread_, &attr,
      [](void* self) -> void* {
        static_cast<PulseThread*>(self)->body();
        return nullptr;
      },
      this);
  pthread_attr_destroy(&attr);
  if (rc != 0) return false;
  joinable_ = true;
  pthread_setname_np(thread_, "stepmod-pulse");
  ready_.wait(false, std::memory_order_acquire);
  return true;
}

void PulseThread::join() {
  if (!joinable_) return;
  pthread_join(thread_, nullptr);
  joinable_ = false;
}

void PulseThread::ring() noexcept {
  doorbell_.fetch_add(1, std::memory_order_release);
  futex_wake_all(doorbell_);
}

void PulseThread::body() noexcept {
  setup();
  status_.started = true;
  ready_.store(true, std::memory_order_release);
  ready_.notify_all();
  loop();
}

void PulseThread::setup() noexcept {
  // The early wake-up's cap on a machine whose only CPU the thread shares (loop()).
  single_shared_cpu_ = setup_output_thread(options_, status_);
}

// No allocation, lock, logging or system call in here but the engine's line writes, the clock
// (vDSO) and the sleep (a futex wait with a deadline: clock_nanosleep that ring() can end).
// The policies are named apart: AdaptiveSpin (how early to wake before an edge), OffCpuBudget
// (the cap on that while the thread owes CPU time), DoorbellWindow and plan_sleep (when to wake
// with no edge near).
void PulseThread::loop() noexcept {
  const Nanos max_spin =
      single_shared_cpu_ ? std::min(options_.spin_ns, kSharedSingleCpuSpin) : options_.spin_ns;
  const Nanos min_spin = std::min(options_.min_spin_ns, max_spin);
  const SleepLimits limits{options_.max_sleep_ns,
                           std::max(options_.quiet_sleep_ns, options_.max_sleep_ns)};
  AdaptiveSpin adaptive(min_spin, max_spin);
  DoorbellWindow doorbell(doorbell_.load(std::memory_order_acquire), options_.awake_ns);
  OffCpuBudget budget(options_.min_off_cpu_permille, min_spin, max_spin, monotonic_now(),
                      thread_cpu_now());
  std::uint64_t loops = 0;
  std::uint64_t edges = 0;
  spin_now_.store(adaptive.spin(), std::memory_order_relaxed);
  while (!stop_.load(std::memory_order_acquire)) {
    loops_.store(++loops, std::memory_order_relaxed);
    const Nanos t = engine_.next_due();
    engine_.announce();  // before the clock read that would stamp a step (StepHistory::announce)
    const Nanos now = monotonic_now();
    if (t != kNever && t <= now) {
      // Stamped with the clock read just before the write: lateness includes the loop's own
      // overhead, which is what a drive sees.
      engine_.execute_one(now);
      edges_.store(++edges, std::memory_order_relaxed);
      continue;
    }
    engine_.withdraw();
    doorbell.see(doorbell_.load(std::memory_order_acquire), now);
    if (budget.window_over(now)) budget.close_window(now, thread_cpu_now());
    const Nanos spin = std::min(adaptive.spin(), budget.spin_cap());
    if (t == kNever || t - now > spin) {
      const SleepPlan plan = plan_sleep(now, t, spin, doorbell.awake(now),
                                        {engine_.starved(), engine_.dry_until()}, limits);
      sleep_as_planned(plan, doorbell.bell());
      if (plan.for_edge && adaptive.adapts()) {
        if (adaptive.add(monotonic_now() - plan.wake)) {
          wake_p99_.store(adaptive.p99(), std::memory_order_relaxed);
        }
        spin_now_.store(std::min(adaptive.spin(), budget.spin_cap()), std::memory_order_relaxed);
      }
      continue;
    }
    // Within the spin of the edge: spin. Each turn goes back through next_due(), so an immediate
    // stop or an earlier edge of another axis is still seen while spinning.
    cpu_relax();
  }
}

// One sleep of the loop, counted (the counters are the pulse thread's alone: a store, no
// read-modify-write).
void PulseThread::sleep_as_planned(const SleepPlan& plan, std::uint32_t bell) noexcept {
  if (plan.starved) {
    starved_polls_.store(starved_polls_.load(std::memory_order_relaxed) + 1,
                         std::memory_order_relaxed);
  }
  futex_sleep_until(doorbell_, bell, plan.wake);
  sleeps_.store(sleeps_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}

}  // namespace stepmod::rt
