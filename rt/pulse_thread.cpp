#include "rt/pulse_thread.hpp"

#include "rt/adaptive_spin.hpp"
#include "rt/off_cpu_budget.hpp"

#include <linux/futex.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

namespace stepmod::rt {

namespace {

inline void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__) || defined(__arm__)
  asm volatile("yield" ::: "memory");
#endif
}

// Touch the stack the loop will use so that its first page faults happen here, not at an edge.
// With mlockall(MCL_FUTURE) the touched pages then stay resident.
[[gnu::noinline]] void prefault_stack(std::size_t bytes) noexcept {
  if (bytes == 0) return;
  auto* p = static_cast<volatile char*>(__builtin_alloca(bytes));
  for (std::size_t i = 0; i < bytes; i += 1024) p[i] = 0;
}

// Sleeps until `deadline` (absolute CLOCK_MONOTONIC) or until `word` no longer holds `seen`
// (FUTEX_WAIT_BITSET measures an absolute timeout on CLOCK_MONOTONIC). Returns early on a
// signal or a spurious wake-up, which the loop tolerates: it re-reads the clock every turn.
void futex_sleep_until(std::atomic<std::uint32_t>& word, std::uint32_t seen,
                       Nanos deadline) noexcept {
  static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));
  const timespec ts = to_timespec(deadline);
  syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAIT_BITSET_PRIVATE, seen, &ts,
          nullptr, FUTEX_BITSET_MATCH_ANY);
}

// CPU time of the calling thread (a system call: read once per 20 ms window only).
Nanos thread_cpu_now() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<Nanos>(ts.tv_sec) * kNsPerSec + ts.tv_nsec;
}

void futex_wake_all(std::atomic<std::uint32_t>& word) noexcept {
  syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAKE_PRIVATE, INT32_MAX,
          nullptr, nullptr, 0);
}

}  // namespace

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
  // Memory first: once locked (MCL_FUTURE), the stack touched below stays resident too. Refusal
  // (no CAP_IPC_LOCK and a small RLIMIT_MEMLOCK) is recorded; the thread still runs, with the
  // risk of a page fault at an edge.
  if (options_.lock_memory) {
    // MCL_ONFAULT: pages are locked as they are touched, and never paged out after, instead of
    // every mapping being populated whole (other threads' 8 MB stacks, whole libraries: twice
    // the resident memory). Everything the loop uses was touched before it starts (rings and
    // statistics are initialised when allocated; the stack is prefaulted below); a code page
    // run for the first time costs one minor fault, once. Kernels before 4.4: plain mlockall.
    int rc = mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT);
    if (rc != 0 && errno == EINVAL) rc = mlockall(MCL_CURRENT | MCL_FUTURE);
    if (rc == 0) {
      status_.memory_locked = true;
    } else {
      status_.mlock_errno = errno;
    }
  }
  if (options_.priority > 0) {
    sched_param sp{};
    sp.sched_priority = std::clamp(options_.priority, sched_get_priority_min(SCHED_FIFO),
                                   sched_get_priority_max(SCHED_FIFO));
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    if (rc == 0) {
      status_.fifo = true;
    } else {
      status_.sched_errno = rc;
    }
  }
  if (options_.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    int rc = EINVAL;
    if (options_.cpu < CPU_SETSIZE) {
      CPU_SET(static_cast<unsigned>(options_.cpu), &set);
      rc = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
    }
    if (rc == 0) {
      status_.pinned = true;
    } else {
      status_.affinity_errno = rc;
    }
  }
  // On a machine with one CPU the thread may use (and not pinned to a CPU of its own), every
  // microsecond it spins before an edge is taken from the threads that feed it (the planner, the
  // control thread, the PLC): there the early wake-up stays within kSharedSingleCpuSpin.
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (options_.cpu < 0 && sched_getaffinity(0, sizeof allowed, &allowed) == 0 &&
      CPU_COUNT(&allowed) <= 1) {
    single_shared_cpu_ = true;
  }
  prefault_stack(options_.prefault_stack_bytes);
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
