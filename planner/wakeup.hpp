#pragma once
// Sleeping on the planner's wake counter with a deadline. std::atomic::wait has no timeout, so the
// planner thread waits on the counter's futex directly (CLOCK_MONOTONIC absolute deadline) and
// submit() wakes that futex.
#include <atomic>
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::planner {

// Blocks until `word` no longer holds `seen`, `deadline` passes, or a spurious wake-up.
void wait_for_change(std::atomic<std::uint32_t>& word, std::uint32_t seen, Nanos deadline) noexcept;
// Bumps `word` and wakes every waiter of wait_for_change() (and of std::atomic::wait).
void bump_and_wake(std::atomic<std::uint32_t>& word) noexcept;

}  // namespace stepmod::planner
