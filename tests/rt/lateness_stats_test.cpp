#include "rt/lateness_stats.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

namespace stepmod::rt {
namespace {

TEST(LatenessStats, EmptyReadsZero) {
  LatenessStats s;
  const auto snap = s.snapshot();
  EXPECT_EQ(snap.count, 0u);
  EXPECT_EQ(snap.min, 0);
  EXPECT_EQ(snap.max, 0);
  EXPECT_EQ(snap.percentile(0.5), 0);
  EXPECT_EQ(snap.mean(), 0.0);
}

TEST(LatenessStats, ExactPercentilesBelowOneMicrosecond) {
  auto s = std::make_unique<LatenessStats>();
  // 1 ... 1000 in a scrambled order: percentiles must not depend on arrival order.
  for (Nanos i = 0; i < 1000; ++i) s->record(1 + (i * 379) % 1000);
  const auto snap = s->snapshot();
  EXPECT_EQ(snap.count, 1000u);
  EXPECT_EQ(snap.min, 1);
  EXPECT_EQ(snap.max, 1000);
  EXPECT_EQ(snap.sum, 500500);
  EXPECT_DOUBLE_EQ(snap.mean(), 500.5);
  EXPECT_EQ(snap.percentile(0.5), 500);
  EXPECT_EQ(snap.percentile(0.99), 990);
  EXPECT_EQ(snap.percentile(0.999), 999);
  EXPECT_EQ(snap.percentile(1.0), 1000);
  EXPECT_EQ(snap.percentile(0.0), 1);
  EXPECT_EQ(snap.early, 0u);
}

TEST(LatenessStats, LargeValuesWithinOnePercent) {
  auto s = std::make_unique<LatenessStats>();
  // 98 values of 20 us, one of 1.5 ms, one of 3 s.
  for (int i = 0; i < 98; ++i) s->record(20 * kNsPerUs);
  s->record(1'500 * kNsPerUs);
  s->record(3 * kNsPerSec);
  const auto snap = s->snapshot();
  EXPECT_NEAR(snap.percentile(0.5), 20 * kNsPerUs, 20 * kNsPerUs / 100);
  EXPECT_NEAR(snap.percentile(0.99), 1'500 * kNsPerUs, 1'500 * kNsPerUs / 100);
  EXPECT_EQ(snap.percentile(0.999), 3 * kNsPerSec);  // the top bucket is clamped to max
  EXPECT_EQ(snap.max, 3 * kNsPerSec);
}

TEST(LatenessStats, BucketsAreContiguousAndNarrow) {
  using S = LatenessStats;
  EXPECT_EQ(S::bucket_lower(0), 0);
  for (std::size_t b = 0; b + 1 < S::kBuckets; ++b) {
    ASSERT_EQ(S::bucket_upper(b) + 1, S::bucket_lower(b + 1)) << b;
    ASSERT_EQ(S::bucket_of(S::bucket_lower(b)), b);
    ASSERT_EQ(S::bucket_of(S::bucket_upper(b)), b);
    const Nanos width = S::bucket_upper(b) - S::bucket_lower(b) + 1;
    if (b < S::kLinear) {
      ASSERT_EQ(width, 1);
    } else {
      ASSERT_LE(static_cast<double>(width) / static_cast<double>(S::bucket_lower(b)), 0.01);
    }
  }
  EXPECT_EQ(S::bucket_of(std::numeric_limits<Nanos>::max()), S::kBuckets - 1);
  EXPECT_GE(S::bucket_lower(S::kBuckets - 1), 100 * kNsPerSec);  // "up to seconds" and beyond
}

TEST(LatenessStats, NegativeValuesCountAsEarlyInBucketZero) {
  auto s = std::make_unique<LatenessStats>();
  s->record(-50);
  s->record(100);
  const auto snap = s->snapshot();
  EXPECT_EQ(snap.count, 2u);
  EXPECT_EQ(snap.early, 1u);
  EXPECT_EQ(snap.min, -50);
  EXPECT_EQ(snap.buckets[0], 1u);
  EXPECT_EQ(snap.percentile(0.5), 0);
  EXPECT_EQ(snap.percentile(1.0), 100);
}

TEST(LatenessStats, ResetAndRequestedReset) {
  auto s = std::make_unique<LatenessStats>();
  s->record(10);
  s->reset();
  EXPECT_EQ(s->snapshot().count, 0u);
  s->record(7);
  EXPECT_EQ(s->snapshot().min, 7);
  s->request_reset();
  EXPECT_EQ(s->snapshot().count, 0u);  // reads empty before the writer applied it
  s->record(30);
  const auto snap = s->snapshot();
  EXPECT_EQ(snap.count, 1u);
  EXPECT_EQ(snap.min, 30);
  EXPECT_EQ(snap.max, 30);
  EXPECT_EQ(snap.sum, 30);
}

}  // namespace
}  // namespace stepmod::rt
