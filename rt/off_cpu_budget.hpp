#pragma once
// Off-CPU budget of the pulse thread (why: rt/pulse_thread.hpp). Once per kWindow the caller
// hands in its own CPU time (a clock read); the budget keeps `debt`, the CPU time used beyond
// the allowed share (1000 - min_off_permille per mille), clamped to +-kMaxDebt. While there is
// debt the early wake-up is capped at min_spin (an economy window), else at max_spin.
//
// Pulse-thread code: no allocation, no system call (the caller reads the clocks).
#include <algorithm>

#include "core/clock.hpp"

namespace stepmod::rt {

class OffCpuBudget {
 public:
  static constexpr Nanos kWindow = 20 * kNsPerMs;
  static constexpr Nanos kMaxDebt = 200 * kNsPerMs;

  // min_off_permille = 0: off (window_over() is never true, the cap stays max_spin).
  OffCpuBudget(unsigned min_off_permille, Nanos min_spin, Nanos max_spin, Nanos now,
               Nanos cpu_now) noexcept
      : min_off_(static_cast<Nanos>(min_off_permille)),
        min_spin_(min_spin),
        max_spin_(max_spin),
        window_start_(now),
        window_cpu_(cpu_now),
        spin_cap_(max_spin) {}

  // True when a window has passed: read the thread's CPU time and call close_window().
  bool window_over(Nanos now) const noexcept {
    return min_off_ > 0 && now - window_start_ >= kWindow;
  }
  void close_window(Nanos now, Nanos cpu_now) noexcept {
    debt_ += (cpu_now - window_cpu_) - (now - window_start_) * (1000 - min_off_) / 1000;
    debt_ = std::clamp(debt_, -kMaxDebt, kMaxDebt);
    spin_cap_ = debt_ > 0 ? min_spin_ : max_spin_;
    window_start_ = now;
    window_cpu_ = cpu_now;
  }

  // The longest early wake-up the budget allows now.
  Nanos spin_cap() const noexcept { return spin_cap_; }
  Nanos debt() const noexcept { return debt_; }

 private:
  Nanos min_off_;
  Nanos min_spin_;
  Nanos max_spin_;
  Nanos window_start_;
  Nanos window_cpu_;
  Nanos spin_cap_;
  Nanos debt_ = 0;
};

}  // namespace stepmod::rt
