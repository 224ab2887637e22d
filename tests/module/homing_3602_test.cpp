// 3602 homing (3602 manual Ch.4 "Homing the 3602", Ch.8 "Homing Timeout"; checklist items
// Home Invalid and CE-12): the home input alone, the 2-s pause after each stop inside the
// sequence, the homing timeout, the command checks.
#include <vector>

#include "tests/module/rig_3602.hpp"
#include "tests/support/checklist_rows.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::status_msw;
namespace cmd = m2::cmd_msw;

// Find Home + on axis 1 (home switch at 5,000..5,100): Vp 10,000, Vs 1,000.
constexpr Move3602 kHome{.target = 0, .speed = 10'000, .accel = 20, .decel = 20};

class Homing3602 : public Rig3602 {
 protected:
  static constexpr Nanos kLimit = 60 * kNsPerSec;

  bool wait_homed(unsigned axis) {
    return vm_.run_until_true([this, axis] { return status(axis, kAtHome); }, kLimit);
  }
  // The backplane proximity bit (command LSW bit 6): a level the PLC holds (A44).
  void set_proximity(unsigned axis, bool on) {
    word(axis, m2::out_word::kLsw) =
        static_cast<std::int16_t>(on ? m2::cmd_lsw::kBackplaneProximity : std::uint16_t{0});
  }
  // The idle gaps between step edges longer than `at_least`.
  unsigned gaps(unsigned axis, Nanos at_least) const {
    const auto& t = vm_.step_times(axis);
    unsigned n = 0;
    for (std::size_t i = 1; i < t.size(); ++i) {
      if (t[i] - t[i - 1] >= at_least) ++n;
    }
    return n;
  }
};

TEST_F(Homing3602, AH_01_HomeInputAloneEndsAtHomeWithPositionZero) {
  configure(kAxis1);
  command(kAxis1, cmd::kFindHomeCw, kHome);
  ASSERT_TRUE(wait_homed(kAxis1));
  EXPECT_EQ(position(kAxis1), 0);
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));
  EXPECT_FALSE(status(kAxis1, kHomeInvalid));
  EXPECT_TRUE(status(kAxis1, kStopped));  // 3602-STP-01: idle after homing too
  // The home edge is met at 5,000 going CW at Vs after the reversal and pauses.
  EXPECT_GE(motor(kAxis1), 5'000);
  EXPECT_LE(motor(kAxis1), 5'001);
  // The 2-s pause after each decel-to-stop inside the sequence: after the stop past the home
  // switch and after the stop of the reversal (3602 manual ch. 4).
  EXPECT_EQ(gaps(kAxis1, 2 * kNsPerSec), 2u);
  EXPECT_EQ(gaps(kAxis1, 2 * kNsPerSec + 50 * kNsPerMs), 0u);  // and not much more
  // Passing the home switch later does not set At Home again once a move cleared it.
  command(kAxis1, cmd::kRelativeMove, {.target = 300});
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_FALSE(status(kAxis1, kAtHome));
}

// 3602-HI-07, A16: the timeout stops the search with a controlled stop and sets HI; PI is left
// as it was.
TEST_F(Homing3602, HI_07_HomingTimeoutSetsHomeInvalid) {
  configure(kAxis1, kLimitsConfigMsw, kAllActiveHigh3602, 1'000, 1);  // T = 1 s
  command(kAxis1, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  ASSERT_FALSE(status(kAxis1, kPositionInvalid));
  Move3602 slow = kHome;
  slow.speed = 2'000;  // 5,000 steps away: 2.5 s, longer than T
  command(kAxis1, cmd::kFindHomeCw, slow);
  vm_.run_for(900 * kNsPerMs);
  EXPECT_TRUE(moving(kAxis1));
  EXPECT_FALSE(status(kAxis1, kHomeInvalid));
  ASSERT_TRUE(wait_idle(kAxis1, 2 * kNsPerSec));
  EXPECT_TRUE(status(kAxis1, kHomeInvalid));
  EXPECT_FALSE(status(kAxis1, kAtHome));
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));  // A16
  EXPECT_LT(motor(kAxis1), 5'000);
  EXPECT_GT(motor(kAxis1), 1'000);
  EXPECT_EQ(position(kAxis1), motor(kAxis1));
  // Nothing runs on afterwards.
  const std::int64_t at = motor(kAxis1);
  vm_.run_for(3 * kNsPerSec);
  EXPECT_EQ(motor(kAxis1), at);
}

TEST_F(Homing3602, HI_07_TimeoutCountsThePauses) {
  // T = 3 s: the search reaches the switch in ~0.6 s, then the 2-s pause and the reversal; the
  // sequence cannot complete within 3 s, so it times out, pauses included.
  configure(kAxis1, kLimitsConfigMsw, kAllActiveHigh3602, 1'000, 3);
  command(kAxis1, cmd::kFindHomeCw, kHome);
  ASSERT_TRUE(vm_.run_until_true([this] { return status(kAxis1, kHomeInvalid); }, kLimit));
  ASSERT_TRUE(wait_idle(kAxis1));
  EXPECT_FALSE(status(kAxis1, kAtHome));
  const std::int64_t at = motor(kAxis1);
  vm_.run_for(5 * kNsPerSec);
  EXPECT_EQ(motor(kAxis1), at);
}

TEST_F(Homing3602, HI_07_ZeroTimeoutSearchesWithoutLimit) {
  configure(kAxis1, kLimitsConfigMsw, kAllActiveHigh3602, 1'000, 0);
  Move3602 slow = kHome;
  slow.speed = 2'000;
  command(kAxis1, cmd::kFindHomeCw, slow);
  ASSERT_TRUE(wait_homed(kAxis1));
  EXPECT_FALSE(status(kAxis1, kHomeInvalid));
}

// Both axes home at once, each on its own switch (axis 2: -3,000..-2,900, Find Home -).
TEST_F(Homing3602, AH_01_BothAxesHomeIndependently) {
  configure(kAxis1);
  configure(kAxis2);
  set_command(kAxis1, cmd::kFindHomeCw, kHome);
  set_command(kAxis2, cmd::kFindHomeCcw, kHome);
  vm_.scans(3);
  word(kAxis1, m2::out_word::kMsw) = 0;
  word(kAxis2, m2::out_word::kMsw) = 0;
  ASSERT_TRUE(wait_homed(kAxis1));
  ASSERT_TRUE(wait_homed(kAxis2));
  EXPECT_GE(motor(kAxis1), 5'000);
  EXPECT_LE(motor(kAxis1), 5'001);
  EXPECT_LE(motor(kAxis2), -2'900);
  EXPECT_GE(motor(kAxis2), -2'901);
}

// 3602-HI-05 / IE-04 / PI-06: the limit opposite to the homing direction during the search.
TEST_F(Homing3602, HI_05_IE_04_PI_06_OppositeLimitDuringHoming) {
  configure(kAxis1);
  command(kAxis1, cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  command(kAxis1, cmd::kFindHomeCw, kHome);
  vm_.run_for(200 * kNsPerMs);
  ASSERT_TRUE(moving(kAxis1));
  vm_.sim().force(kAxis1, 1u << static_cast<unsigned>(InputLine::kCcwLimit),
                  1u << static_cast<unsigned>(InputLine::kCcwLimit), vm_.now());
  ASSERT_TRUE(wait_idle(kAxis1, kNsPerSec));
  EXPECT_TRUE(status(kAxis1, kHomeInvalid));
  EXPECT_TRUE(status(kAxis1, kInputError));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
  EXPECT_FALSE(status(kAxis1, kAtHome));
}

// 3602-HI-08: both overtravel limits met while searching -> immediate stop with HI + IE + PI.
TEST_F(Homing3602, HI_08_BothLimitsDuringHoming) {
  configure(kAxis1);
  command(kAxis1, cmd::kFindHomeCw, kHome);
  vm_.run_for(200 * kNsPerMs);
  const std::uint32_t cw = 1u << static_cast<unsigned>(InputLine::kCwLimit);
  const std::uint32_t ccw = 1u << static_cast<unsigned>(InputLine::kCcwLimit);
  vm_.sim().force(kAxis1, cw, cw, vm_.now());  // the limit ahead: reverse after the pause
  vm_.run_for(3 * kNsPerSec);
  vm_.sim().force(kAxis1, cw | ccw, 0 | ccw, vm_.now());  // then the other one
  ASSERT_TRUE(wait_idle(kAxis1, 10 * kNsPerSec));
  EXPECT_TRUE(status(kAxis1, kHomeInvalid));
  EXPECT_TRUE(status(kAxis1, kInputError));
  EXPECT_TRUE(status(kAxis1, kPositionInvalid));
}

// 3602-HI-06: a limit active at the same time as the Home input during homing.
TEST_F(Homing3602, HI_06_LimitTogetherWithTheHomeInput) {
  configure(kAxis1);
  command(kAxis1, cmd::kFindHomeCw, kHome);
  vm_.run_for(200 * kNsPerMs);
  const std::uint32_t home = 1u << static_cast<unsigned>(InputLine::kHome);
  const std::uint32_t cw = 1u << static_cast<unsigned>(InputLine::kCwLimit);
  vm_.sim().force(kAxis1, home, home, vm_.now());  // the home input: the sequence goes on
  vm_.scans(2);
  EXPECT_FALSE(status(kAxis1, kHomeInvalid));
  vm_.sim().force(kAxis1, home | cw, home | cw, vm_.now());  // and a limit with it
  ASSERT_TRUE(wait_idle(kAxis1, kNsPerSec));
  EXPECT_TRUE(status(kAxis1, kHomeInvalid));
  EXPECT_FALSE(status(kAxis1, kAtHome));
}

// 3602-CE-08, third clause: Hold during a Find Home -> CE; the homing goes on to At Home
// (3602 manual ch. 4: "Hold -> CE, homing continues").
TEST_F(Homing3602, CE_08_HoldDuringFindHomeIsRefusedAndHomingContinues) {
  configure(kAxis1);
  command(kAxis1, cmd::kFindHomeCw, kHome);
  vm_.run_for(200 * kNsPerMs);
  ASSERT_TRUE(moving(kAxis1));
  command(kAxis1, cmd::kHold, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_TRUE(status(kAxis1, kCommandError));
  EXPECT_FALSE(status(kAxis1, kHoldState));
  EXPECT_TRUE(moving(kAxis1));
  ASSERT_TRUE(wait_homed(kAxis1));
  EXPECT_EQ(position(kAxis1), 0);
  EXPECT_GE(motor(kAxis1), 5'000);
  EXPECT_LE(motor(kAxis1), 5'001);
}

// ---- Homing option 2: the home input gated by the backplane proximity bit (config MSW bit 7,
// command LSW bit 6; 3602 manual Ch.4 "Homing the 3602" Figure 4.2) -------------------------------

// H-B: the proximity bit's 0->1 edge slows the search to Vs; the next home input edge stops it
// at once (no pause, no reversal): At Home, position 0 (AH-01), PI cleared (PI-C1).
TEST_F(Homing3602, AH_01_PI_C1_ProximityBitSlowsToVsAndTheHomeEdgeStops) {
  configure(kAxis1, kLimitsConfigMsw | m2::cfg_msw::kBackplaneProximity);
  ASSERT_TRUE(status(kAxis1, kPositionInvalid));  // configured, never preset or homed
  command(kAxis1, cmd::kFindHomeCw, kHome);
  ASSERT_TRUE(vm_.run_until_true([this] { return motor(kAxis1) >= 1'000; }, kLimit));
  set_proximity(kAxis1, true);
  ASSERT_TRUE(wait_homed(kAxis1));
  EXPECT_EQ(position(kAxis1), 0);
  EXPECT_FALSE(status(kAxis1, kPositionInvalid));
  EXPECT_FALSE(status(kAxis1, kHomeInvalid));
  EXPECT_FALSE(moving(kAxis1));
  // Stopped on the home edge at 5,000 on the way CW: no reversal, so no 2-s pause either.
  EXPECT_GE(motor(kAxis1), 5'000);
  EXPECT_LE(motor(kAxis1), 5'001);
  EXPECT_EQ(gaps(kAxis1, kNsPerSec), 0u);
  // Slowed toward Vs after the bit rose: from 10,000 to 1,000 steps/s at 20,000 steps/s^2 takes
  // 2,475 steps, so the last steps before the switch (4,000 steps after the edge) ran at Vs:
  // 1 ms apart, where the search at Vp made them 0.1 ms apart.
  const auto& t = vm_.step_times(kAxis1);
  ASSERT_GE(t.size(), 20u);
  EXPECT_GE(t[t.size() - 1] - t[t.size() - 3], 2 * 900 * kNsPerUs);
  EXPECT_LE(t[t.size() - 1] - t[t.size() - 3], 2 * 1'100 * kNsPerUs);
}

// H-B step 2: until the proximity bit rises the home input is ignored; the axis runs across the
// whole switch at Vp and on. The bit rising past the switch slows it to Vs, but only the next
// home edge would stop it (none lies ahead before the limit): Immediate Stop ends the test.
TEST_F(Homing3602, AH_01_HomeInputIgnoredUntilTheProximityBitRises) {
  configure(kAxis1, kLimitsConfigMsw | m2::cfg_msw::kBackplaneProximity);
  command(kAxis1, cmd::kFindHomeCw, kHome);
  ASSERT_TRUE(vm_.run_until_true([this] { return motor(kAxis1) >= 6'000; }, kLimit));
  EXPECT_TRUE(moving(kAxis1));
  EXPECT_FALSE(status(kAxis1, kAtHome));
  EXPECT_EQ(gaps(kAxis1, kNsPerSec), 0u);  // no stop and pause at the switch
  set_proximity(kAxis1, true);
  vm_.run_for(kNsPerSec);
  EXPECT_TRUE(moving(kAxis1));
  EXPECT_FALSE(status(kAxis1, kAtHome));
  const auto& t = vm_.step_times(kAxis1);
  ASSERT_GE(t.size(), 3u);
  EXPECT_GE(t[t.size() - 1] - t[t.size() - 3], 2 * 900 * kNsPerUs);  // at Vs
  command(kAxis1, cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(kAxis1, kNsPerSec));
  EXPECT_FALSE(status(kAxis1, kAtHome));
}

// A44: the proximity bit acts only when the configuration enables it. Without config MSW bit 7
// the same bit raised before the switch changes nothing: H-A (stop past the switch, 2-s pauses,
// creep back onto its edge), and it is still echoed (LSW-01).
TEST_F(Homing3602, AH_01_ProximityBitIgnoredWhenNotConfigured) {
  configure(kAxis1);
  command(kAxis1, cmd::kFindHomeCw, kHome);
  ASSERT_TRUE(vm_.run_until_true([this] { return motor(kAxis1) >= 1'000; }, kLimit));
  set_proximity(kAxis1, true);
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kProximityEcho));
  ASSERT_TRUE(wait_homed(kAxis1));
  EXPECT_EQ(position(kAxis1), 0);
  EXPECT_EQ(gaps(kAxis1, 2 * kNsPerSec), 2u);  // H-A's two pauses
  EXPECT_GE(motor(kAxis1), 5'000);
  EXPECT_LE(motor(kAxis1), 5'001);
}

// ---- Find Home refused at the start: the error bits, and no step --------------------------------

struct RefusedHoming {
  const char* name;
  std::uint16_t config = kLimitsConfigMsw;
  Move3602 words = kHome;
  std::vector<std::uint16_t> set{};  // status MSW bits set after the command
};

const RefusedHoming kRefusedHomings[] = {
    {.name = "CE_12_FindHomeWithoutTheHomeInputEnabled",
     .config = static_cast<std::uint16_t>(kLimitsConfigMsw & ~m2::cfg_msw::kHomeEnabled),
     .set = {kCommandError}},
    {.name = "HI_04_FindHomeWithNonZeroReservedWords",
     .words = {.target = 1, .speed = 10'000, .accel = 20, .decel = 20},
     .set = {kHomeInvalid, kCommandError}},
    {.name = "HI_01_FindHomeWithVpBelowVs",
     .words = {.target = 0, .speed = 999, .accel = 20, .decel = 20},
     .set = {kHomeInvalid}},
    {.name = "CE_11_HI_02_FindHomeWithSCurve",
     .words = {.target = 0, .speed = 10'000, .accel = 20, .decel = 20, .lsw = m2::cmd_lsw::kSCurve},
     .set = {kCommandError, kHomeInvalid}},
    {.name = "HI_03_FindHomeWithAccelOutOfRange",
     .words = {.target = 0, .speed = 10'000, .accel = 2'001, .decel = 20},
     .set = {kHomeInvalid}},
};

class RefusedHoming3602 : public Homing3602, public ::testing::WithParamInterface<RefusedHoming> {};

TEST_P(RefusedHoming3602, NoStep) {
  const RefusedHoming& r = GetParam();
  configure(kAxis1, r.config);
  command(kAxis1, cmd::kFindHomeCw, r.words);
  for (const std::uint16_t bit : r.set) EXPECT_TRUE(status(kAxis1, bit)) << "status bit " << bit;
  vm_.run_for(200 * kNsPerMs);
  EXPECT_EQ(motor(kAxis1), 0);
}

INSTANTIATE_TEST_SUITE_P(Items, RefusedHoming3602, ::testing::ValuesIn(kRefusedHomings), RowName{});

}  // namespace
}  // namespace stepmod::testing
