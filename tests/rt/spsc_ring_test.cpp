#include "core/spsc_ring.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>

namespace stepmod::rt {
namespace {

TEST(SpscRing, RejectsCapacityNotPowerOfTwo) {
  EXPECT_THROW(SpscRing<int>(0), std::invalid_argument);
  EXPECT_THROW(SpscRing<int>(1), std::invalid_argument);
  EXPECT_THROW(SpscRing<int>(3), std::invalid_argument);
  EXPECT_THROW(SpscRing<int>(1000), std::invalid_argument);
  EXPECT_NO_THROW(SpscRing<int>(2));
  EXPECT_NO_THROW(SpscRing<int>(1024));
}

TEST(SpscRing, HoldsExactlyCapacityItems) {
  SpscRing<int> r(8);
  EXPECT_EQ(r.capacity(), 8u);
  EXPECT_TRUE(r.empty());
  EXPECT_EQ(r.peek(), nullptr);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(r.free_slots(), static_cast<std::size_t>(8 - i));
    EXPECT_TRUE(r.try_push(i));
  }
  EXPECT_FALSE(r.try_push(99));
  EXPECT_EQ(r.size(), 8u);
  EXPECT_EQ(r.free_slots(), 0u);
  int v = -1;
  ASSERT_TRUE(r.try_pop(v));
  EXPECT_EQ(v, 0);
  EXPECT_TRUE(r.try_push(8));  // one slot freed, one slot usable
  EXPECT_FALSE(r.try_push(9));
}

TEST(SpscRing, WrapsAroundKeepingOrder) {
  SpscRing<std::uint64_t> r(4);
  std::uint64_t next_in = 0;
  std::uint64_t next_out = 0;
  // Uneven push/pop batches so that head and tail cross the end of the slot array at every
  // offset, many times over.
  for (int round = 0; round < 1000; ++round) {
    const int pushes = 1 + round % 4;
    for (int i = 0; i < pushes && r.try_push(next_in); ++i) ++next_in;
    const int pops = 1 + (round * 7) % 4;
    for (int i = 0; i < pops; ++i) {
      const std::uint64_t* p = r.peek();
      if (p == nullptr) break;
      EXPECT_EQ(*p, next_out);
      r.pop();
      ++next_out;
    }
    EXPECT_EQ(r.size(), next_in - next_out);
  }
  EXPECT_GT(next_out, 1000u);
}

}  // namespace
}  // namespace stepmod::rt
