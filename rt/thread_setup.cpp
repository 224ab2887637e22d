#include "rt/thread_setup.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <algorithm>
#include <cerrno>

namespace stepmod::rt {

namespace {

// Touch the stack the loop will use so that its first page faults happen here, not at an edge.
// With mlockall(MCL_FUTURE) the touched pages then stay resident.
[[gnu::noinline]] void prefault_stack(std::size_t bytes) noexcept {
  if (bytes == 0) return;
  auto* p = static_cast<volatile char*>(__builtin_alloca(bytes));
  for (std::size_t i = 0; i < bytes; i += 1024) p[i] = 0;
}

// MCL_ONFAULT: pages are locked as they are touched, and never paged out after, instead of
// every mapping being populated whole (other threads' 8 MB stacks, whole libraries: twice the
// resident memory). Everything the loop uses was touched before it starts (rings and statistics
// are initialised when allocated; the stack is prefaulted); a code page run for the first time
// costs one minor fault, once. Kernels before 4.4: plain mlockall.
void lock_memory(OutputThreadStatus& status) noexcept {
  int rc = mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT);
  if (rc != 0 && errno == EINVAL) rc = mlockall(MCL_CURRENT | MCL_FUTURE);
  if (rc == 0) {
    status.memory_locked = true;
  } else {
    status.mlock_errno = errno;
  }
}

void set_fifo(int priority, OutputThreadStatus& status) noexcept {
  sched_param sp{};
  sp.sched_priority =
      std::clamp(priority, sched_get_priority_min(SCHED_FIFO), sched_get_priority_max(SCHED_FIFO));
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
  if (rc == 0) {
    status.fifo = true;
  } else {
    status.sched_errno = rc;
  }
}

void pin(int cpu, OutputThreadStatus& status) noexcept {
  cpu_set_t set;
  CPU_ZERO(&set);
  int rc = EINVAL;
  if (cpu < CPU_SETSIZE) {
    CPU_SET(static_cast<unsigned>(cpu), &set);
    rc = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
  }
  if (rc == 0) {
    status.pinned = true;
  } else {
    status.affinity_errno = rc;
  }
}

}  // namespace

bool setup_output_thread(const OutputThreadOptions& options, OutputThreadStatus& status) noexcept {
  // Memory first: once locked (MCL_FUTURE), the stack touched below stays resident too. Refusal
  // (no CAP_IPC_LOCK and a small RLIMIT_MEMLOCK) is recorded; the thread still runs, with the
  // risk of a page fault at an edge.
  if (options.lock_memory) lock_memory(status);
  if (options.priority > 0) set_fifo(options.priority, status);
  if (options.cpu >= 0) pin(options.cpu, status);
  // The kernel may defer a normal thread's timer by its slack (50 us by default) to batch
  // wake-ups; real-time threads get none. A pulse thread refused SCHED_FIFO would otherwise
  // wake up to 50 us late at every edge and spin that much longer (its early wake-up follows
  // its measured lateness): ask for the least slack there is.
  if (!status.fifo) prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  // On a machine with one CPU the thread may use (and not pinned to a CPU of its own), every
  // microsecond it spins before an edge is taken from the threads that feed it (the planner, the
  // control thread, the PLC).
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  const bool single_shared = options.cpu < 0 &&
                             sched_getaffinity(0, sizeof allowed, &allowed) == 0 &&
                             CPU_COUNT(&allowed) <= 1;
  prefault_stack(options.prefault_stack_bytes);
  return single_shared;
}

}  // namespace stepmod::rt
