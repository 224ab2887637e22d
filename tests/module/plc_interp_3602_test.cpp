// The PLC-side interpolated moves (module_types/m3602/plc_interp_3602) over the virtual machine: the block word by
// word, the manual's sequence (data first, the bits >= 10 ms later), lines and circles to their
// end points, Hold / Resume on axis 1, refusals reported from axis 1.
#include <gtest/gtest.h>

#include "module_types/m3602/plc_interp_3602.hpp"
#include "tests/module/rig_3602.hpp"
#include "tests/support/virtual_port.hpp"

namespace stepmod::testing {
namespace {

using Method = plc::PathMove3602::Method;
namespace iw = m2::interp_word;
namespace il = m2::cmd_lsw;

TEST(PlcInterpWords3602, BlockInAllSixteenWords) {
  plc::PathMove3602 p{
      .method = Method::kCentreCcw,
      .absolute = true,
      .end_x = 1'563,
      .end_y = 950,
      .point_x = -70'000,
      .point_y = 65'536,
      .profile = {
          .speed = 100'000, .accel = 20, .decel = 30, .type = plc::AccelType::kTriangularS}};
  ImageWords w;
  for (auto& x : w.w) x = 77;  // stale words are overwritten
  plc::m3602::put_interpolated(w, p, false, il::kGpo);
  EXPECT_EQ(w.w[iw::kMsw], 0);
  EXPECT_EQ(static_cast<std::uint16_t>(w.w[iw::kLsw]), il::kSCurve | il::kGpo);
  plc::m3602::put_interpolated(w, p, true, 0);
  EXPECT_EQ(static_cast<std::uint16_t>(w.w[iw::kLsw]),
            il::kSCurve | il::kAbsoluteCoordinates | il::kCcwCircular);
  EXPECT_EQ(w.w[2], 1);  // 100,000 = 16#0001:86A0
  EXPECT_EQ(static_cast<std::uint16_t>(w.w[3]), 0x86A0);
  EXPECT_EQ(w.w[4], 20);
  EXPECT_EQ(w.w[5], 30);
  EXPECT_EQ(w.w[6], 0);
  EXPECT_EQ(w.w[7], 1'563);
  EXPECT_EQ(w.w[8], 0);
  EXPECT_EQ(w.w[9], 0);
  EXPECT_EQ(w.w[10], 0);
  EXPECT_EQ(w.w[11], 950);
  EXPECT_EQ(w.w[12], -2);  // -70,000 = 16#FFFE:EE90
  EXPECT_EQ(static_cast<std::uint16_t>(w.w[13]), 0xEE90);
  EXPECT_EQ(w.w[14], 1);
  EXPECT_EQ(w.w[15], 0);
  // The radius method: R in 12/13, 14/15 zero; the linear move: 12..15 zero.
  p.method = Method::kRadiusCw;
  p.radius = -5;
  plc::m3602::put_interpolated(w, p, true, 0);
  EXPECT_EQ(static_cast<std::uint16_t>(w.w[iw::kLsw]) & il::kInterpolation,
            il::kAbsoluteCoordinates | il::kRadiusMethod | il::kCwCircular);
  EXPECT_EQ(w.w[12], -1);
  EXPECT_EQ(w.w[13], -5);
  EXPECT_EQ(w.w[14], 0);
  p.method = Method::kLinear;
  plc::m3602::put_interpolated(w, p, true, 0);
  for (unsigned i = 12; i < 16; ++i) EXPECT_EQ(w.w[i], 0);
}

class PlcInterp3602 : public Rig3602 {
 protected:
  void SetUp() override {
    ASSERT_TRUE(plc_.configure(0, kLimitsConfigMsw, kAllActiveHigh3602, 1'000).ok);
    ASSERT_TRUE(plc_.configure(1, kLimitsConfigMsw, kAllActiveHigh3602, 1'000).ok);
    ASSERT_TRUE(plc_.preset_position(0, 0).ok);
    ASSERT_TRUE(plc_.preset_position(1, 0).ok);
  }
  VirtualPort port_{vm_};
  plc::Plc3602 plc_{port_};
  plc::Interp3602 interp_{port_};
  static constexpr plc::Profile kProfile{.speed = 20'000, .accel = 50, .decel = 50};
};

TEST_F(PlcInterp3602, LineThenCircleByEachMethodEndOnTheirPoints) {
  ASSERT_TRUE(interp_.move({.end_x = 3'000, .end_y = 4'000, .profile = kProfile}).ok);
  ASSERT_TRUE(interp_.wait_done(std::chrono::seconds(20)).ok);
  ASSERT_TRUE(interp_
                  .move({.method = Method::kCentreCw,
                         .end_x = 0,
                         .end_y = 0,
                         .point_x = 1'000,
                         .profile = kProfile})
                  .ok);
  ASSERT_TRUE(interp_.wait_done(std::chrono::seconds(20)).ok);
  ASSERT_TRUE(interp_
                  .move({.method = Method::kRadiusCcw,
                         .end_x = -1'000,
                         .end_y = 1'000,
                         .radius = 1'000,
                         .profile = kProfile})
                  .ok);
  ASSERT_TRUE(interp_.wait_done(std::chrono::seconds(20)).ok);
  ASSERT_TRUE(interp_
                  .move({.method = Method::kViaPoint,
                         .absolute = true,
                         .end_x = 0,
                         .end_y = 0,
                         .point_x = 1'000,
                         .point_y = 1'000,
                         .profile = kProfile})
                  .ok);
  ASSERT_TRUE(interp_.wait_done(std::chrono::seconds(20)).ok);
  const auto s1 = plc::m3602::decode_status(vm_.plc_in(), 0);
  const auto s2 = plc::m3602::decode_status(vm_.plc_in(), 1);
  EXPECT_EQ(s1.position, 0);
  EXPECT_EQ(s2.position, 0);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_EQ(motor(kAxis2), 0);
  EXPECT_TRUE(s1.has(m2::status_msw::kMoveComplete));
  EXPECT_TRUE(s2.has(m2::status_msw::kMoveComplete));
}

TEST_F(PlcInterp3602, HoldAndResumeOnAxis1) {
  ASSERT_TRUE(interp_.move({.end_x = 20'000, .end_y = -10'000, .profile = kProfile}).ok);
  port_.pass(std::chrono::milliseconds(300));
  ASSERT_TRUE(interp_.hold().ok);
  ASSERT_TRUE(interp_.wait_done(std::chrono::seconds(5)).ok);
  EXPECT_TRUE(plc::m3602::decode_status(vm_.plc_in(), 0).has(m2::status_msw::kHoldState));
  ASSERT_TRUE(interp_.resume(kProfile).ok);
  ASSERT_TRUE(interp_.wait_done(std::chrono::seconds(20)).ok);
  EXPECT_EQ(motor(kAxis1), 20'000);
  EXPECT_EQ(motor(kAxis2), -10'000);
}

TEST_F(PlcInterp3602, RefusedGeometryIsReportedFromAxis1) {
  const auto o = interp_.move({.method = Method::kViaPoint,
                               .end_x = 2'000,
                               .end_y = 2'000,
                               .point_x = 1'000,
                               .point_y = 1'000,
                               .profile = kProfile});
  EXPECT_FALSE(o.ok);
  EXPECT_NE(o.message.find("Command Error"), std::string::npos);
  EXPECT_NE(o.message.find("Invalid Profile"), std::string::npos);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_TRUE(plc_.reset_errors(0).ok);
}

}  // namespace
}  // namespace stepmod::testing
