// 3601 discrete inputs in virtual time: E-stop, end limits, External, capture, encoder and the
// input-state bits of the status LSW (3601 checklist IE, PI, STP, HLD items; 3601 manual ch. 4, 6).
#include "tests/module/plc_3601.hpp"

namespace stepmod::testing {
namespace {

using namespace m::status_msw;
namespace cmd = m::cmd_msw;

class Inputs3601 : public Plc3601 {
 protected:
  void SetUp() override {
    configure();
    command(cmd::kPresetPosition, {.target = 0, .speed = 0, .accel = 0, .decel = 0});
  }
};

TEST_F(Inputs3601, LSW_InputStateBitsFollowTheLogicalInputs) {
  EXPECT_EQ(status_lsw() & 0x3F, 0);
  force(InputLine::kExternal, true);
  force(InputLine::kCwLimit, true);
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(m::status_lsw::kExternalActive));
  EXPECT_TRUE(lsw_status(m::status_lsw::kCwLimitActive));
  EXPECT_FALSE(lsw_status(m::status_lsw::kHomeActive));
  release(InputLine::kExternal);
  release(InputLine::kCwLimit);
  vm_.scans(2);
  EXPECT_EQ(status_lsw() & 0x3F, 0);
}

TEST_F(Inputs3601, LSW_ActiveLowInputIsActiveWhenItsLineIsLow) {
  configure(kFullConfigMsw, kAllActiveHigh & ~(1u << 2));  // home input active low (N.C.)
  force(InputLine::kHome, false);
  vm_.scans(2);
  EXPECT_TRUE(lsw_status(m::status_lsw::kHomeActive));
  force(InputLine::kHome, true);
  vm_.scans(2);
  EXPECT_FALSE(lsw_status(m::status_lsw::kHomeActive));
}

TEST_F(Inputs3601, A27_UnusedInputReadsInactive) {
  configure(m::cfg_msw::kHomeUsed | m::cfg_msw::kCwLimitUsed | m::cfg_msw::kStepDirOutput);
  force(InputLine::kExternal, true);
  force(InputLine::kEStop, true);
  vm_.scans(2);
  EXPECT_EQ(status_lsw() & 0x3F, 0);
  // ... and an unused E-stop does not stop anything.
  command(cmd::kRelativeMove, {.target = 300});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), 300);
}

TEST_F(Inputs3601, IE_01_PI_03_STP_02_EStopWhileMovingStopsImmediately) {
  command(cmd::kRelativeMove, {.target = 50'000});
  vm_.run_for(400 * kNsPerMs);
  force(InputLine::kEStop, true);
  ASSERT_TRUE(wait_idle(50 * kNsPerMs));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));  // 3601-PI-03
  EXPECT_TRUE(status(kStopped));          // 3601-STP-02
  EXPECT_FALSE(status(kMoveComplete));
}

TEST_F(Inputs3601, A15_EStopActiveBlocksANewMove) {
  force(InputLine::kEStop, true);
  vm_.scans(2);
  EXPECT_FALSE(status(kInputError));  // activation at rest: no IE (A15)
  command(cmd::kRelativeMove, {.target = 500});
  EXPECT_TRUE(status(kInputError));
  vm_.run_for(100 * kNsPerMs);
  EXPECT_EQ(motor(), 0);
}

