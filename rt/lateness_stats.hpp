#pragma once
// Lateness of the pulse thread's writes (write time - scheduled edge time), kept so that any
// thread can read p50/p99/p99.9/max at any time while the pulse thread keeps recording.
//
// One writer (the pulse thread) and any number of readers. The writer updates each counter with a
// relaxed load + store (no read-modify-write: there is no other writer, and a locked instruction
// per edge is a cost worth avoiding); readers copy with relaxed loads. A snapshot is therefore not
// one instant: its buckets may hold a record or two more or fewer than its count. Percentiles are
// computed from the buckets alone so that they are always self-consistent.
//
// Histogram: log-linear. Exact (1 ns buckets) below 1024 ns; above, each power of two is split
// into 128 buckets, so a bucket is at most 1/128 (0.8 %) of its value wide. Values up to 2^40 ns
// (~18 minutes) have their own bucket; larger ones share the last. Negative lateness (a write
// before its time, which the thread never does on purpose) goes to bucket 0 and is counted as
// `early`; min and sum keep the signed value so that it shows.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/clock.hpp"

namespace stepmod::rt {

class LatenessStats {
 public:
  static constexpr unsigned kLinearBits = 10;  // 1 ns buckets for [0, 1024)
  static constexpr unsigned kSubBits = 7;      // 128 buckets per power of two above
  static constexpr unsigned kMaxExp = 40;      // powers of two 2^10 ... 2^39 are bucketed
  static constexpr std::size_t kLinear = std::size_t{1} << kLinearBits;
  static constexpr std::size_t kSub = std::size_t{1} << kSubBits;
  static constexpr std::size_t kBuckets = kLinear + (kMaxExp - kLinearBits) * kSub;

  // Bucket of a (non-negative) value, and the value range [lower, upper] of a bucket.
  static constexpr std::size_t bucket_of(Nanos v) noexcept {
    if (v < 0) return 0;
    const auto u = static_cast<std::uint64_t>(v);
    if (u < kLinear) return static_cast<std::size_t>(u);
    const unsigned e = 63u - static_cast<unsigned>(__builtin_clzll(u));  // 2^e <= u < 2^(e+1)
    if (e >= kMaxExp) return kBuckets - 1;
    const std::size_t sub = static_cast<std::size_t>(u >> (e - kSubBits)) & (kSub - 1);
    return kLinear + (e - kLinearBits) * kSub + sub;
  }
  static constexpr Nanos bucket_lower(std::size_t b) noexcept {
    if (b < kLinear) return static_cast<Nanos>(b);
    const std::size_t e = (b - kLinear) / kSub + kLinearBits;
    const std::size_t sub = (b - kLinear) % kSub;
    return static_cast<Nanos>((kSub + sub) << (e - kSubBits));
  }
  static constexpr Nanos bucket_upper(std::size_t b) noexcept {
    if (b + 1 >= kBuckets) return std::numeric_limits<Nanos>::max();
    return bucket_lower(b + 1) - 1;
  }

  struct Snapshot {
    std::uint64_t count = 0;
    std::uint64_t early = 0;  // records with negative lateness
    Nanos min = 0;            // 0 when count == 0
    Nanos max = 0;
    Nanos sum = 0;
    std::array<std::uint64_t, kBuckets> buckets{};

    double mean() const noexcept {
      return count == 0 ? 0.0 : static_cast<double>(sum) / static_cast<double>(count);
    }
    // Value at quantile q in [0, 1] (0.5 = p50, 0.999 = p99.9): the highest value of the bucket
    // holding that rank, clamped to [min, max] (exact below 1 us, within 0.8 % above). 0 when
    // empty.
    Nanos percentile(double q) const noexcept;
  };

  // Pulse thread only.
  void record(Nanos v) noexcept {
    if (reset_requested_.load(std::memory_order_acquire) != reset_done_) apply_reset();
    const std::uint64_t n = count_.load(std::memory_order_relaxed);
    if (n == 0 || v < min_.load(std::memory_order_relaxed)) {
      min_.store(v, std::memory_order_relaxed);
    }
    if (n == 0 || v > max_.load(std::memory_order_relaxed)) {
      max_.store(v, std::memory_order_relaxed);
    }
    sum_.store(sum_.load(std::memory_order_relaxed) + v, std::memory_order_relaxed);
    if (v < 0) early_.store(early_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    std::atomic<std::uint64_t>& b = buckets_[bucket_of(v)];
    b.store(b.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    count_.store(n + 1, std::memory_order_release);
  }

  // Any thread, at any time. The copy is large (~40 KB): keep one around and reuse it.
  void snapshot(Snapshot& out) const noexcept;
  Snapshot snapshot() const noexcept {
    Snapshot s;
    snapshot(s);
    return s;
  }

  // Clears everything at once. Only while no record() can run concurrently (the pulse thread is
  // stopped, or from the pulse thread itself); from another thread use request_reset().
  void reset() noexcept;

  // Any thread: the pulse thread clears the statistics before its next record(). Until then a
  // snapshot() already reads as empty.
  void request_reset() noexcept { reset_requested_.fetch_add(1, std::memory_order_acq_rel); }

 private:
  void apply_reset() noexcept;

  std::atomic<std::uint64_t> count_{0};
  std::atomic<std::uint64_t> early_{0};
  std::atomic<Nanos> min_{0};
  std::atomic<Nanos> max_{0};
  std::atomic<Nanos> sum_{0};
  std::atomic<std::uint64_t> reset_requested_{0};
  std::uint64_t reset_done_ = 0;  // pulse thread's copy of the requests it has applied
  std::atomic<std::uint64_t> reset_applied_{0};  // the same, published for snapshot()
  std::atomic<std::uint64_t> reset_seq_{0};      // odd while a reset is clearing
  std::array<std::atomic<std::uint64_t>, kBuckets> buckets_{};
};

}  // namespace stepmod::rt
