#pragma once
// How late the pulse thread's wake-ups are, as a distribution over its last kWindow sleeps: the
// thread wakes that distribution's high percentile (plus a margin) before an edge, so that on
// this machine nearly every edge finds it awake already (issue 12 item 5). An estimate that
// only moved by fractions of each sample (the earlier 1/8-up, 1/64-down average, capped at
// 30 us) sat near the mean on a VM whose wake-ups are ~40 us late on average: half the edges
// were late.
//
// Fixed arrays, no allocation; one writer (the pulse thread). 1 us buckets up to kBuckets - 1;
// longer overshoots (stalls, which the late-edge guard deals with) share the last bucket, so a
// few of them move a high percentile only once they are more than (1 - p) of the window.
#include <array>
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::rt {

class WakeLatencyWindow {
 public:
  static constexpr unsigned kWindow = 1024;  // sleeps
  static constexpr unsigned kBuckets = 512;  // 1 us each

  void add(Nanos overshoot) noexcept {
    const auto us = static_cast<std::uint16_t>(
        overshoot <= 0 ? 0
                       : (overshoot / kNsPerUs >= kBuckets ? kBuckets - 1 : overshoot / kNsPerUs));
    if (size_ == kWindow) {
      --counts_[samples_[next_]];
    } else {
      ++size_;
    }
    samples_[next_] = us;
    ++counts_[us];
    next_ = (next_ + 1) % kWindow;
  }

  unsigned size() const noexcept { return size_; }

  // The smallest overshoot (bucket upper bound, ns) that at least `permille`/1000 of the window
  // did not exceed; 0 for an empty window.
  Nanos percentile(unsigned permille) const noexcept {
    if (size_ == 0) return 0;
    // Walk down from the top: the samples above the percentile are the few.
    const unsigned above = size_ - (size_ * permille + 999) / 1000;
    unsigned seen = 0;
    for (unsigned b = kBuckets; b-- > 0;) {
      seen += counts_[b];
      if (seen > above) return static_cast<Nanos>(b + 1) * kNsPerUs;
    }
    return kNsPerUs;
  }

 private:
  std::array<std::uint16_t, kWindow> samples_{};
  std::array<std::uint16_t, kBuckets> counts_{};
  unsigned size_ = 0;
  unsigned next_ = 0;
};

}  // namespace stepmod::rt
