#include "rt/lateness_stats.hpp"

#include <algorithm>
#include <cmath>

namespace stepmod::rt {

Nanos LatenessStats::Snapshot::percentile(double q) const noexcept {
  // The buckets, not `count`, are the population: a snapshot taken while the pulse thread writes
  // may have them differ by a record, and the answer must come from one consistent set.
  std::uint64_t total = 0;
  for (const std::uint64_t b : buckets) total += b;
  if (total == 0) return 0;
  q = std::clamp(q, 0.0, 1.0);
  auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  rank = std::clamp<std::uint64_t>(rank, 1, total);
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < kBuckets; ++i) {
    seen += buckets[i];
    if (seen >= rank) {
      const Nanos v = bucket_upper(i);
      return std::clamp(v, std::min(min, max), max);
    }
  }
  return max;
}

void LatenessStats::snapshot(Snapshot& out) const noexcept {
  // A reset applied halfway through the copy would mix old and new data; copy again then. Three
  // tries are plenty: resets are rare, user-driven events.
  for (int attempt = 0; attempt < 3; ++attempt) {
    const std::uint64_t seq = reset_seq_.load(std::memory_order_acquire);
    if ((seq & 1) != 0) continue;  // a reset is clearing right now
    if (reset_requested_.load(std::memory_order_acquire) !=
        reset_applied_.load(std::memory_order_acquire)) {
      out = Snapshot{};  // reset requested, not yet applied: already reads as empty
      return;
    }
    out.count = count_.load(std::memory_order_acquire);
    // Acquire loads: one that reads a value cleared by a concurrent reset (a release store)
    // makes the reset's odd sequence visible to the check below.
    out.early = early_.load(std::memory_order_acquire);
    out.min = out.count == 0 ? 0 : min_.load(std::memory_order_acquire);
    out.max = out.count == 0 ? 0 : max_.load(std::memory_order_acquire);
    out.sum = sum_.load(std::memory_order_acquire);
    for (std::size_t i = 0; i < kBuckets; ++i) {
      out.buckets[i] = buckets_[i].load(std::memory_order_acquire);
    }
    if (reset_seq_.load(std::memory_order_relaxed) == seq) return;
  }
}

void LatenessStats::apply_reset() noexcept {
  // Seqlock around the clearing: the clearing stores are releases (resets are rare), so a reader
  // whose acquire load saw any cleared value also sees the odd/new sequence. No fences: GCC's
  // ThreadSanitizer does not support them.
  const std::uint64_t seq = reset_seq_.load(std::memory_order_relaxed);
  reset_seq_.store(seq + 1, std::memory_order_relaxed);
  count_.store(0, std::memory_order_release);
  early_.store(0, std::memory_order_release);
  min_.store(0, std::memory_order_release);
  max_.store(0, std::memory_order_release);
  sum_.store(0, std::memory_order_release);
  for (auto& b : buckets_) b.store(0, std::memory_order_release);
  reset_done_ = reset_requested_.load(std::memory_order_acquire);
  reset_applied_.store(reset_done_, std::memory_order_release);
  reset_seq_.store(seq + 2, std::memory_order_release);
}

void LatenessStats::reset() noexcept {
  apply_reset();
}

}  // namespace stepmod::rt
