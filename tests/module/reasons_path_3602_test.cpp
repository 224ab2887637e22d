// The 3602's interpolated move refuses with its own reason (docs/error-reasons.md): each refusal
// records its checklist item on axis 1 (3602-CE-I1) in the scan that sets the Command Error, so
// the image that first shows the bit shows its reason too. Before, the refusal set the bit after
// the axis had recorded its reasons for the scan: for one scan the block kept the previous,
// unrelated reason, then showed only "3602-CE".
#include <gtest/gtest.h>

#include <string>

#include "tests/module/reasons_rig.hpp"
#include "tests/module/rig_interp_3602.hpp"

namespace stepmod::testing {
namespace {

class PathReasons3602 : public ReasonsRig<RigInterp3602> {
 protected:
  // The manual's sequence (the data, then the bits), scanned one scan at a time until axis 1
  // shows Command Error (at most 5 scans): the reason as of that scan.
  ErrorReason refused(const Path3602& p) {
    write_path(p, false);
    vm_.scans(10);
    set_bits(p.lsw);
    return reason_when_ce();
  }
  ErrorReason reason_when_ce() {
    for (int i = 0; i < 5 && !ce(kAxis1); ++i) vm_.scans(1);
    EXPECT_TRUE(ce(kAxis1));
    return reason(kAxis1);
  }
  static bool starts(const ErrorReason& r, const std::string& prefix) {
    return text(r).rfind(prefix, 0) == 0;
  }
};

TEST_F(PathReasons3602, CE_I6_PatternNamesItsItemOnTheScanOfTheBit) {
  const ErrorReason r = refused({.lsw = il::kLinear | il::kViaPoint, .end_x = 1'000});
  EXPECT_EQ(r.code, 20266u);
  EXPECT_EQ(text(r), "3602-CE-I6: path bits 10..14 name no method");
  vm_.scans(3);
  EXPECT_EQ(reason(kAxis1).seq, r.seq) << "no second, general reason: " << text(reason(kAxis1));
}

TEST_F(PathReasons3602, CE_03_CommandBitWithThePathBits) {
  write_path({.end_x = 1'000}, false);
  vm_.scans(10);
  module_word(iw::kMsw) = static_cast<std::int16_t>(m2::cmd_msw::kRelativeMove);
  set_bits(il::kLinear);
  const ErrorReason r = reason_when_ce();
  EXPECT_EQ(r.code, 20203u);
  EXPECT_TRUE(starts(r, "3602-CE-03: ")) << text(r);
}

TEST_F(PathReasons3602, CE_I5_ReservedWordsOfTheBlock) {
  write_path({.end_x = 1'000}, false);
  module_word(iw::kAxis2Lsw) = 1;
  vm_.scans(10);
  set_bits(il::kLinear);
  const ErrorReason r = reason_when_ce();
  EXPECT_TRUE(ip(kAxis1));
  EXPECT_EQ(r.code, 20265u);
  EXPECT_TRUE(starts(r, "3602-CE-I5: ")) << text(r);
}

TEST_F(PathReasons3602, CE_06_PathBelowTheStartingSpeed) {
  const ErrorReason r = refused({.speed = 500, .end_x = 1'000});
  EXPECT_EQ(r.code, 20206u);
  EXPECT_EQ(text(r), "3602-CE-06: path Vp 500 is below Vs 1000");
}

TEST_F(PathReasons3602, CE_I7_RadiusBelowHalfTheChord) {
  const ErrorReason r =
      refused({.lsw = il::kRadiusMethod | il::kCwCircular, .end_x = 1'000, .point_x = 100});
  EXPECT_EQ(r.code, 20267u);
  EXPECT_EQ(text(r), "3602-CE-I7: circle: radius below half the chord");
}

TEST_F(PathReasons3602, CE_I2_Axis2CommandWhileThePathRuns) {
  path_command({.end_x = 20'000, .end_y = 20'000});
  ASSERT_TRUE(lsw_status(kAxis1, m2::status_lsw::kInterpolatedRunning));
  set_command(kAxis2, m2::cmd_msw::kImmediateStop);
  const ErrorReason r = reason_when_ce();
  EXPECT_EQ(r.code, 20262u);
  EXPECT_EQ(text(r), "3602-CE-I2: axis 2 command while a path runs");
}

// 3602-CE-I3 with axis 2 never configured (RigInterp3602 configures both: a plain rig here).
class PathReasonsOneAxis3602 : public ReasonsRig<Rig3602> {};

TEST_F(PathReasonsOneAxis3602, CE_I3_PathWithAxis2NotConfigured) {
  configure(kAxis1);
  vm_.plc_out().w[iw::kLsw] = static_cast<std::int16_t>(il::kLinear);
  put_split(kAxis1, iw::kSpeedMsw, 10'000);
  vm_.plc_out().w[iw::kAccel] = 10;
  vm_.plc_out().w[iw::kDecel] = 10;
  put_split(kAxis1, iw::kEndXMsw, 1'000);
  for (int i = 0; i < 5 && !status(kAxis1, m2::status_msw::kCommandError); ++i) vm_.scans(1);
  ASSERT_TRUE(status(kAxis1, m2::status_msw::kCommandError));
  EXPECT_EQ(reason(kAxis1).code, 20263u);
  EXPECT_EQ(text(reason(kAxis1)), "3602-CE-I3: path: axis 2 is not configured");
}

}  // namespace
}  // namespace stepmod::testing
