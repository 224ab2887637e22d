#include "rt/pulse_thread.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

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

}  // namespace

PulseThread::PulseThread(PulseEngine& engine, Options options)
    : engine_(engine), options_(options) {}

PulseThread::~PulseThread() {
  stop();
  join();
}

bool PulseThread::start() {
  if (thread_.joinable()) return false;
  stop_.store(false, std::memory_order_relaxed);
  ready_.store(false, std::memory_order_relaxed);
  status_ = Status{};
  try {
    thread_ = std::thread([this] { body(); });
  } catch (const std::system_error&) {
    return false;
  }
  ready_.wait(false, std::memory_order_acquire);
  return true;
}

void PulseThread::join() {
  if (thread_.joinable()) thread_.join();
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
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
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
  prefault_stack(options_.prefault_stack_bytes);
}

// No allocation, lock, logging or system call in here but the engine's line writes, the clock
// (vDSO) and clock_nanosleep.
void PulseThread::loop() noexcept {
  const Nanos spin_ns = options_.spin_ns;
  const Nanos max_sleep_ns = options_.max_sleep_ns;
  std::uint64_t loops = 0;
  std::uint64_t edges = 0;
  while (!stop_.load(std::memory_order_acquire)) {
    loops_.store(++loops, std::memory_order_relaxed);
    const Nanos t = engine_.next_due();
    const Nanos now = monotonic_now();
    if (t != kNever && t <= now) {
      // Stamped with the clock read just before the write: lateness includes the loop's own
      // overhead, which is what a drive sees.
      engine_.execute_one(now);
      edges_.store(++edges, std::memory_order_relaxed);
      continue;
    }
    if (t == kNever || t - now > spin_ns) {
      Nanos wake = now + max_sleep_ns;
      if (t != kNever) wake = std::min(wake, t - spin_ns);
      sleep_until(wake);
      continue;
    }
    // Within spin_ns of the edge: spin. Each turn goes back through next_due(), so an immediate
    // stop or an earlier edge of another axis is still seen while spinning.
    cpu_relax();
  }
}

}  // namespace stepmod::rt
