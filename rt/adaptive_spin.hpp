#pragma once
// Adaptive spin: how long before an edge the pulse thread wakes (rt/pulse_thread.hpp). It wakes
// the 99th percentile of its last WakeLatencyWindow::kWindow wake-ups' lateness plus a margin
// before an edge, within [min_spin, max_spin]; until it has measured a few, max_spin. With
// min_spin == max_spin the spin is fixed and nothing is measured.
//
// Pulse-thread code: fixed arrays, no allocation, no system call; one writer.
#include <algorithm>

#include "core/clock.hpp"
#include "rt/wake_latency.hpp"

namespace stepmod::rt {

class AdaptiveSpin {
 public:
  static constexpr Nanos kMargin = 2 * kNsPerUs;
  static constexpr unsigned kPercentile = 990;  // per mille
  static constexpr unsigned kRecompute = 16;    // wake-ups between two percentile computations

  AdaptiveSpin(Nanos min_spin, Nanos max_spin) noexcept
      : min_spin_(min_spin), max_spin_(max_spin), spin_(max_spin) {}

  // False for a fixed spin: the caller need not measure its wake-ups.
  bool adapts() const noexcept { return min_spin_ < max_spin_; }
  // The early wake-up to use now.
  Nanos spin() const noexcept { return spin_; }
  // The percentile of the lateness last computed (0 until then).
  Nanos p99() const noexcept { return p99_; }

  // A wake-up for an edge came `late` after the time it asked for. True when this one
  // recomputed the percentile (every kRecompute-th): spin() and p99() may have changed.
  bool add(Nanos late) noexcept {
    window_.add(late);
    if (++since_recompute_ < kRecompute) return false;
    since_recompute_ = 0;
    p99_ = window_.percentile(kPercentile);
    spin_ = std::clamp(p99_ + kMargin, min_spin_, max_spin_);
    return true;
  }

 private:
  WakeLatencyWindow window_;
  Nanos min_spin_;
  Nanos max_spin_;
  Nanos spin_;
  Nanos p99_ = 0;
  unsigned since_recompute_ = 0;
};

}  // namespace stepmod::rt
