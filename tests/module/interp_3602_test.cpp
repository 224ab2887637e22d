// The 3602's interpolated moves, what needs no motion (3602 manual ch. 3, tables 9.4, 9.23-9.26;
// A17, A34-A37): the block decoded from all sixteen words, the word rules, the acceptance rules,
// the geometry check; every refusal is a Command Error on axis 1 only (3602-CE-I1) and starts
// nothing.
#include "module_types/m3602/dialect_3602.hpp"
#include "tests/module/rig_interp_3602.hpp"

namespace stepmod::testing {
namespace {

using namespace m2::status_msw;
using module::m3602::InterpolatedCommand;
using module::m3602::InterpolationFault;
using module::m3602::InterpolationMethod;

// ---- the dialect: the block -> InterpolatedCommand -------------------------------------------

ImageWords block(std::uint16_t lsw, std::int32_t ex, std::int32_t ey, std::int32_t px = 0,
                 std::int32_t py = 0) {
  ImageWords w;
  w.w[iw::kLsw] = static_cast<std::int16_t>(lsw);
  const auto put = [&w](unsigned i, std::int32_t v) {
    const auto p = words::encode_3602(v);
    w.w[i] = p.msw;
    w.w[i + 1] = p.lsw;
  };
  put(iw::kSpeedMsw, 250'000);
  w.w[iw::kAccel] = 20;
  w.w[iw::kDecel] = 2000;
  put(iw::kEndXMsw, ex);
  put(iw::kEndYMsw, ey);
  put(iw::kPointXMsw, px);
  put(iw::kPointYMsw, py);
  return w;
}

TEST(InterpolatedWords3602, NoInterpolationBitsNoCommand) {
  EXPECT_FALSE(module::m3602::interpolated_from_words(block(il::kGpo | il::kSCurve, 5, 5)));
}

TEST(InterpolatedWords3602, EveryValidPatternDecodes) {
  struct Case {
    std::uint16_t bits;
    InterpolationMethod method;
    bool ccw;
  };
  const Case cases[] = {
      {il::kLinear, InterpolationMethod::kLinear, false},
      {il::kViaPoint, InterpolationMethod::kViaPoint, false},
      {il::kCwCircular, InterpolationMethod::kCentre, false},
      {il::kCcwCircular, InterpolationMethod::kCentre, true},
      {il::kRadiusMethod | il::kCwCircular, InterpolationMethod::kRadius, false},
      {il::kRadiusMethod | il::kCcwCircular, InterpolationMethod::kRadius, true},
  };
  for (const Case& k : cases) {
    for (const bool absolute : {false, true}) {
      const std::uint16_t lsw = k.bits | (absolute ? il::kAbsoluteCoordinates : 0) | il::kSCurve |
                                il::kTrapezoidalS | il::kGpo;
      const bool linear = k.method == InterpolationMethod::kLinear;
      const bool radius = k.method == InterpolationMethod::kRadius;
      const auto c = module::m3602::interpolated_from_words(block(
          lsw, -1'073'741'823, 1'073'741'823, linear ? 0 : -70'000, linear || radius ? 0 : 9));
      ASSERT_TRUE(c);
      EXPECT_EQ(c->fault, InterpolationFault::kNone) << std::hex << lsw;
      EXPECT_EQ(c->method, k.method);
      EXPECT_EQ(c->ccw, k.ccw);
      EXPECT_EQ(c->absolute, absolute);
      EXPECT_EQ(c->shape, planner::AccelShape::kTrapezoidalS);
      EXPECT_EQ(c->speed, 250'000);
      EXPECT_EQ(c->accel, 20'000);  // steps/ms/s -> steps/s^2
      EXPECT_EQ(c->decel, 2'000'000);
      EXPECT_EQ(c->end_x, -1'073'741'823);
      EXPECT_EQ(c->end_y, 1'073'741'823);
      if (radius) {
        EXPECT_EQ(c->radius, -70'000);
      } else if (!linear) {
        EXPECT_EQ(c->point_x, -70'000);
        EXPECT_EQ(c->point_y, 9);
      }
    }
  }
}

TEST(InterpolatedWords3602, CE_I6_PatternsNotInTheTable) {
  const std::uint16_t bad[] = {
      il::kLinear | il::kViaPoint,
      il::kRadiusMethod,
      il::kCwCircular | il::kCcwCircular,
      il::kRadiusMethod | il::kCwCircular | il::kCcwCircular,
      il::kRadiusMethod | il::kLinear,
      il::kAbsoluteCoordinates,
      il::kLinear | 0x8000,
      il::kLinear | 0x0100,
      il::kLinear | il::kProgramBlend,
  };
  for (const std::uint16_t lsw : bad) {
    const auto c = module::m3602::interpolated_from_words(block(lsw, 1, 1));
    ASSERT_TRUE(c);
    EXPECT_EQ(c->fault, InterpolationFault::kPattern) << std::hex << lsw;
  }
}

TEST(InterpolatedWords3602, CE_I5_ReservedWordsPerMethod) {
  // Words 8 and 9 for every method; 12..15 for the linear move; 14/15 for the radius method.
  for (const unsigned w : {iw::kAxis2Msw, iw::kAxis2Lsw}) {
    ImageWords b = block(il::kViaPoint, 1, 1, 5, 9);
    b.w[w] = 1;
    EXPECT_EQ(module::m3602::interpolated_from_words(b)->fault, InterpolationFault::kReserved);
  }
  for (unsigned w = 12; w <= 15; ++w) {
    ImageWords b = block(il::kLinear, 1, 1);
    b.w[w] = 1;
    EXPECT_EQ(module::m3602::interpolated_from_words(b)->fault, InterpolationFault::kReserved);
  }
  for (unsigned w = 14; w <= 15; ++w) {
    ImageWords b = block(il::kRadiusMethod | il::kCcwCircular, 1, 1, 500);
    b.w[w] = 1;
    EXPECT_EQ(module::m3602::interpolated_from_words(b)->fault, InterpolationFault::kReserved);
  }
}

TEST(InterpolatedWords3602, CE_05_CoordinatesOutOfRange) {
  const auto fault = [](const ImageWords& b) {
    return module::m3602::interpolated_from_words(b)->fault;
  };
  EXPECT_EQ(fault(block(il::kLinear, 1'073'741'824, 0)), InterpolationFault::kRange);
  EXPECT_EQ(fault(block(il::kLinear, 0, -1'073'741'824)), InterpolationFault::kRange);
  EXPECT_EQ(fault(block(il::kViaPoint, 10, 0, 5, 1'073'741'824)), InterpolationFault::kRange);
  EXPECT_EQ(fault(block(il::kCwCircular, 10, 0, -1'073'741'824, 0)), InterpolationFault::kRange);
  // A35: the radius takes any int32 but -2^31.
  EXPECT_EQ(fault(block(il::kRadiusMethod | il::kCwCircular, 10, 0, 2'147'483'647)),
            InterpolationFault::kNone);
  EXPECT_EQ(fault(block(il::kRadiusMethod | il::kCwCircular, 10, 0, INT32_MIN)),
            InterpolationFault::kRange);
}

TEST(InterpolatedWords3602, CE_03_CommandMswWithInterpolationBits) {
  ImageWords b = block(il::kLinear, 1, 1);
  b.w[iw::kMsw] = m2::cmd_msw::kRelativeMove;
  EXPECT_EQ(module::m3602::interpolated_from_words(b)->fault, InterpolationFault::kCommandBits);
}

// ---- the module: refusals ---------------------------------------------------------------------

class Interpolation3602 : public RigInterp3602 {
 protected:
  // Refused with a Command Error on axis 1 only (3602-CE-I1), with or without Invalid Profile, and
  // nothing moved.
  void expect_refused(bool invalid_profile) {
    EXPECT_TRUE(ce(kAxis1));
    EXPECT_EQ(ip(kAxis1), invalid_profile);
    EXPECT_FALSE(ce(kAxis2));
    EXPECT_FALSE(ip(kAxis2));
    EXPECT_FALSE(moving(kAxis1));
    EXPECT_FALSE(moving(kAxis2));
    EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kInterpolatedRunning));
    EXPECT_TRUE(status(kAxis1, kStopped));
    EXPECT_TRUE(status(kAxis2, kStopped));
    vm_.scans(20);
    EXPECT_EQ(motor(kAxis1), 0);
    EXPECT_EQ(motor(kAxis2), 0);
  }
  void reset_both() {
    reset_errors(kAxis1);
    reset_errors(kAxis2);
    ASSERT_FALSE(ce(kAxis1));
  }
};

TEST_F(Interpolation3602, CE_I6_InvalidBitPatternIsACommandErrorOnAxis1) {
  for (const std::uint16_t lsw :
       {static_cast<std::uint16_t>(il::kLinear | il::kViaPoint), il::kRadiusMethod,
        static_cast<std::uint16_t>(il::kCwCircular | il::kCcwCircular), il::kAbsoluteCoordinates}) {
    path_command({.lsw = lsw, .end_x = 1'000, .end_y = 1'000});
    expect_refused(false);
    reset_both();
  }
}

TEST_F(Interpolation3602, CE_03_CommandBitTogetherWithInterpolationBits) {
  write_path({.end_x = 1'000, .end_y = 500}, false);
  vm_.scans(10);
  module_word(iw::kMsw) = m2::cmd_msw::kRelativeMove;
  set_bits(il::kLinear);
  vm_.scans(3);
  expect_refused(false);
}

TEST_F(Interpolation3602, CE_I5_ReservedWordsNonZero) {
  // Word 9 (axis 2's command LSW): the GPO bit a PLC left there.
  write_path({.end_x = 1'000, .end_y = 500}, false);
  module_word(iw::kAxis2Lsw) = il::kGpo;
  vm_.scans(10);
  set_bits(il::kLinear);
  vm_.scans(3);
  expect_refused(true);
}

TEST_F(Interpolation3602, IP_18_DataInTheReservedWordsOfALinearMove) {
  path_command({.end_x = 1'000, .end_y = 500, .point_x = 7});  // words 12/13 of a linear move
  expect_refused(true);
  reset_both();
  // The radius method leaves 14/15 unused.
  path_command({.lsw = il::kRadiusMethod | il::kCwCircular,
                .end_x = 1'000,
                .end_y = 0,
                .point_x = 800,
                .point_y = 1});
  expect_refused(true);
}

// The manual: data written together with the bits may find words 8..15 stale (the backplane moves
// 8-word blocks); whatever check the stale words fail gives the Command Error.
TEST_F(Interpolation3602, CE_I4_StaleWords8To15WhenTheBitsRiseWithTheData) {
  // Axis 2's last relative move is still in words 8..15 when axis 1's half of the block arrives.
  clear_words(kAxis2);
  set_command(kAxis2, 0, {.target = 2'000, .speed = 20'000, .accel = 10, .decel = 10});
  vm_.scans(3);
  clear_words(kAxis1);
  module_word(iw::kLsw) = il::kLinear;
  put_module_split(iw::kSpeedMsw, 10'000);
  module_word(iw::kAccel) = 10;
  module_word(iw::kDecel) = 10;
  put_module_split(iw::kEndXMsw, 1'000);
  vm_.scans(3);
  // Words 12..15 (axis 2's old speed, accel, decel) are not 0 for a linear move.
  expect_refused(true);
  // Written the manual's way, the same move is accepted.
  reset_both();
  clear_bits();
  vm_.scans(2);
  path_command({.end_x = 1'000, .end_y = 2'000});
  EXPECT_FALSE(ce(kAxis1));
  EXPECT_FALSE(ip(kAxis1));
  ASSERT_TRUE(wait_path_end());
  EXPECT_EQ(motor(kAxis1), 1'000);
  EXPECT_EQ(motor(kAxis2), 2'000);
}

TEST_F(Interpolation3602, CE_05_EndPointOutOfRange) {
  path_command({.end_x = 1'073'741'824, .end_y = 0});
  expect_refused(true);
  reset_both();
  path_command(
      {.lsw = il::kViaPoint, .end_x = 10, .end_y = 0, .point_x = 5, .point_y = -1'073'741'824});
  expect_refused(true);
}

TEST_F(Interpolation3602, CE_05_VectorSpeedAccelDecelOutOfRange) {
  for (const Path3602& p :
       {Path3602{.speed = 1'000'001, .end_x = 1'000}, Path3602{.speed = 0, .end_x = 1'000},
        Path3602{.accel = 0, .end_x = 1'000}, Path3602{.accel = 2'001, .end_x = 1'000},
        Path3602{.decel = 0, .end_x = 1'000}, Path3602{.decel = -3, .end_x = 1'000}}) {
    path_command(p);
    expect_refused(true);
    reset_both();
  }
}

// A37: the vector speed must reach axis 1's starting speed.
TEST_F(Interpolation3602, CE_06_IP_01_VectorSpeedBelowAxis1StartingSpeed) {
  path_command({.speed = 999, .end_x = 1'000, .end_y = 1'000});
  expect_refused(true);
}

TEST_F(Interpolation3602, CE_07_IP_17_AbsoluteWithEitherPositionInvalid) {
  // After configuration both positions are invalid.
  path_command({.lsw = il::kLinear | il::kAbsoluteCoordinates, .end_x = 1'000, .end_y = 500});
  expect_refused(true);
  reset_both();
  preset(kAxis1, 0);  // axis 2's still invalid
  path_command({.lsw = il::kLinear | il::kAbsoluteCoordinates, .end_x = 1'000, .end_y = 500});
  expect_refused(true);
  EXPECT_TRUE(status(kAxis2, kPositionInvalid));
}

TEST_F(Interpolation3602, CE_I3_Axis2InConfigurationMode) {
  write_config(kAxis2, kLimitsConfigMsw);
  vm_.scans(3);
  // Axis 1's half of the block; axis 2's words are its configuration (words 8/9 non-zero, too).
  clear_words(kAxis1);
  put_module_split(iw::kSpeedMsw, 10'000);
  module_word(iw::kAccel) = 10;
  module_word(iw::kDecel) = 10;
  put_module_split(iw::kEndXMsw, 1'000);
  vm_.scans(10);
  set_bits(il::kLinear);
  vm_.scans(3);
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_FALSE(moving(kAxis1));
  EXPECT_EQ(motor(kAxis1), 0);
}

class Interpolation3602Unconfigured : public RigInterp3602 {
 protected:
  void SetUp() override { configure(kAxis1); }
};

TEST_F(Interpolation3602Unconfigured, CE_I3_Axis2NotConfigured) {
  path_command({.end_x = 1'000, .end_y = 1'000});
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_FALSE(ip(kAxis1));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_EQ(motor(kAxis2), 0);
}

TEST_F(Interpolation3602Unconfigured, CE_I3_Axis2Disabled) {
  configure(kAxis2, kLimitsConfigMsw | m2::cfg_msw::kDisableAxis);
  ASSERT_FALSE(status(kAxis2, kAxisEnabled));
  path_command({.end_x = 1'000, .end_y = 1'000});
  EXPECT_TRUE(ce(kAxis1));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
}

// 3602 manual ch. 3 "Rounding, reject" through the words: no motion, CE + IP on axis 1 (A36).
TEST_F(Interpolation3602, CE_I7_CentreRadiiDifferAfterRoundingNoMotion) {
  preset(kAxis1, -1'000);
  preset(kAxis2, 1'531);
  path_command({.lsw = il::kCcwCircular | il::kAbsoluteCoordinates,
                .end_x = 1'562,
                .end_y = 950,
                .point_x = 0,
                .point_y = 0});
  expect_refused(true);
  EXPECT_EQ(position(kAxis1), -1'000);
  EXPECT_EQ(position(kAxis2), 1'531);
}

TEST_F(Interpolation3602, CE_I7_ViaPointsCollinear) {
  path_command(
      {.lsw = il::kViaPoint, .end_x = 2'000, .end_y = 2'000, .point_x = 1'000, .point_y = 1'000});
  expect_refused(true);
}

TEST_F(Interpolation3602, CE_I7_RadiusTooSmallForTheChord) {
  path_command(
      {.lsw = il::kRadiusMethod | il::kCcwCircular, .end_x = 3'000, .end_y = 0, .point_x = 1'499});
  expect_refused(true);
}

TEST_F(Interpolation3602, CE_I1_ErrorsOnAxis1OnlyCommandErrorLatchBlocks) {
  path_command({.end_x = 1'073'741'824});
  expect_refused(true);
  // While CE is set, the next interpolated command is not looked at (3602-CE-L1 latch rules).
  path_command({.end_x = 1'000, .end_y = 1'000});
  EXPECT_FALSE(lsw_status(kAxis1, m2::status_lsw::kInterpolatedRunning));
  EXPECT_FALSE(ce(kAxis2));
}

TEST_F(Interpolation3602, CE_04_InterpolatedMoveWhileAxis2Moves) {
  set_command(kAxis2, m2::cmd_msw::kRelativeMove, {.target = 3'000});
  vm_.scans(3);
  word(kAxis2, m2::out_word::kMsw) = 0;
  ASSERT_TRUE(moving(kAxis2));
  // Axis 2's words must be 0 for the block: the PLC writes the block over them (axis 2's move
  // runs on).
  path_command({.end_x = 1'000, .end_y = 0});
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_FALSE(moving(kAxis1));
  ASSERT_TRUE(wait_idle(kAxis2));
  EXPECT_EQ(motor(kAxis2), 3'000);
  EXPECT_EQ(motor(kAxis1), 0);
}

// A15 at the start: a limit ahead of an axis' first steps -> Input Error on that axis, no motion.
TEST_F(Interpolation3602, LimitAheadOfAnAxisBlocksTheStart) {
  force(kAxis2, InputLine::kCcwLimit, true);
  path_command({.end_x = 1'000, .end_y = -1'000});
  EXPECT_TRUE(status(kAxis2, kInputError));
  EXPECT_FALSE(ce(kAxis1));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_EQ(motor(kAxis2), 0);
}

// A17: External active at the start: no motion, axis 1 in Hold.
TEST_F(Interpolation3602, HLD_01_ExternalActiveAtTheStartHoldsWithoutMotion) {
  force(kAxis2, InputLine::kExternal, true);
  path_command({.end_x = 1'000, .end_y = 1'000});
  EXPECT_TRUE(status(kAxis1, kHoldState));
  EXPECT_FALSE(ce(kAxis1));
  EXPECT_FALSE(status(kAxis2, kHoldState));
  vm_.scans(20);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_EQ(motor(kAxis2), 0);
}

TEST_F(Interpolation3602, MC_01_ZeroLengthLineCompletesOnBothAxes) {
  path_command({.end_x = 0, .end_y = 0});
  EXPECT_FALSE(ce(kAxis1));
  EXPECT_TRUE(status(kAxis1, kMoveComplete));
  EXPECT_TRUE(status(kAxis2, kMoveComplete));
}

// A32: a position outside the +-2^30 box (reached by a relative move) and an absolute end point at
// the box's other side are 2^31 steps apart: more than the module's 32-bit registers hold.
TEST_F(Interpolation3602, IP_03_AbsolutePathOverflowsTheRegisters) {
  preset(kAxis1, 1'073'741'823);
  preset(kAxis2, 0);
  clear_words(kAxis1);
  command(kAxis1, m2::cmd_msw::kRelativeMove, {.target = 2});
  ASSERT_TRUE(wait_idle(kAxis1));
  ASSERT_EQ(position(kAxis1), 1'073'741'825);
  path_command(
      {.lsw = il::kLinear | il::kAbsoluteCoordinates, .end_x = -1'073'741'823, .end_y = 0});
  EXPECT_TRUE(ce(kAxis1));
  EXPECT_TRUE(ip(kAxis1));
  vm_.scans(20);
  EXPECT_EQ(position(kAxis1), 1'073'741'825);
  // One step less is a 32-bit count: accepted.
  reset_errors(kAxis1);
  path_command(
      {.lsw = il::kLinear | il::kAbsoluteCoordinates, .end_x = -1'073'741'822, .end_y = 0});
  EXPECT_FALSE(ce(kAxis1));
  EXPECT_TRUE(lsw_status(kAxis1, m2::status_lsw::kInterpolatedRunning));
}

}  // namespace
}  // namespace stepmod::testing
