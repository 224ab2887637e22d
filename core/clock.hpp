#pragma once
// Time in stepmod is always integer nanoseconds of CLOCK_MONOTONIC (see DEVELOPERS.md).
#include <cstdint>
#include <ctime>

namespace stepmod {

using Nanos = std::int64_t;

inline constexpr Nanos kNsPerUs = 1'000;
inline constexpr Nanos kNsPerMs = 1'000'000;
inline constexpr Nanos kNsPerSec = 1'000'000'000;

// vDSO call: no kernel entry on x86/arm64 with a TSC/arch-timer clocksource, so it is safe in the
// pulse thread.
inline Nanos monotonic_now() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<Nanos>(ts.tv_sec) * kNsPerSec + ts.tv_nsec;
}

inline timespec to_timespec(Nanos t) noexcept {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t / kNsPerSec);
  ts.tv_nsec = static_cast<long>(t % kNsPerSec);
  return ts;
}

// Absolute sleep on CLOCK_MONOTONIC; returns early on a signal, which callers tolerate because
// every loop re-reads the clock.
inline void sleep_until(Nanos t) noexcept {
  const timespec ts = to_timespec(t);
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

}  // namespace stepmod
