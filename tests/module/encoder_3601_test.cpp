// 3601 encoder functions in virtual time: preset encoder, encoder moves, diagnostic feedback and
// the encoder follower (3601 manual Ch.4); the 3601 checklist items are named in the test
// names.
#include <cmath>

#include "tests/module/plc_3601.hpp"
#include "tests/support/checklist_rows.hpp"

namespace stepmod::testing {
namespace {

using namespace m::status_msw;
namespace cmd = m::cmd_msw;
namespace lsw = m::cmd_lsw;

constexpr Nanos kMs = kNsPerMs;
constexpr std::uint16_t kNoEncoderConfig = m::cfg_msw::kHomeUsed | m::cfg_msw::kCwLimitUsed |
                                           m::cfg_msw::kCcwLimitUsed | m::cfg_msw::kEStopUsed |
                                           m::cfg_msw::kExternalUsed | m::cfg_msw::kStepDirOutput;
// Deceleration distance of the encoder-move profile below: 10,000 -> Vs 1,000 steps/s at
// 10 steps/ms/s = (10,000^2 - 1,000^2) / (2 x 10,000) steps.
constexpr std::int64_t kDecelDistance = 4'950;
// The stop reaches the planner a scan and a lookahead (4 ms) after the count: at 10,000 steps/s
// a few tens of steps more.
constexpr std::int64_t kLateSteps = 120;

const Move kEncoderMove{
    .target = 0, .speed = 10'000, .accel = 10, .decel = 10, .lsw = lsw::kEncoderMove};
Move encoder_move(std::int32_t target) {
  Move mv = kEncoderMove;
  mv.target = target;
  return mv;
}
const Move kPresetWords{.target = 0, .speed = 0, .accel = 0, .decel = 0};
Move preset(std::int32_t value) {
  Move mv = kPresetWords;
  mv.target = value;
  return mv;
}

class Encoder3601 : public Plc3601 {
 protected:
  explicit Encoder3601(VirtualMachineOptions o = default_3601()) : Plc3601(std::move(o)) {}
  void SetUp() override { configure(); }
  bool errors() const {
    return status(kCommandError) || status(kInvalidProfile) || status(kInputError);
  }
};

// ---- Preset Encoder
// ------------------------------------------------------------------------------

TEST_F(Encoder3601, PresetEncoderSetsTheCountOnly) {
  command(cmd::kRelativeMove, {.target = 500});
  ASSERT_TRUE(wait_idle());
  ASSERT_TRUE(status(kMoveComplete));
  command(cmd::kPresetEncoder, preset(-123'456));
  EXPECT_FALSE(status(kCommandError));
  EXPECT_EQ(encoder(), -123'456);
  EXPECT_EQ(position(), 500);             // position untouched
  EXPECT_TRUE(status(kMoveComplete));     // MC untouched
  EXPECT_TRUE(status(kPositionInvalid));  // PI untouched (still from the configuration)
  command(cmd::kRelativeMove, {.target = 100});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(encoder(), -123'356);  // keeps counting from the preset value
}

TEST_F(Encoder3601, CE_09_PresetEncoderWithNonZeroSpeedAccelOrDecel) {
  command(cmd::kPresetEncoder, {.target = 10, .speed = 1, .accel = 0, .decel = 0});
  EXPECT_TRUE(status(kCommandError));
  command(cmd::kResetErrors);
  command(cmd::kPresetEncoder, {.target = 10, .speed = 0, .accel = 1, .decel = 0});
  EXPECT_TRUE(status(kCommandError));
  command(cmd::kResetErrors);
  command(cmd::kPresetEncoder, {.target = 10, .speed = 0, .accel = 0, .decel = 1});
  EXPECT_TRUE(status(kCommandError));
  EXPECT_EQ(encoder(), 0);
  command(cmd::kResetErrors);
  command(cmd::kPresetEncoder, preset(10));
  EXPECT_FALSE(status(kCommandError));
  EXPECT_EQ(encoder(), 10);
}

TEST_F(Encoder3601, CE_11_PresetEncoderWithoutEncoderConfigured) {
  configure(kNoEncoderConfig);
  command(cmd::kPresetEncoder, preset(10));
  EXPECT_TRUE(status(kCommandError));
  EXPECT_EQ(encoder(), 0);
}

TEST_F(Encoder3601, CE_15_PresetEncoderNeedsAZeroLsw) {
  Move p = preset(10);
  p.lsw = lsw::kEncoderMove;
  command(cmd::kPresetEncoder, p);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_EQ(encoder(), 0);
}

TEST_F(Encoder3601, CE_04_PresetEncoderValueOutOfRange) {
  set_words(cmd::kPresetEncoder, 0, 0, 0, 0, 0);
  word(2) = 8'389;  // 8,389,000: above 8,388,607
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_EQ(encoder(), 0);
}

// ---- Encoder move
// --------------------------------------------------------------------------------

// The manual: "When this encoder count is reached, the 3601 module will begin to decelerate ...
// It will overshoot the target position". The simulated encoder gives one count per step.
TEST_F(Encoder3601, MC_01_RelativeEncoderMoveCwOvershootsByTheDecelerationDistance) {
  command(cmd::kRelativeMove, encoder_move(20'000));
  EXPECT_TRUE(status(kMovingCw));
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kStopped));
  EXPECT_FALSE(errors());
  const std::int64_t over = encoder() - 20'000;
  EXPECT_GE(over, kDecelDistance - 5);
  EXPECT_LE(over, kDecelDistance + kLateSteps);
  EXPECT_EQ(position(), motor());
  EXPECT_EQ(encoder(), motor());
}

TEST_F(Encoder3601, MC_01_RelativeEncoderMoveCcwOvershootsByTheDecelerationDistance) {
  command(cmd::kRelativeMove, encoder_move(-20'000));
  EXPECT_TRUE(status(kMovingCcw));
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kMoveComplete));
  const std::int64_t over = -20'000 - encoder();
  EXPECT_GE(over, kDecelDistance - 5);
  EXPECT_LE(over, kDecelDistance + kLateSteps);
}

// Absolute: compared with the encoder count (here preset away from the position), and no valid
// position needed (PI is still set from the configuration).
TEST_F(Encoder3601, MC_01_AbsoluteEncoderMoveComparesWithTheEncoderCountBothWays) {
  command(cmd::kPresetEncoder, preset(10'000));
  ASSERT_TRUE(status(kPositionInvalid));
  command(cmd::kAbsoluteMove, encoder_move(30'000));
  EXPECT_FALSE(status(kCommandError));
  EXPECT_TRUE(status(kMovingCw));
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_GE(encoder(), 30'000 + kDecelDistance - 5);
  EXPECT_LE(encoder(), 30'000 + kDecelDistance + kLateSteps);
  EXPECT_EQ(motor(), encoder() - 10'000);

  // Target below the count: CCW, although the position (about 25,000) is above it too.
  command(cmd::kAbsoluteMove, encoder_move(20'000));
  EXPECT_TRUE(status(kMovingCcw));
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_LE(encoder(), 20'000 - kDecelDistance + 5);
  EXPECT_GE(encoder(), 20'000 - kDecelDistance - kLateSteps);
}

TEST_F(Encoder3601, MC_01_EncoderMoveAlreadyOnItsCountCompletesAtOnce) {
  command(cmd::kPresetEncoder, preset(700));
  command(cmd::kAbsoluteMove, encoder_move(700));
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_EQ(motor(), 0);
}

// Holding (A4) is ignored: no CE, no Hold, the move runs to its count and completes.
TEST_F(Encoder3601, A4_HoldDuringEncoderMoveIsIgnored) {
  command(cmd::kRelativeMove, encoder_move(20'000));
  vm_.run_for(300 * kMs);
  ASSERT_TRUE(moving());
  raw_command(cmd::kHold);
  EXPECT_FALSE(status(kCommandError));
  EXPECT_FALSE(status(kHoldState));
  EXPECT_TRUE(moving());
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_FALSE(status(kHoldState));
  EXPECT_GE(encoder(), 20'000 + kDecelDistance - 5);
}

// External input: a controlled stop, not to the Hold state; the move has not completed.
TEST_F(Encoder3601, ExternalInputStopsAnEncoderMoveWithoutHold) {
  command(cmd::kRelativeMove, encoder_move(50'000));
  vm_.run_for(1'500 * kMs);  // cruising at 10,000 steps/s
  ASSERT_TRUE(moving());
  const std::int64_t at = encoder();
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_FALSE(status(kHoldState));
  EXPECT_FALSE(status(kMoveComplete));
  EXPECT_FALSE(status(kInputError));
  // Controlled: it decelerated over about the deceleration distance, well short of the target.
  EXPECT_GE(encoder() - at, kDecelDistance - 5);
  EXPECT_LE(encoder() - at, kDecelDistance + kLateSteps);
  EXPECT_LT(encoder(), 50'000);
  release(InputLine::kExternal);
  // A Resume finds no Hold.
  command(cmd::kResume);
  EXPECT_TRUE(status(kCommandError));
}

// 3601 manual ch. 6 (inferred): External already active at the start → one step, then a stop (no
// Hold).
TEST_F(Encoder3601, ExternalActiveAtTheStartOfAnEncoderMoveGivesOneStep) {
  force(InputLine::kExternal, true);
  vm_.scans(2);
  command(cmd::kRelativeMove, encoder_move(-5'000));
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), -1);
  EXPECT_FALSE(status(kHoldState));
  EXPECT_FALSE(status(kMoveComplete));
}

// No encoder signal (stalled motor, simulated by encoder_ratio 0): the move never sees its count
// and runs on until an Immediate Stop.
class EncoderStall3601 : public Encoder3601 {
 protected:
  static VirtualMachineOptions stalled() {
    VirtualMachineOptions o = default_3601();
    o.axes[0].sim.encoder_ratio = 0.0;
    return o;
  }
  EncoderStall3601() : Encoder3601(stalled()) {}
};

TEST_F(EncoderStall3601, EncoderMoveWithoutEncoderSignalRunsUntilImmediateStop) {
  command(cmd::kRelativeMove, encoder_move(1'000));
  vm_.run_for(3'000 * kMs);
  EXPECT_TRUE(moving());
  EXPECT_EQ(encoder(), 0);
  EXPECT_GT(motor(), 20'000);  // far past 1,000 counts' worth of steps
  raw_command(cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(10 * kMs));
  EXPECT_TRUE(status(kStopped));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_FALSE(status(kMoveComplete));
}

TEST_F(EncoderStall3601, EncoderMoveWithoutEncoderSignalStopsOnEStop) {
  command(cmd::kRelativeMove, encoder_move(1'000));
  vm_.run_for(1'000 * kMs);
  ASSERT_TRUE(moving());
  force(InputLine::kEStop, true);
  ASSERT_TRUE(wait_idle(10 * kMs));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kStopped));
}

// 3601 manual ch. 4, encoder follower: clearing only the MSW is harmless (command() clears word 0
// only)...
TEST_F(Encoder3601, ClearingOnlyTheMswDuringAnEncoderMoveIsHarmless) {
  command(cmd::kRelativeMove, encoder_move(15'000));
  ASSERT_EQ(word(0), 0);
  ASSERT_EQ(word(1), lsw::kEncoderMove);
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kMoveComplete));
  EXPECT_LE(encoder(), 15'000 + kDecelDistance + kLateSteps);
}

// ... clearing MSW and LSW makes the move miss its count and keep going.
TEST_F(Encoder3601, ClearingMswAndLswDuringAnEncoderMoveMissesTheTarget) {
  command(cmd::kRelativeMove, encoder_move(15'000));
  word(1) = 0;
  vm_.run_for(4'000 * kMs);
  EXPECT_TRUE(moving());
  EXPECT_GT(encoder(), 30'000);
  raw_command(cmd::kImmediateStop);
  ASSERT_TRUE(wait_idle(10 * kMs));
  EXPECT_FALSE(status(kMoveComplete));
}

// 3601 manual ch. 4: an encoder move stops at either end limit, like an absolute/relative move.
TEST_F(Encoder3601, IE_02_EncoderMoveStopsAtEitherLimit) {
  command(cmd::kRelativeMove, encoder_move(50'000));
  vm_.run_for(500 * kMs);
  ASSERT_TRUE(moving());
  force(InputLine::kCcwLimit, true);  // the limit behind the axis
  ASSERT_TRUE(wait_idle(10 * kMs));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kStopped));
}

// ---- Diagnostic feedback ------------------------------------------------------------------------

TEST_F(Encoder3601, DiagnosticFeedbackCountsOwnPulsesAndPresetPositionPresetsIt) {
  configure(kNoEncoderConfig | m::cfg_msw::kDiagnosticFeedback);
  ASSERT_FALSE(status(kConfigurationError));
  command(cmd::kRelativeMove, {.target = 1'000});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(encoder(), 1'000);
  command(cmd::kRelativeMove, {.target = -300});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(encoder(), 700);  // direction from the direction line
  // Counts while moving, not only at the end.
  command(cmd::kRelativeMove, {.target = 30'000});
  vm_.run_for(500 * kMs);
  ASSERT_TRUE(moving());
  EXPECT_GT(encoder(), 1'000);
  EXPECT_EQ(encoder(), position());
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(encoder(), 30'700);
  command(cmd::kPresetPosition, preset(5'000));
  EXPECT_FALSE(status(kCommandError));
  EXPECT_EQ(position(), 5'000);
  EXPECT_EQ(encoder(), 5'000);
  command(cmd::kRelativeMove, {.target = 100});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(encoder(), 5'100);
}

TEST_F(Encoder3601, PresetPositionLeavesTheQuadratureEncoderCountAlone) {
  command(cmd::kPresetEncoder, preset(42));
  command(cmd::kPresetPosition, preset(5'000));
  EXPECT_EQ(position(), 5'000);
  EXPECT_EQ(encoder(), 42);
}

// ---- Encoder follower ---------------------------------------------------------------------------

// The simulated encoder does not follow the motor here (encoder_ratio 0): a master encoder is
// injected as A/B quadrature edges straight into the personality, as the input thread would.
class Follower3601 : public Encoder3601 {
 protected:
  static VirtualMachineOptions no_sim_encoder() {
    VirtualMachineOptions o = default_3601();
    o.axes[0].sim.encoder_ratio = 0.0;
    return o;
  }
  Follower3601() : Encoder3601(no_sim_encoder()) {}

  // One X4 count of the master (+1: A leads B), at the machine's present time.
  void count(int d) {
    // (A,B) in the + sense: 00 -> 10 -> 11 -> 01 -> 00.
    static constexpr bool kA[4] = {false, true, true, false};
    static constexpr bool kB[4] = {false, false, true, true};
    const unsigned next = (phase_ + (d > 0 ? 1u : 3u)) & 3u;
    module::InputEvent e;
    e.t = vm_.now();
    e.axis = 0;
    e.line = kA[next] != kA[phase_] ? InputLine::kEncA : InputLine::kEncB;
    e.level = e.line == InputLine::kEncA ? kA[next] : kB[next];
    phase_ = next;
    vm_.stack().personality().on_input(e);
  }
  // `n` counts (sign = sense) at `rate` counts/s.
  void master(std::int64_t n, double rate) {
    const Nanos start = vm_.now();
    const std::int64_t k = n < 0 ? -n : n;
    for (std::int64_t i = 1; i <= k; ++i) {
      vm_.run_until(start + static_cast<Nanos>(std::llround(static_cast<double>(i) * 1e9 / rate)));
      count(n < 0 ? -1 : 1);
    }
  }
  // Follower words: LSW bit 7, multiplier, divisor, accel, decel.
  void follower(std::uint16_t msw, std::int16_t mul = 1, std::int16_t div = 1,
                std::int16_t accel = 0, std::int16_t decel = 0,
                std::uint16_t l = lsw::kEncoderFollower) {
    port_.write_outputs(plc::m3601::follower_words(msw, mul, div, accel, decel, l));
  }
  bool follower_mode() const { return lsw_status(m::status_lsw::kFollowerMode); }
  // Master counts then a settling time for the follower.
  void settle(Nanos d = 50 * kMs) { vm_.run_for(d); }
  // 2,000 steps, the step rate never above what ramps of 1,000 steps/s^2 allow: the peak of a
  // 2,000-step triangle from 1,000 steps/s is sqrt(1,000^2 + 2,000 x 1,000) = 1,732 steps/s.
  void expect_2000_steps_within_the_ramps() {
    const auto& t = vm_.step_times(0);
    ASSERT_EQ(t.size(), 2'000u);
    Nanos shortest = t[1] - t[0];
    for (std::size_t i = 1; i < t.size(); ++i) shortest = std::min(shortest, t[i] - t[i - 1]);
    EXPECT_GT(shortest, static_cast<Nanos>(1e9 / 1'800.0));
    EXPECT_FALSE(errors());
  }

  unsigned phase_ = 0;
};

TEST_F(Follower3601, LSW_01_FollowerModeBit7WhileLswBit7IsSet) {
  EXPECT_FALSE(follower_mode());
  follower(0);
  vm_.scans(3);
  EXPECT_TRUE(follower_mode());
  EXPECT_FALSE(errors());
  master(100, 10'000);  // no direction bit: no output
  settle();
  EXPECT_EQ(motor(), 0);
  EXPECT_EQ(encoder(), 100);
  follower(cmd::kManualCw);
  vm_.scans(3);
  EXPECT_TRUE(follower_mode());
  follower(0);
  vm_.scans(3);
  EXPECT_TRUE(follower_mode());  // mode stays on while LSW bit 7 is set
  word(1) = 0;
  vm_.scans(3);
  EXPECT_FALSE(follower_mode());
}

TEST_F(Follower3601, STP_05_LeavingFollowerModeSetsStopped) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  ASSERT_TRUE(follower_mode());
  master(200, 20'000);
  settle();
  EXPECT_EQ(motor(), 200);
  EXPECT_FALSE(status(kStopped));  // 3601-STP-N1: not while in follower mode
  EXPECT_FALSE(status(kMoveComplete));
  follower(0);
  vm_.scans(2);
  word(1) = 0;
  vm_.scans(3);
  EXPECT_FALSE(follower_mode());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kMoveComplete));  // 3601-MC-02: not set by the follower
  EXPECT_FALSE(errors());
  EXPECT_FALSE(moving());
  // Out of follower mode the master moves nothing.
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 200);
}

TEST_F(Follower3601, RatioIsExactOverManyCountsKeepingTheRemainder) {
  follower(cmd::kManualCw, 3, 7);
  vm_.scans(3);
  master(10'000, 20'000);
  settle();
  EXPECT_EQ(motor(), 30'000 / 7);  // 4,285 (remainder 5/7)
  EXPECT_EQ(position(), 4'285);
  count(1);  // 5/7 + 3/7: one more step
  settle();
  EXPECT_EQ(motor(), 4'286);
  count(1);  // 1/7 + 3/7: none
  settle();
  EXPECT_EQ(motor(), 4'286);
  EXPECT_FALSE(errors());
}

TEST_F(Follower3601, RatioChangesOnTheFly) {
  follower(cmd::kManualCw, 1, 1);
  vm_.scans(3);
  master(1'000, 20'000);
  settle();
  EXPECT_EQ(motor(), 1'000);
  word(2) = 2;  // x2
  vm_.scans(2);
  master(1'000, 20'000);
  settle();
  EXPECT_EQ(motor(), 3'000);
  word(2) = 1;
  word(3) = 4;  // x1/4
  vm_.scans(2);
  master(1'000, 20'000);
  settle();
  EXPECT_EQ(motor(), 3'250);
  EXPECT_FALSE(errors());
  // Instant mode (accel/decel 0): the output keeps up with the master count by count.
  word(3) = 1;
  vm_.scans(2);
  const std::int64_t before = motor();
  master(500, 2'000);
  vm_.run_for(2 * kMs);
  EXPECT_GE(motor() - before, 498);
}

TEST_F(Follower3601, AccelAndDecelSlewTheOutputItLagsThenCatchesUpExactly) {
  follower(cmd::kManualCw, 1, 1, 1, 1);  // 1,000 steps/s^2 both ways
  vm_.scans(3);
  master(2'000, 20'000);  // 0.1 s of master motion
  // After 0.1 s the ramp from Vs = 1,000 steps/s has output only about 100 steps.
  EXPECT_LT(motor(), 200);
  EXPECT_GT(motor(), 0);
  EXPECT_TRUE(status(kMovingCw));
  vm_.run_for(4'000 * kMs);
  EXPECT_EQ(motor(), 2'000);             // caught up to the exact count, no overshoot
  expect_2000_steps_within_the_ramps();  // never faster than the ramps allow
}

// Issue 18: pauses of the pulse thread slip the follower's steps; it never steps faster than its
// ramps allow to catch up, and its count stays exact.
TEST_F(Follower3601, StallsNeverMakeTheFollowerStepFasterThanItsRamps) {
  follower(cmd::kManualCw, 1, 1, 1, 1);  // 1,000 steps/s^2 both ways
  vm_.scans(3);
  master(2'000, 20'000);
  for (int i = 0; i < 40; ++i) {  // 4 ms stalls (at most 7 steps at 1,732 steps/s: < 8)
    vm_.stall_pulse_thread(vm_.now() + 10 * kMs, 4 * kMs);
    vm_.run_for(50 * kMs);
  }
  vm_.run_for(4'000 * kMs);
  EXPECT_EQ(motor(), 2'000);
  EXPECT_EQ(vm_.stack().motion(0).late_fault().count, 0u);
  EXPECT_GE(vm_.stack().motion(0).slip_ns(), 40 * kMs);  // the stalls did slip it
  expect_2000_steps_within_the_ramps();
}

TEST_F(Follower3601, DirectionBit7SameSenseBit8ReverseSense) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(500, 20'000);
  settle();
  EXPECT_EQ(motor(), 500);
  master(-200, 20'000);  // the master reverses: so does the output
  settle();
  EXPECT_EQ(motor(), 300);
  follower(0);
  vm_.scans(1);  // one scan with the command word at 0
  follower(cmd::kManualCcw);
  vm_.scans(3);
  EXPECT_FALSE(status(kCommandError));
  master(500, 20'000);  // reverse sense
  settle();
  EXPECT_EQ(motor(), -200);
  EXPECT_TRUE(follower_mode());
}

TEST_F(Follower3601, NoDirectionBitNoOutput) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 100);
  follower(0);
  vm_.scans(3);
  master(300, 20'000);
  settle();
  EXPECT_EQ(motor(), 100);
  EXPECT_TRUE(follower_mode());
  EXPECT_FALSE(moving());
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(50, 20'000);
  settle();
  EXPECT_EQ(motor(), 150);  // counts seen without a direction bit are not owed later
}

TEST_F(Follower3601, ExternalInputHasNoEffect) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(100, 20'000);
  force(InputLine::kExternal, true);
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 200);
  EXPECT_TRUE(follower_mode());
  EXPECT_FALSE(status(kStopped));
}

TEST_F(Follower3601, A24_LimitInTheOutputDirectionStopsTheOppositeIsIgnored) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(100, 20'000);
  force(InputLine::kCcwLimit, true);  // behind the CW output: ignored
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 200);
  EXPECT_TRUE(follower_mode());
  EXPECT_FALSE(status(kInputError));
  release(InputLine::kCcwLimit);
  vm_.scans(2);
  master(2'000, 20'000);  // outputting CW...
  const Nanos t_limit = vm_.now();
  force(InputLine::kCwLimit, true);  // ...into the CW limit: immediate stop, IE, PI, Stopped
  master(500, 20'000);
  settle();
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(follower_mode());
  const auto& t = vm_.step_times(0);
  ASSERT_FALSE(t.empty());
  // Nothing after the limit (the machine delivers the input after the edge in flight).
  EXPECT_LE(t.back(), t_limit + 100 * kNsPerUs);
  EXPECT_LE(motor(), 2'200);
}

TEST_F(Follower3601, EStopDuringFollowerStopsImmediately) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(300, 20'000);
  const Nanos t_stop = vm_.now();
  force(InputLine::kEStop, true);
  master(300, 20'000);
  settle();
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(follower_mode());
  EXPECT_LE(vm_.step_times(0).back(), t_stop + 100 * kNsPerUs);
  EXPECT_LE(motor(), 300);
}

TEST_F(Follower3601, CE_35_FollowerRequestedDuringAnotherMotionWhichCompletes) {
  command(cmd::kRelativeMove, {.target = 5'000});
  ASSERT_TRUE(moving());
  word(1) = lsw::kEncoderFollower;
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(follower_mode());
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 5'000);
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Follower3601, CE_36_MultiplierOrDivisorOutOfRange) {
  follower(cmd::kManualCw, 0, 1);
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 0);

  // On the fly: a divisor of -1 stops the output.
  follower(0, 1, 1, 0, 0, 0);
  vm_.scans(2);
  command(cmd::kResetErrors);
  ASSERT_FALSE(status(kCommandError));
  follower(cmd::kManualCw, 1, 1);
  vm_.scans(3);
  ASSERT_FALSE(status(kCommandError));
  master(100, 20'000);
  settle();
  ASSERT_EQ(motor(), 100);
  word(3) = -1;
  vm_.scans(2);
  EXPECT_TRUE(status(kCommandError));
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 100);
}

TEST_F(Follower3601, CE_38_DirectionChangedWithoutAZeroScan) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(100, 20'000);
  settle();
  ASSERT_EQ(motor(), 100);
  follower(cmd::kManualCcw);  // straight from bit 7 to bit 8
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 100);  // output stopped
}

TEST_F(Follower3601, CE_39_AnyOtherCommandBitWhileFollowing) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(100, 20'000);
  settle();
  follower(cmd::kManualCw | cmd::kHold);  // Hold included
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(status(kHoldState));
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 100);
  EXPECT_FALSE(follower_mode());

  // With LSW bit 7 set, a move command is an error too, and does not run.
  follower(0, 1, 1, 0, 0, 0);
  vm_.scans(2);
  command(cmd::kResetErrors);
  ASSERT_FALSE(status(kCommandError));
  command(cmd::kRelativeMove, {.target = 1'000, .lsw = lsw::kEncoderFollower});
  EXPECT_TRUE(status(kCommandError));
  settle();
  EXPECT_EQ(motor(), 100);
}

TEST_F(Follower3601, CE_40_LswBit7ClearedWhileADirectionBitIsSet) {
  follower(cmd::kManualCw);
  vm_.scans(3);
  master(100, 20'000);
  word(1) = 0;
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(follower_mode());
  EXPECT_TRUE(status(kStopped));
}

// Follower mode refused at the request: Command Error, not in follower mode, no output for the
// master's counts.
struct RefusedFollower {
  const char* name;
  std::uint16_t config = 0;  // a configuration instead of the fixture's (0: the fixture's)
  bool ccw_limit_active = false;
  std::int16_t accel = 0;
  std::int16_t decel = 0;
  std::uint16_t lsw = lsw::kEncoderFollower;
  std::int16_t word5 = 0;  // the speed LSW word (must be 0)
};

const RefusedFollower kRefusedFollowers[] = {
    {.name = "CE_34_FollowerWithoutEncoderConfigured", .config = kNoEncoderConfig},
    {.name = "CE_37_SpeedWordsMustBeZero", .word5 = 1},
    {.name = "CE_41_SCurveWithFollower",
     .accel = 10,
     .decel = 10,
     .lsw = static_cast<std::uint16_t>(lsw::kEncoderFollower | lsw::kSCurve)},
    {.name = "CE_42_FollowerRequestedWithAnEndLimitActive", .ccw_limit_active = true},  // A24
};

class RefusedFollower3601 : public Follower3601,
                            public ::testing::WithParamInterface<RefusedFollower> {};

TEST_P(RefusedFollower3601, NoOutput) {
  const RefusedFollower& r = GetParam();
  if (r.config != 0) configure(r.config);
  if (r.ccw_limit_active) {
    force(InputLine::kCcwLimit, true);
    vm_.scans(2);
  }
  follower(cmd::kManualCw, 1, 1, r.accel, r.decel, r.lsw);
  if (r.word5 != 0) word(5) = r.word5;
  vm_.scans(3);
  EXPECT_TRUE(status(kCommandError));
  EXPECT_FALSE(follower_mode());
  master(100, 20'000);
  settle();
  EXPECT_EQ(motor(), 0);
}

INSTANTIATE_TEST_SUITE_P(Items, RefusedFollower3601, ::testing::ValuesIn(kRefusedFollowers),
                         RowName{});

}  // namespace
}  // namespace stepmod::testing
