#pragma once
// The pulse thread's three system facilities, shared with what measures them (stepmodctl doctor's
// wake-up probe runs the same sleep and clock): an absolute-deadline sleep that a doorbell can end,
// the thread's own CPU time, and the pause instruction of a spin. Real-time safe: no allocation,
// no lock; the sleep is one futex system call.
#include <atomic>
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::rt {

// Sleeps until `deadline` (absolute CLOCK_MONOTONIC) or until `word` no longer holds `seen`
// (FUTEX_WAIT_BITSET measures an absolute timeout on CLOCK_MONOTONIC). Returns early on a
// signal or a spurious wake-up: callers re-read the clock.
void futex_sleep_until(std::atomic<std::uint32_t>& word, std::uint32_t seen,
                       Nanos deadline) noexcept;
// Wakes every sleeper on `word`.
void futex_wake_all(std::atomic<std::uint32_t>& word) noexcept;
// CPU time of the calling thread (a system call: the pulse thread reads it once per 20 ms).
Nanos thread_cpu_now() noexcept;

inline void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__) || defined(__arm__)
  asm volatile("yield" ::: "memory");
#endif
}

}  // namespace stepmod::rt
