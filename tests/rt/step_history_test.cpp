#include <gtest/gtest.h>

#include <memory>

#include "rt/axis_feedback.hpp"

namespace stepmod::rt {
namespace {

class StepHistoryTest : public ::testing::Test {
 protected:
  std::int64_t at(Nanos t, std::int64_t now_steps) {
    std::int64_t out = -12345;
    EXPECT_TRUE(h->steps_at(t, now_steps, out)) << "t=" << t;
    return out;
  }
  std::unique_ptr<StepHistory> h = std::make_unique<StepHistory>();
};

TEST_F(StepHistoryTest, NoStepsYetAnswersNowSteps) {
  EXPECT_EQ(at(1000, 0), 0);
}

TEST_F(StepHistoryTest, CountsAtTimesBeforeBetweenAndAfterSteps) {
  // Steps CW at 100, 200, 300 (counts 1, 2, 3), then CCW at 400 (count 2).
  h->record(100, 1);
  h->record(200, 2);
  h->record(300, 3);
  h->record(400, 2);
  EXPECT_EQ(at(50, 2), 0);  // before the first step
  EXPECT_EQ(at(99, 2), 0);
  EXPECT_EQ(at(100, 2), 1);  // at a step: counted
  EXPECT_EQ(at(150, 2), 1);  // between steps
  EXPECT_EQ(at(299, 2), 2);
  EXPECT_EQ(at(300, 2), 3);
  EXPECT_EQ(at(399, 2), 3);
  EXPECT_EQ(at(400, 2), 2);
  EXPECT_EQ(at(10'000, 2), 2);  // after the last
}

TEST_F(StepHistoryTest, AfterWraparoundOldTimesAreRefused) {
  const std::int64_t n = 3 * StepHistory::kSize + 17;
  for (std::int64_t i = 1; i <= n; ++i) h->record(i * 10, i);
  EXPECT_EQ(at(n * 10 + 5, n), n);
  EXPECT_EQ(at(n * 10 - 5, n), n - 1);
  const std::int64_t old = n - static_cast<std::int64_t>(StepHistory::kSize) / 2;
  EXPECT_EQ(at(old * 10 + 3, n), old);
  std::int64_t out = -1;
  EXPECT_FALSE(h->steps_at(50, n, out));  // long overwritten
  EXPECT_EQ(out, -1);
  EXPECT_FALSE(h->steps_at((n - static_cast<std::int64_t>(StepHistory::kSize)) * 10 - 1, n, out));
}

}  // namespace
}  // namespace stepmod::rt
