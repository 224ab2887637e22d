// 3202 Find Home + / - per channel: the four homing options chosen by configuration bits 12 / 2
// / 6 and the homing errors (3202 manual Ch.4 "Find Home", Ch.6; checklist items HI-05/06,
// IE-04/05, PI-05/06). The sequences themselves are the shared axis' (3202 manual ch. 4).
#include "tests/module/plc_3202.hpp"

namespace stepmod::testing {
namespace {

namespace sb = m2::status_bit;
namespace cb = m2::cmd_bit;
using namespace m2::cfg_bit;

constexpr Move3202 kHome{.target = 0, .speed = 5'000, .accel = 100'000, .decel = 100'000};

// Limits at +-3,000, no home switch on channel 1; channel 2 as default_3202.
VirtualMachineOptions no_switch() {
  VirtualMachineOptions o = default_3202();
  gpio::SimAxisParams& s = o.axes[0].sim;
  s.home_from.reset();
  s.home_to.reset();
  s.cw_limit_at = 3'000;
  s.ccw_limit_at = -3'000;
  return o;
}

class Homing3202 : public Plc3202 {
 protected:
  Homing3202() : Plc3202(no_switch()) {}
  void SetUp() override {
    configure(0);
    configure(1);
  }
  bool run_until_stopped(unsigned ch) {
    return vm_.run_until_true(
        [&] { return !moving(ch) && (status(ch, sb::kHomeInvalid) || status(ch, sb::kAtHome)); },
        30 * kNsPerSec);
  }
};

TEST_F(Homing3202, HI_05_IE_04_PI_05_BothLimitsReached) {
  command(0, cb::kFindHomeCw, kHome);
  ASSERT_TRUE(run_until_stopped(0));
  EXPECT_TRUE(status(0, sb::kHomeInvalid));
  EXPECT_TRUE(status(0, sb::kInputError));
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  EXPECT_FALSE(status(0, sb::kAtHome));
  EXPECT_FALSE(status(0, sb::kStopped));
  EXPECT_EQ(motor(0), -3'000);
  EXPECT_FALSE(status(1, sb::kHomeInvalid | sb::kInputError));
}

TEST_F(Homing3202, HI_06_IE_05_PI_06_OppositeLimitReachedFirst) {
  command(0, cb::kFindHomeCw, kHome);
  ASSERT_TRUE(vm_.run_until_true([&] { return motor(0) >= 1'000; }, 5 * kNsPerSec));
  force(0, InputLine::kCcwLimit, true);
  const auto at = motor(0);
  vm_.run_for(300 * kNsPerMs);
  EXPECT_LE(motor(0), at + 1);
  EXPECT_TRUE(status(0, sb::kHomeInvalid));
  EXPECT_TRUE(status(0, sb::kInputError));
  EXPECT_TRUE(status(0, sb::kPositionInvalid));
  EXPECT_FALSE(moving(0));
}

// Option 1: the home limit switch (channel 2, home 5,000..5,100), from both sides.
TEST_F(Homing3202, FindHomeWithTheHomeSwitchBothDirections) {
  command(1, cb::kFindHomeCw, kHome);
  ASSERT_TRUE(run_until_stopped(1));
  EXPECT_TRUE(status(1, sb::kAtHome));
  EXPECT_EQ(motor(1), 5'000);
  command(1, cb::kRelativeMove, {.target = 2'000});
  ASSERT_TRUE(vm_.run_until_true([&] { return status(1, sb::kMoveComplete); }, 5 * kNsPerSec));
  command(1, cb::kFindHomeCcw, kHome);
  ASSERT_TRUE(run_until_stopped(1));
  EXPECT_TRUE(status(1, sb::kAtHome));
  EXPECT_EQ(motor(1), 5'100);
}

// Options 2 and 4 take the proximity from command bit 29: the PLC program's sensor sets it
// while the motor is within [4,500, 5,500] (read once per scan).
class Homing3202Prox : public Homing3202 {
 protected:
  bool run_with_prox_zone(unsigned ch) {
    return vm_.run_until_true(
        [&] {
          const bool on = motor(ch) >= 4'500 && motor(ch) <= 5'500;
          auto& w = word(ch, 0);
          w = on ? (w | static_cast<std::int32_t>(cb::kBackplaneProximity))
                 : (w & ~static_cast<std::int32_t>(cb::kBackplaneProximity));
          return !moving(ch) && (status(ch, sb::kHomeInvalid) || status(ch, sb::kAtHome));
        },
        30 * kNsPerSec);
  }
};

// Option 2: the home switch gated by bit 29: the switch counts only with the bit set.
TEST_F(Homing3202Prox, FindHomeWithBackplaneProximity) {
  configure(1, kFull3202 | kBackplaneProximity);
  command(1, cb::kFindHomeCw, kHome);
  ASSERT_TRUE(run_with_prox_zone(1));
  EXPECT_TRUE(status(1, sb::kAtHome));
  EXPECT_EQ(motor(1), 5'000);
}

// Option 3: the marker pulse after the home input (the proximity).
TEST_F(Homing3202, FindHomeOnTheMarkerAfterTheHomeInput) {
  configure(1, kFull3202 | kMarkerHoming);
  command(1, cb::kFindHomeCw, kHome);
  ASSERT_TRUE(run_until_stopped(1));
  EXPECT_TRUE(status(1, sb::kAtHome));
  EXPECT_GE(motor(1), 5'000);
  EXPECT_EQ(motor(1) % 4'000, 0);  // a marker every 4,000 counts
}

// Option 4: the marker pulse after bit 29.
TEST_F(Homing3202Prox, FindHomeOnTheMarkerAfterTheBackplaneBit) {
  configure(1, (kFull3202 & ~kHomeUsed) | kMarkerHoming | kBackplaneProximity);
  command(1, cb::kFindHomeCw, kHome);
  ASSERT_TRUE(run_with_prox_zone(1));
  EXPECT_TRUE(status(1, sb::kAtHome));
  EXPECT_GE(motor(1), 4'500);
  EXPECT_EQ(motor(1) % 4'000, 0);
}

}  // namespace
}  // namespace stepmod::testing
