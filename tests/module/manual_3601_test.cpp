// 3601 manual moves, registration moves and the minimum registration distance in virtual time
// (3601 manual Ch.4 "Manual Move", "Registration Move"; the 3601 checklist). Each checklist item
// is named in its test's name.
#include <algorithm>
#include <cmath>

#include "tests/module/plc_3601.hpp"

namespace stepmod::testing {
namespace {

using namespace m::status_msw;
namespace cmd = m::cmd_msw;

class Manual3601 : public Plc3601 {
 protected:
  void SetUp() override {
    configure();
    command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
    ASSERT_FALSE(status(kPositionInvalid));
  }
  // A manual / registration move: the bit stays set (level) until the test clears it.
  void start(std::uint16_t bit, const Move& p) {
    set_words(bit, p.lsw, p.target, p.speed, p.accel, p.decel);
  }
  // Program Minimum Registration Move Distance: MSW 0, LSW bit 10 rising, words 2-3.
  void program_dmin(std::int32_t d, std::int32_t w45 = 0, std::int16_t w6 = 0, std::int16_t w7 = 0,
                    std::uint16_t lsw = m::cmd_lsw::kStoreMinRegistration) {
    set_words(0, lsw, d, w45, w6, w7);
    vm_.scans(3);
    word(1) = 0;
    vm_.scans(1);
  }
  void reset_errors() {
    set_words(0, 0, 0, 0, 0, 0);
    vm_.scans(2);
    command(cmd::kResetErrors, {.speed = 0, .accel = 0, .decel = 0});
    ASSERT_FALSE(status(kCommandError));
  }
  std::size_t steps_after(Nanos t) const {
    const auto& s = vm_.step_times(0);
    return static_cast<std::size_t>(s.end() - std::upper_bound(s.begin(), s.end(), t));
  }
  // Mean step period (ns) of the steps in (t - window, t].
  double period_before(Nanos t, Nanos window = 50 * kNsPerMs) const {
    const auto& s = vm_.step_times(0);
    const auto lo = std::upper_bound(s.begin(), s.end(), t - window);
    const auto hi = std::upper_bound(s.begin(), s.end(), t);
    if (hi - lo < 2) return 0;
    return static_cast<double>(*(hi - 1) - *lo) / static_cast<double>(hi - lo - 1);
  }
  // Changes words while moving, lets the module scan once; returns the scan's time.
  Nanos scan_once() {
    vm_.scans(1);
    return vm_.now();
  }
  bool errors() const {
    return status(kCommandError) || status(kInvalidProfile) || status(kInputError) ||
           status(kHomeInvalid);
  }
  // An invalid runtime change: CE + IP, the pulses stop at once (A10), no PI (3601 PI list).
  void expect_error_stop(Nanos change_scan) {
    ASSERT_TRUE(wait_idle(20 * kNsPerMs));
    EXPECT_TRUE(status(kCommandError));
    EXPECT_TRUE(status(kInvalidProfile));
    EXPECT_FALSE(status(kPositionInvalid));
    EXPECT_LE(steps_after(change_scan), 1u);  // a controlled stop from 10,000 takes 4,950 steps
    EXPECT_EQ(position(), motor());
  }
};

constexpr Move kRamped{.target = 0, .speed = 10'000, .accel = 10, .decel = 10};
constexpr Nanos kAtSpeed = 1'200 * kNsPerMs;  // 1,000 -> 10,000 at 10 steps/ms/s takes 0.9 s

// ---- Manual move: runtime changes ----------------------------------------------------------

TEST_F(Manual3601, CE_17_IP_09_SpeedChangeInConstantSpeedModeStops) {
  start(cmd::kManualCw, {.speed = 800});  // Vp 800 <= Vs 1,000: constant-speed mode
  vm_.run_for(300 * kNsPerMs);
  ASSERT_TRUE(moving());
  EXPECT_FALSE(errors());
  word(5) = 700;  // lower (a raise is refused too, below)
  const Nanos t = scan_once();
  ASSERT_TRUE(wait_idle(20 * kNsPerMs));
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));  // 3601-IP-09
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_LE(steps_after(t), 1u);
  reset_errors();
  start(cmd::kManualCcw, {.speed = 1'000});  // Vp = Vs is constant-speed mode too
  vm_.run_for(300 * kNsPerMs);
  word(5) = 500;  // 1,500: a raise
  vm_.scans(2);
  ASSERT_TRUE(wait_idle(20 * kNsPerMs));
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));
}

TEST_F(Manual3601, CE_19_IP_10_InvalidSpeedOrRateChangeStopsImmediately) {
  struct Case {
    const char* what;
    std::int32_t w4, w5, w6, w7;
  };
  const Case cases[] = {
      {"speed above 1,000,000", 1'000, 1, 10, 10},
      {"speed LSW outside 0..999", 5, 1'000, 10, 10},
      {"negative speed MSW", -5, 0, 10, 10},
      {"accel 0", 5, 0, 0, 10},
      {"accel 2001", 5, 0, 2'001, 10},
      {"decel 0", 5, 0, 10, 0},
      {"decel 2001", 5, 0, 10, 2'001},
      {"speed 0 (A13)", 0, 0, 10, 10},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    start(cmd::kManualCw, kRamped);
    vm_.run_for(kAtSpeed);
    ASSERT_TRUE(moving());
    ASSERT_FALSE(errors());
    word(4) = c.w4;
    word(5) = c.w5;
    word(6) = c.w6;
    word(7) = c.w7;
    expect_error_stop(scan_once());
    reset_errors();
  }
}

TEST_F(Manual3601, CE_19_AccelDecelChangesAloneAreNotLookedAt) {
  start(cmd::kManualCw, kRamped);
  vm_.run_for(kAtSpeed);
  word(6) = 0;  // invalid, but the speed did not change
  word(7) = 5'000;
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(moving());
  EXPECT_FALSE(errors());
  word(5) = 500;  // 10,500: now both must be valid
  expect_error_stop(scan_once());
}

TEST_F(Manual3601, A13_SpeedChangedToZeroIsInvalid) {
  start(cmd::kManualCcw, kRamped);
  vm_.run_for(kAtSpeed);
  word(4) = 0;
  word(5) = 0;
  expect_error_stop(scan_once());
  EXPECT_TRUE(status(kStopped));  // the manual move has ended
}

TEST_F(Manual3601, CE_30_IP_15_TargetWrittenIntoAPlainManualMove) {
  start(cmd::kManualCw, kRamped);
  vm_.run_for(kAtSpeed);
  word(3) = 100;
  expect_error_stop(scan_once());
}

TEST_F(Manual3601, SpeedChangeUpAndDownRampsToTheNewSpeed) {
  start(cmd::kManualCw, {.speed = 5'000, .accel = 20, .decel = 20});
  vm_.run_for(500 * kNsPerMs);
  EXPECT_NEAR(period_before(vm_.now()), 200'000.0, 500.0);  // 5,000 steps/s
  word(4) = 12;                                             // 12,000 steps/s with the new accel 40
  word(5) = 0;
  word(6) = 40;
  const Nanos up = scan_once();
  vm_.run_for(30 * kNsPerMs);
  const double ramping = period_before(vm_.now(), 20 * kNsPerMs);
  EXPECT_LT(ramping, 200'000.0);
  EXPECT_GT(ramping, 1e9 / 12'000.0);
  vm_.run_for(400 * kNsPerMs);  // 7,000 / 40,000 = 0.175 s of ramp
  EXPECT_NEAR(period_before(vm_.now()), 1e9 / 12'000.0, 300.0);
  word(4) = 2;  // down to 2,000 with decel 20: 0.5 s
  vm_.scans(1);
  vm_.run_for(700 * kNsPerMs);
  EXPECT_NEAR(period_before(vm_.now()), 500'000.0, 1'000.0);
  EXPECT_TRUE(moving());
  EXPECT_FALSE(errors());
  // The new accel was used: 0.175 s of ramp, not 0.35 s with the old 20.
  EXPECT_NEAR(period_before(up + 260 * kNsPerMs), 1e9 / 12'000.0, 300.0);
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kStopped));
  EXPECT_EQ(position(), motor());
}

TEST_F(Manual3601, SpeedChangeBelowStartingSpeed) {
  start(cmd::kManualCcw, {.speed = 4'000, .accel = 10, .decel = 10});
  vm_.run_for(500 * kNsPerMs);
  word(4) = 0;
  word(5) = 400;  // below Vs = 1,000: legal for a manual move started in ramped mode
  vm_.scans(1);
  vm_.run_for(800 * kNsPerMs);
  EXPECT_NEAR(period_before(vm_.now(), 200 * kNsPerMs), 2.5e6, 5e3);
  EXPECT_FALSE(errors());
  EXPECT_TRUE(status(kMovingCcw));
  word(0) = 0;
  ASSERT_TRUE(wait_idle(50 * kNsPerMs));
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(errors());
}

// ---- Manual move: direction, stopping ------------------------------------------------------

TEST_F(Manual3601, DIR_01_OneShotDirectionBitStaysOnWhileTheBitIsHeld) {
  start(cmd::kManualCcw, {.speed = 0});
  vm_.run_for(300 * kNsPerMs);
  EXPECT_EQ(motor(), -1);
  EXPECT_TRUE(status(kMovingCcw));  // the pulse is long gone
  EXPECT_FALSE(status(kMovingCw));
  word(0) = 0;
  vm_.scans(2);
  EXPECT_FALSE(status(kMovingCcw));
  EXPECT_FALSE(status(kStopped));  // 3601-STP-N1
  // Direction bits of a running manual move follow its direction.
  start(cmd::kManualCw, {.speed = 3'000});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kMovingCw));
  EXPECT_FALSE(status(kMovingCcw));
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
}

TEST_F(Manual3601, STP_N1_OneShotReleaseSetsNoStopped) {
  start(cmd::kManualCw, {.speed = 0});
  vm_.scans(1);
  word(0) = 0;  // released while its single pulse is under way
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 1);
  EXPECT_FALSE(status(kStopped));
  EXPECT_FALSE(moving());
  start(cmd::kManualCw, {.speed = 0});  // a new 0 -> 1 edge: one more pulse
  vm_.run_for(100 * kNsPerMs);
  word(0) = 0;
  vm_.scans(3);
  EXPECT_EQ(motor(), 2);
  EXPECT_FALSE(status(kStopped));
  EXPECT_FALSE(errors());
}

TEST_F(Manual3601, STP_01_ReleaseStopsControlledToStopped) {
  start(cmd::kManualCw, kRamped);
  vm_.run_for(kAtSpeed);
  word(0) = 0;
  const Nanos t = scan_once();
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_FALSE(errors());
  EXPECT_NEAR(static_cast<double>(steps_after(t)), 4'950.0, 60.0);  // decel 10 to Vs
}

TEST_F(Manual3601, STP_01_ExternalInputStopsControlledToStopped) {
  start(cmd::kManualCcw, kRamped);
  vm_.run_for(kAtSpeed);
  const Nanos t = vm_.now();
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kHoldState));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_NEAR(static_cast<double>(steps_after(t)), 4'950.0, 60.0);
  EXPECT_TRUE(status(kStopped));
}

TEST_F(Manual3601, STP_01_ExternalActiveAtTheStartGivesOneStepThenStopped) {
  force(InputLine::kExternal, true);
  vm_.scans(2);
  start(cmd::kManualCcw, kRamped);  // 3601 manual ch. 6: one step, then stop
  vm_.run_for(200 * kNsPerMs);
  EXPECT_EQ(motor(), -1);
  EXPECT_FALSE(moving());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(errors());
  word(0) = 0;
  vm_.scans(2);
  EXPECT_EQ(motor(), -1);
}

TEST_F(Manual3601, A11_ZeroingAllEightWordsIsNoError) {
  start(cmd::kManualCw, kRamped);
  vm_.run_for(kAtSpeed);
  set_words(0, 0, 0, 0, 0, 0);  // all eight words, not only the command word
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(errors());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kPositionInvalid));
  // The same for a registration move: the words' change is not CE-31, the release triggers.
  start(cmd::kManualCw, {.target = 6'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(kAtSpeed);
  set_words(0, 0, 0, 0, 0, 0);
  const Nanos t = scan_once();
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(errors());
  EXPECT_EQ(steps_after(t), 6'000u);
  EXPECT_TRUE(status(kStopped));
}

TEST_F(Manual3601, CE_16_CE_18_IP_08_OldFirmwareErrorsAreNotEmulated) {
  // CE-16 / IP-08 (firmware below 3.1): a manual move with a non-zero target was an error. The
  // emulated firmware (4.1, A3) runs it as a registration move: no CE, no IP.
  start(cmd::kManualCw, {.target = 7'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(kAtSpeed);
  EXPECT_TRUE(moving());
  EXPECT_FALSE(status(kCommandError));
  EXPECT_FALSE(status(kInvalidProfile));
  // CE-18 (A11): stopping it by zeroing all eight words is not an error either.
  set_words(0, 0, 0, 0, 0, 0);
  const Nanos t = scan_once();
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(steps_after(t), 7'000u);  // the registration count, not a 4,950-step stop
  EXPECT_FALSE(errors());
}

TEST_F(Manual3601, A43_HoldDuringAManualMoveIsCeAndAControlledStop) {
  start(cmd::kManualCw, kRamped);
  vm_.run_for(kAtSpeed);
  word(0) = static_cast<std::int16_t>(cmd::kHold);
  const Nanos t = scan_once();
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_NEAR(static_cast<double>(steps_after(t)), 4'950.0, 60.0);
}

// ---- Minimum registration distance ---------------------------------------------------------

TEST_F(Manual3601, CE_25_MinRegistrationDistanceOutOfRange) {
  program_dmin(1'234);
  ASSERT_FALSE(status(kCommandError));
  ASSERT_TRUE(lsw_status(m::status_lsw::kMinRegistrationSet));
  program_dmin(-5);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(lsw_status(m::status_lsw::kMinRegistrationSet));  // value kept
  reset_errors();
  // 8,388,608 is one above the range.
  set_words(0, m::cmd_lsw::kStoreMinRegistration, 0, 0, 0, 0);
  word(2) = 8'388;
  word(3) = 608;
  vm_.scans(3);
  word(1) = 0;
  vm_.scans(1);
  EXPECT_TRUE(status(kCommandError));
  reset_errors();
  // An LSW outside 0..999 is out of range too.
  set_words(0, m::cmd_lsw::kStoreMinRegistration, 0, 0, 0, 0);
  word(2) = 1;
  word(3) = 1'000;
  vm_.scans(3);
  word(1) = 0;
  vm_.scans(1);
  EXPECT_TRUE(status(kCommandError));
  reset_errors();
  program_dmin(8'388'607);  // the top of the range is accepted
  EXPECT_FALSE(status(kCommandError));
  EXPECT_TRUE(lsw_status(m::status_lsw::kMinRegistrationSet));
}

TEST_F(Manual3601, CE_25_MinRegistrationNeedsZeroWordsAndOnlyBit10) {
  program_dmin(100, /*w45=*/1);
  EXPECT_TRUE(status(kCommandError));
  reset_errors();
  program_dmin(100, 0, /*w6=*/1);
  EXPECT_TRUE(status(kCommandError));
  reset_errors();
  program_dmin(100, 0, 0, /*w7=*/1);
  EXPECT_TRUE(status(kCommandError));
  reset_errors();
  program_dmin(100, 0, 0, 0, m::cmd_lsw::kStoreMinRegistration | m::cmd_lsw::kSCurve);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(lsw_status(m::status_lsw::kMinRegistrationSet));
  reset_errors();
  program_dmin(100);
  EXPECT_FALSE(status(kCommandError));
  EXPECT_TRUE(lsw_status(m::status_lsw::kMinRegistrationSet));
}

TEST_F(Manual3601, LSW_01_MinRegistrationStatusBitAndClearedByConfiguration) {
  EXPECT_FALSE(lsw_status(m::status_lsw::kMinRegistrationSet));  // power-up: 0
  program_dmin(500);
  EXPECT_TRUE(lsw_status(m::status_lsw::kMinRegistrationSet));
  program_dmin(0);  // 0 disables it
  EXPECT_FALSE(lsw_status(m::status_lsw::kMinRegistrationSet));
  program_dmin(500);
  ASSERT_TRUE(lsw_status(m::status_lsw::kMinRegistrationSet));
  configure();  // every configuration resets it
  EXPECT_FALSE(lsw_status(m::status_lsw::kMinRegistrationSet));
  // ... and the registration move then honours the first trigger (no minimum distance).
  command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  start(cmd::kManualCw, {.target = 2'000, .speed = 2'000, .accel = 10, .decel = 10});
  vm_.run_for(50 * kNsPerMs);
  const Nanos t = vm_.now();
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(steps_after(t), 2'000u);
}

// ---- Registration move: start checks -------------------------------------------------------

TEST_F(Manual3601, CE_27_IP_12_RegistrationStartedWithExternalActive) {
  program_dmin(1'000);  // even with a minimum distance
  force(InputLine::kExternal, true);
  vm_.scans(2);
  start(cmd::kManualCw, {.target = 6'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_FALSE(moving());
  EXPECT_EQ(motor(), 0);
}

TEST_F(Manual3601, CE_28_IP_13_RegistrationCountShorterThanTheDeceleration) {
  // Registration (3601 manual ch. 4), worked: Vs 1,000, Vp 10,000, decel 10 -> 4,950 steps to stop.
  start(cmd::kManualCw, {.target = 4'949, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_FALSE(moving());
  EXPECT_EQ(motor(), 0);
  reset_errors();
  start(cmd::kManualCw, {.target = 4'950, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(kAtSpeed);
  EXPECT_TRUE(moving());
  EXPECT_FALSE(errors());
  word(0) = 0;
  const Nanos t = scan_once();
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(steps_after(t), 4'950u);
  reset_errors();
  // Triangular S doubles the requirement to 9,900.
  const auto tri = m::cmd_lsw::kSCurve;
  start(cmd::kManualCw, {.target = 9'899, .speed = 10'000, .accel = 10, .decel = 10, .lsw = tri});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_FALSE(moving());
  reset_errors();
  start(cmd::kManualCw, {.target = 9'900, .speed = 10'000, .accel = 10, .decel = 10, .lsw = tri});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(moving());
  EXPECT_FALSE(errors());
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
  // Constant-speed mode needs no deceleration: any count is accepted.
  start(cmd::kManualCcw, {.target = 3, .speed = 800, .accel = 10, .decel = 10});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(moving());
  EXPECT_FALSE(errors());
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
}

TEST_F(Manual3601, CE_29_IP_14_NegativeRegistrationCount) {
  start(cmd::kManualCw, {.target = -100, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_FALSE(moving());
  EXPECT_EQ(motor(), 0);
}

TEST_F(Manual3601, CE_04_RegistrationCountAboveTheTargetRange) {
  start(cmd::kManualCw, {.target = 0, .speed = 10'000, .accel = 10, .decel = 10});
  word(2) = 8'388;
  word(3) = 608;  // 8,388,608
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_EQ(motor(), 0);
}

TEST_F(Manual3601, RegistrationWithSpeedZeroIsRefused) {
  // Inferred: a one-shot (Vp = 0) cannot be a registration move; refused rather than the count
  // silently ignored.
  start(cmd::kManualCw, {.target = 500, .speed = 0, .accel = 10, .decel = 10});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_TRUE(status(kInvalidProfile));
  EXPECT_EQ(motor(), 0);
}

// ---- Registration move: runtime changes ----------------------------------------------------

constexpr Move kRegistration{.target = 20'000, .speed = 10'000, .accel = 10, .decel = 10};

TEST_F(Manual3601, CE_31_IP_16_RegistrationCountChangedWhileRunning) {
  start(cmd::kManualCw, kRegistration);
  vm_.run_for(kAtSpeed);
  word(2) = 25;  // 25,000
  expect_error_stop(scan_once());
}

TEST_F(Manual3601, CE_32_IP_17_RegistrationSpeedRaised) {
  start(cmd::kManualCw, kRegistration);
  vm_.run_for(kAtSpeed);
  word(4) = 12;
  expect_error_stop(scan_once());
}

TEST_F(Manual3601, CE_32_RegistrationSpeedMayBeLoweredBeforeTheTrigger) {
  start(cmd::kManualCcw, kRegistration);
  vm_.run_for(kAtSpeed);
  word(4) = 4;  // 4,000
  vm_.scans(1);
  vm_.run_for(800 * kNsPerMs);
  EXPECT_NEAR(period_before(vm_.now()), 250'000.0, 500.0);
  EXPECT_FALSE(errors());
  const Nanos t = vm_.now();
  force(InputLine::kExternal, true);
  vm_.run_for(10 * kNsPerMs);
  word(4) = 9;  // after the trigger speed changes are ignored (even a raise)
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(errors());
  EXPECT_EQ(steps_after(t), 20'000u);
  EXPECT_TRUE(status(kStopped));
  EXPECT_EQ(position(), motor());
}

TEST_F(Manual3601, CE_33_IP_18_RegistrationRatesChangedWithTheSpeed) {
  start(cmd::kManualCw, kRegistration);
  vm_.run_for(kAtSpeed);
  word(6) = 20;  // alone: not checked
  vm_.run_for(100 * kNsPerMs);
  EXPECT_TRUE(moving());
  EXPECT_FALSE(errors());
  word(4) = 8;  // a legal decrease, but accel differs from the start's
  expect_error_stop(scan_once());
}

TEST_F(Manual3601, CE_33_DecelChangedWithTheSpeed) {
  start(cmd::kManualCw, kRegistration);
  vm_.run_for(kAtSpeed);
  word(4) = 8;
  word(7) = 11;
  expect_error_stop(scan_once());
}

TEST_F(Manual3601, CE_26_HoldBeforeTheTriggerIsAPlainControlledStop) {
  program_dmin(1'000);
  start(cmd::kManualCw, kRegistration);
  vm_.run_for(kAtSpeed);
  word(0) = static_cast<std::int16_t>(cmd::kHold);  // the Hold bit replaces the manual bit
  const Nanos t = scan_once();
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kInvalidProfile));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_FALSE(status(kHoldState));
  // A45: decel 10 from 10,000 (4,950 steps), not the registration count (20,000).
  EXPECT_NEAR(static_cast<double>(steps_after(t)), 4'950.0, 60.0);
  EXPECT_TRUE(status(kStopped));
}

// ---- Registration move: trigger and count --------------------------------------------------

TEST_F(Manual3601, Registration_ExactlyRStepsAfterTheExternalEdge) {
  start(cmd::kManualCw, {.target = 6'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(kAtSpeed);
  const Nanos t = vm_.now();
  const std::int64_t before = motor();
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(steps_after(t), 6'000u);
  EXPECT_EQ(motor(), before + 6'000);
  EXPECT_EQ(position(), motor());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kMoveComplete));  // 3601-MC-02
  EXPECT_FALSE(errors());
  // The count includes the deceleration: the last steps are at about Vs.
  EXPECT_NEAR(period_before(vm_.step_times(0).back(), 3 * kNsPerMs), 1e6, 1e5);
}

// An External edge stamped while an earlier move still ran, delivered only after the registration
// move started (a loaded control thread): it triggers the registration at its start, and the
// earlier move's steps after the edge are not counted as this move's.
TEST_F(Manual3601, Registration_EdgeStampedBeforeTheMoveStartedCountsFromTheStart) {
  command(cmd::kRelativeMove, {.target = 2'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(100 * kNsPerMs);
  ASSERT_TRUE(moving());
  const Nanos edge = vm_.now();  // the earlier move has steps to go
  ASSERT_TRUE(wait_idle());
  const std::int64_t after_edge = static_cast<std::int64_t>(steps_after(edge));
  ASSERT_GT(after_edge, 100);
  set_words(0, 0, 0, 0, 0, 0);
  vm_.scans(2);
  const std::int64_t before = motor();
  start(cmd::kManualCw, {.target = 6'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.scans(2);
  ASSERT_TRUE(moving());
  vm_.sim().force(0, 1u << static_cast<unsigned>(InputLine::kExternal),
                  1u << static_cast<unsigned>(InputLine::kExternal), edge);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), before + 6'000) << "the earlier move's " << after_edge << " steps";
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(errors());
}

// At constant speed (Vp <= Vs) no steps are needed to stop, so any count >= 1 is legal, and the
// planner has already queued a lookahead's worth of steps (4 ms = 40 at 10,000 steps/s) when
// the trigger comes: the pulse thread's step-count cap keeps the count exact anyway.
TEST_F(Manual3601, Registration_SmallCountAtConstantSpeedIsExact) {
  configure(kFullConfigMsw, kAllActiveHigh, 10'000);  // Vs = 10,000 steps/s
  command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  start(cmd::kManualCw, {.target = 3, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(200 * kNsPerMs);
  const Nanos t = vm_.now();
  const std::int64_t before = motor();
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(steps_after(t), 3u);
  EXPECT_EQ(motor(), before + 3);
  EXPECT_EQ(position(), motor());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(errors());
}

TEST_F(Manual3601, Registration_TriggerByReleasingTheBit) {
  start(cmd::kManualCcw, {.target = 8'000, .speed = 10'000, .accel = 10, .decel = 20});
  vm_.run_for(kAtSpeed);
  const std::int64_t before = motor();
  word(0) = 0;
  const Nanos t = scan_once();  // the scan that sees the bit reset
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(steps_after(t), 8'000u);
  EXPECT_LT(motor(), before - 7'990);
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(errors());
}

TEST_F(Manual3601, Registration_MinDistanceIgnoresEarlierTriggers) {
  program_dmin(20'000);
  start(cmd::kManualCw, {.target = 5'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(500 * kNsPerMs);
  ASSERT_LT(motor(), 20'000);
  force(InputLine::kExternal, true);  // a pulse of the External input inside Dmin
  vm_.run_for(20 * kNsPerMs);
  force(InputLine::kExternal, false);
  vm_.run_for(2'500 * kNsPerMs);
  ASSERT_GT(motor(), 20'000);  // passed Dmin with no trigger present: still running
  EXPECT_TRUE(moving());
  const Nanos t = vm_.now();
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(steps_after(t), 5'000u);
  EXPECT_FALSE(errors());
}

TEST_F(Manual3601, Registration_TriggerAlreadyPresentWhenMinDistanceIsPassed) {
  program_dmin(15'000);
  start(cmd::kManualCw, {.target = 5'000, .speed = 10'000, .accel = 10, .decel = 10});
  vm_.run_for(300 * kNsPerMs);
  force(InputLine::kExternal, true);  // level: stays active past Dmin
  ASSERT_TRUE(wait_idle());
  // Honoured at step Dmin + 1 (A42: steps > Dmin), then exactly R steps.
  EXPECT_EQ(motor(), 15'000 + 1 + 5'000);
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(errors());
}

TEST_F(Manual3601, A42_TriggerHonouredOnceStepsExceedMinDistance) {
  // Release before Dmin: the trigger counts from step Dmin + 1, not from step Dmin. Odd speeds
  // and a CCW move so that no step time coincides with a scan.
  program_dmin(12'345);
  start(cmd::kManualCcw, {.target = 4'321, .speed = 7'777, .accel = 13, .decel = 7});
  vm_.run_for(400 * kNsPerMs);
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), -(12'345 + 1 + 4'321));
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(errors());
}

TEST_F(Manual3601, IE_02_RegistrationStopsAtTheLimitOfItsDirectionOnly) {
  force(InputLine::kCcwLimit, true);  // opposite limit: ignored
  vm_.scans(2);
  start(cmd::kManualCw, {.target = 20'000, .speed = 50'000, .accel = 100, .decel = 100});
  ASSERT_TRUE(vm_.run_until_true([this] { return !moving(); }, 5 * kNsPerSec));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kStopped));
  EXPECT_GE(motor(), 100'000);
  EXPECT_LT(motor(), 100'100);
}

}  // namespace
}  // namespace stepmod::testing