TEST_F(Inputs3601, IE_02_PI_04_STP_04_LimitDuringRelativeMoveStopsImmediately) {
  command(cmd::kRelativeMove, {.target = 200'000, .speed = 50'000, .accel = 100, .decel = 100});
  ASSERT_TRUE(wait_idle(20 * kNsPerSec));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));  // 3601-PI-04
  EXPECT_TRUE(status(kStopped));          // 3601-STP-04
  EXPECT_TRUE(lsw_status(m::status_lsw::kCwLimitActive));
  EXPECT_GE(motor(), 100'000);
  EXPECT_LT(motor(), 100'100);  // stopped at the switch, not after a deceleration
}

TEST_F(Inputs3601, IE_02_OppositeLimitStopsAnAbsoluteMoveToo) {
  command(cmd::kRelativeMove, {.target = 20'000});
  vm_.run_for(300 * kNsPerMs);
  force(InputLine::kCcwLimit, true);
  ASSERT_TRUE(wait_idle(50 * kNsPerMs));
  EXPECT_TRUE(status(kInputError));
}

TEST_F(Inputs3601, IE_02_OppositeLimitIgnoredByManualMove) {
  set_words(cmd::kManualCw, 0, 0, 5'000, 10, 10);
  vm_.run_for(300 * kNsPerMs);
  force(InputLine::kCcwLimit, true);
  vm_.run_for(200 * kNsPerMs);
  EXPECT_TRUE(moving());
  force(InputLine::kCwLimit, true);  // the limit in the direction of travel stops it
  ASSERT_TRUE(wait_idle(50 * kNsPerMs));
  EXPECT_TRUE(status(kInputError));
  EXPECT_TRUE(status(kPositionInvalid));
}

TEST_F(Inputs3601, IE_03_ManualMoveTowardAnActiveLimit) {
  force(InputLine::kCwLimit, true);
  set_words(cmd::kManualCw, 0, 0, 5'000, 10, 10);
  vm_.scans(3);
  EXPECT_TRUE(status(kInputError));
  EXPECT_FALSE(moving());
  word(0) = 0;
  command(cmd::kResetErrors);
  // Away from the limit is allowed: an axis can be driven off its limit.
  set_words(cmd::kManualCcw, 0, 0, 5'000, 10, 10);
  vm_.run_for(200 * kNsPerMs);
  EXPECT_TRUE(status(kMovingCcw));
  EXPECT_FALSE(status(kInputError));
  word(0) = 0;
  ASSERT_TRUE(wait_idle());
}

TEST_F(Inputs3601, IE_C1_InputErrorClearsWhenTheNextMoveStarts) {
  command(cmd::kRelativeMove, {.target = 50'000});
  vm_.run_for(300 * kNsPerMs);
  force(InputLine::kEStop, true);
  ASSERT_TRUE(wait_idle());
  ASSERT_TRUE(status(kInputError));
  release(InputLine::kEStop);
  command(cmd::kRelativeMove, {.target = 100});
  EXPECT_FALSE(status(kInputError));
  ASSERT_TRUE(wait_idle());
}

TEST_F(Inputs3601, HLD_02_ExternalInputHoldsAMove) {
  command(cmd::kAbsoluteMove, {.target = 30'000});
  vm_.run_for(800 * kNsPerMs);
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kHoldState));
  EXPECT_FALSE(status(kPositionInvalid));
  EXPECT_FALSE(status(kStopped));
  release(InputLine::kExternal);
  command(cmd::kResume);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), 30'000);
  EXPECT_TRUE(status(kMoveComplete));
}

TEST_F(Inputs3601, HLD_03_MoveStartedWithExternalActiveMakesOneStepThenHolds) {
  force(InputLine::kExternal, true);
  vm_.scans(2);
  command(cmd::kRelativeMove, {.target = -5'000});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(motor(), -1);
  EXPECT_TRUE(status(kHoldState));
  release(InputLine::kExternal);
  command(cmd::kResume);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(position(), -5'000);
}

TEST_F(Inputs3601, STP_01_ExternalInputStopsAManualMove) {
  set_words(cmd::kManualCw, 0, 0, 5'000, 10, 10);
  vm_.run_for(300 * kNsPerMs);
  force(InputLine::kExternal, true);
  ASSERT_TRUE(wait_idle());
  EXPECT_TRUE(status(kStopped));
  EXPECT_FALSE(status(kHoldState));
  EXPECT_FALSE(status(kPositionInvalid));
}

TEST_F(Inputs3601, CaptureLatchesTheEncoderCountAtTheEdge) {
  command(cmd::kRelativeMove, {.target = 10'000});
  vm_.run_for(900 * kNsPerMs);
  const std::int64_t count_then = vm_.sim().encoder(0);
  force(InputLine::kCapture, true);
  vm_.scans(2);
  EXPECT_EQ(capture(), count_then);
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(encoder(), 10'000);  // encoder_ratio 1: one X4 count per step
  EXPECT_EQ(capture(), count_then);
}

TEST_F(Inputs3601, CaptureLatchesThePositionWithoutAnEncoder) {
  configure(m::cfg_msw::kHomeUsed | m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCaptureUsed |
            m::cfg_msw::kStepDirOutput);
  command(cmd::kRelativeMove, {.target = 10'000});
  vm_.run_for(900 * kNsPerMs);
  const std::int64_t position_then = motor();
  force(InputLine::kCapture, true);
  vm_.scans(2);
  EXPECT_EQ(capture(), position_then);
  ASSERT_TRUE(wait_idle());
}

TEST_F(Inputs3601, EncoderCountsBothDirections) {
  command(cmd::kRelativeMove, {.target = 3'000});
  ASSERT_TRUE(wait_idle());
  command(cmd::kRelativeMove, {.target = -4'000});
  ASSERT_TRUE(wait_idle());
  EXPECT_EQ(encoder(), -1'000);
}

}  // namespace
}  // namespace stepmod::testing
