#include "planner/wakeup.hpp"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <climits>

namespace stepmod::planner {

static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t) &&
                  std::atomic<std::uint32_t>::is_always_lock_free,
              "the wake counter is used as a futex word");

namespace {
std::uint32_t* futex_word(std::atomic<std::uint32_t>& word) noexcept {
  return reinterpret_cast<std::uint32_t*>(&word);
}
}  // namespace

void wait_for_change(std::atomic<std::uint32_t>& word, std::uint32_t seen,
                     Nanos deadline) noexcept {
  if (word.load(std::memory_order_acquire) != seen) return;
  const timespec ts = to_timespec(deadline);
  // FUTEX_WAIT_BITSET takes an absolute CLOCK_MONOTONIC deadline (no FUTEX_CLOCK_REALTIME).
  syscall(SYS_futex, futex_word(word), FUTEX_WAIT_BITSET_PRIVATE, seen, &ts, nullptr,
          FUTEX_BITSET_MATCH_ANY);
}

void bump_and_wake(std::atomic<std::uint32_t>& word) noexcept {
  word.fetch_add(1, std::memory_order_release);
  syscall(SYS_futex, futex_word(word), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
  // libstdc++ skips its own futex call when it tracks no std::atomic::wait waiter; harmless.
  word.notify_all();
}

}  // namespace stepmod::planner
