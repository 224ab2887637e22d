// 3202 features per channel beyond the error lists: manual moves (ramped, constant speed,
// one-shot), S-curve moves by command bits 16/17, diagnostic feedback, capture of the position
// without an encoder (firmware >= 3.1), Preset Encoder (3202 manual Ch.1, Ch.3-5).
#include "tests/module/plc_3202.hpp"

namespace stepmod::testing {
namespace {

namespace sb = m2::status_bit;
namespace cb = m2::cmd_bit;
using namespace m2::cfg_bit;

class Features3202 : public Plc3202 {
 protected:
  void SetUp() override {
    configure(0);
    configure(1);
  }
};

TEST_F(Features3202, OneShotManualMoveOutputsOnePulsePerEdge) {
  set_command(0, cb::kManualCw, {.speed = 0});
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(0), 1);
  EXPECT_TRUE(status(0, sb::kMovingCw));  // while the bit is held
  put(0, {});
  vm_.scans(2);
  EXPECT_FALSE(status(0, sb::kStopped));
  set_command(0, cb::kManualCcw, {.speed = 0});
  vm_.run_for(100 * kNsPerMs);
  put(0, {});
  vm_.scans(2);
  EXPECT_EQ(motor(0), 0);
  EXPECT_EQ(motor(1), 0);
}

TEST_F(Features3202, ConstantSpeedManualMoveRunsAtVp) {
  // Vp <= Vs: no ramp; 1,000 steps/s for 500 ms is ~500 steps.
  set_command(1, cb::kManualCcw, {.speed = 1'000});
  vm_.run_for(500 * kNsPerMs);
  EXPECT_NEAR(static_cast<double>(motor(1)), -500.0, 5.0);
  put(1, {});
  ASSERT_TRUE(wait_idle(1));
  EXPECT_TRUE(status(1, sb::kStopped));
}

TEST_F(Features3202, SCurveMovesByBits16And17ReachTheirTargetExactly) {
  command(0, cb::kRelativeMove, {.target = 9'000, .flags = cb::kSCurve});
  command(1, cb::kRelativeMove, {.target = 7'000, .flags = cb::kSCurve | cb::kTrapezoidalS});
  ASSERT_TRUE(wait_idle(0));
  ASSERT_TRUE(wait_idle(1));
  EXPECT_EQ(motor(0), 9'000);
  EXPECT_EQ(motor(1), 7'000);
  EXPECT_EQ(vm_.step_times(0).size(), 9'000u);
  EXPECT_EQ(vm_.step_times(1).size(), 7'000u);
  // Triangular S takes longer than constant acceleration for the same move (3202 manual ch. 2).
  const Nanos s_time = vm_.step_times(0).back() - vm_.step_times(0).front();
  command(0, cb::kRelativeMove, {.target = 9'000});
  ASSERT_TRUE(wait_idle(0));
  const Nanos c_time = vm_.step_times(0).back() - vm_.step_times(0)[9'000];
  EXPECT_GT(s_time, c_time);
}

TEST_F(Features3202, DiagnosticFeedbackCountsOwnPulsesAndPresetPositionPresetsIt) {
  configure(0, (kFull3202 & ~kQuadratureEncoder) | kDiagnosticFeedback);
  command(0, cb::kRelativeMove, {.target = 1'500});
  ASSERT_TRUE(wait_idle(0));
  EXPECT_EQ(encoder(0), 1'500);
  command(0, cb::kPresetPosition, {.target = 40, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(position(0), 40);
  EXPECT_EQ(encoder(0), 40);
  // Preset Encoder needs the quadrature encoder (3202-CE-11).
  command(0, cb::kPresetEncoder, {.target = 7, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_TRUE(status(0, sb::kCommandError));
  EXPECT_EQ(encoder(0), 40);
}

TEST_F(Features3202, CaptureLatchesThePositionWithoutAnEncoder) {
  configure(1, kFull3202 & ~kQuadratureEncoder);
  command(1, cb::kRelativeMove, {.target = 2'222});
  ASSERT_TRUE(wait_idle(1));
  force(1, InputLine::kCapture, true);
  vm_.scans(2);
  EXPECT_EQ(capture(1), 2'222);
}

TEST_F(Features3202, PresetEncoderSetsTheCountOnlyOnItsChannel) {
  command(0, cb::kPresetEncoder, {.target = -123'456, .speed = 0, .accel = 0, .decel = 0});
  EXPECT_EQ(encoder(0), -123'456);
  EXPECT_EQ(encoder(1), 0);
  EXPECT_TRUE(status(0, sb::kPositionInvalid));  // the position is not touched
}

}  // namespace
}  // namespace stepmod::testing
