// Issue 18 item 2: the axes of a 3602 path share one slip. Stalls of the pulse thread (in virtual
// time) delay both axes by the same amount, so every step point of the line stays within one
// step of the ideal line (the 3602 manual's +-1 step), through hold and resume too, and the
// counts are exact.
#include <algorithm>
#include <cstdlib>
#include <vector>

#include "tests/module/rig_interp_3602.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::status_msw;
namespace cmd = m2::cmd_msw;

class Slip3602 : public RigInterp3602 {
 protected:
  // Stalls of `length` every `every` for `total` (each within the default lag limit).
  void stalls(Nanos length, Nanos every, Nanos total) {
    for (Nanos t = 0; t < total; t += every) {
      vm_.stall_pulse_thread(vm_.now() + every / 2, length);
      vm_.run_for(every);
    }
  }
  // The largest distance, in steps along y, of a step point from the line y = x * dy / dx: both
  // axes' step trains merged in time order (both move in + here).
  double worst_offset(std::int64_t dx, std::int64_t dy) const {
    const auto& xs = vm_.step_times(0);
    const auto& ys = vm_.step_times(1);
    std::size_t i = 0, j = 0;
    double worst = 0;
    while (i < xs.size() || j < ys.size()) {
      if (j >= ys.size() || (i < xs.size() && xs[i] <= ys[j])) {
        ++i;
      } else {
        ++j;
      }
      const double ideal =
          static_cast<double>(i) * static_cast<double>(dy) / static_cast<double>(dx);
      worst = std::max(worst, std::abs(static_cast<double>(j) - ideal));
    }
    return worst;
  }
};

TEST_F(Slip3602, StallsDelayBothAxesAlikeTheLineStaysWithinOneStep) {
  preset(kAxis1, 0);
  preset(kAxis2, 0);
  path_command({.speed = 10'000, .accel = 50, .decel = 50, .end_x = 6'000, .end_y = 2'500});
  stalls(400 * kNsPerUs, 7 * kNsPerMs, 500 * kNsPerMs);
  ASSERT_TRUE(wait_path_end());
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
  EXPECT_TRUE(status(kAxis2, kMoveComplete));
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));
  EXPECT_EQ(vm_.step_times(0).size(), 6'000u);
  EXPECT_EQ(vm_.step_times(1).size(), 2'500u);
  EXPECT_EQ(vm_.stack().motion(0).late_fault().count, 0u);
  EXPECT_GT(vm_.stack().motion(0).slip_ns(), 10 * kNsPerMs);  // the stalls slipped it
  EXPECT_EQ(vm_.stack().motion(0).slip_ns(), vm_.stack().motion(1).slip_ns());
  EXPECT_LE(worst_offset(6'000, 2'500), 1.0);
}

TEST_F(Slip3602, StallsAroundAHoldAndResumeKeepTheLineWithinOneStep) {
  preset(kAxis1, 0);
  preset(kAxis2, 0);
  path_command({.speed = 10'000, .accel = 50, .decel = 50, .end_x = 8'000, .end_y = 3'000});
  stalls(400 * kNsPerUs, 7 * kNsPerMs, 300 * kNsPerMs);
  command(kAxis1, cmd::kHold);
  stalls(400 * kNsPerUs, 7 * kNsPerMs, 100 * kNsPerMs);
  ASSERT_TRUE(
      vm_.run_until_true([this] { return !moving(kAxis1) && !moving(kAxis2); }, 10 * kNsPerSec));
  vm_.scans(5);
  ASSERT_TRUE(status(kAxis1, kHoldState));
  clear_words(kAxis2);
  command(kAxis1, cmd::kResume, {.target = 0, .speed = 10'000, .accel = 50, .decel = 50});
  stalls(400 * kNsPerUs, 7 * kNsPerMs, 300 * kNsPerMs);
  ASSERT_TRUE(wait_path_end());
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
  EXPECT_EQ(vm_.step_times(0).size(), 8'000u);
  EXPECT_EQ(vm_.step_times(1).size(), 3'000u);
  EXPECT_EQ(vm_.stack().motion(0).late_fault().count, 0u);
  EXPECT_LE(worst_offset(8'000, 3'000), 1.0);
}

}  // namespace
}  // namespace stepmod::testing
