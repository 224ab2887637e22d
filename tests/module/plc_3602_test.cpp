// The PLC-side 3602 library (module_types/m3602/plc_3602) over the virtual machine: one axis configured and
// commanded while the other runs, the binary split on the wire, the GPO level kept across commands.
#include <gtest/gtest.h>

#include "module_types/m3602/plc_3602.hpp"
#include "tests/module/rig_3602.hpp"
#include "tests/support/virtual_port.hpp"

namespace stepmod::testing {
namespace {

class PlcSide3602 : public Rig3602 {
 protected:
  VirtualPort port_{vm_};
  plc::Plc3602 plc_{port_};
  static constexpr plc::Profile kProfile{.speed = 20'000, .accel = 50, .decel = 50};
};

TEST_F(PlcSide3602, BothAxesConfiguredAndMovedThroughThePlcLibrary) {
  ASSERT_TRUE(plc_.configure(0, kLimitsConfigMsw, kAllActiveHigh3602, 1'000).ok);
  ASSERT_TRUE(plc_.configure(1, kLimitsConfigMsw, kAllActiveHigh3602, 1'000).ok);
  ASSERT_TRUE(plc_.set_gpo(0, true).ok);
  ASSERT_TRUE(plc_.move(1, false, -30'000, kProfile).ok);
  // Axis 1 commanded while axis 2 runs; 50,800 on the wire is 16#0000 / 16#C670.
  ASSERT_TRUE(plc_.move(0, false, 50'800, kProfile).ok);
  EXPECT_EQ(word(kAxis1, m2::out_word::kTargetLsw), -14'736);
  EXPECT_EQ(word(kAxis1, m2::out_word::kLsw), m2::cmd_lsw::kGpo);  // the GPO level kept
  ASSERT_TRUE(plc_.wait_idle(0, std::chrono::seconds(20)).ok);
  ASSERT_TRUE(plc_.wait_idle(1, std::chrono::seconds(20)).ok);
  EXPECT_EQ(motor(kAxis1), 50'800);
  EXPECT_EQ(motor(kAxis2), -30'000);
  const auto s1 = plc::m3602::decode_status(vm_.plc_in(), 0);
  const auto s2 = plc::m3602::decode_status(vm_.plc_in(), 1);
  EXPECT_EQ(s1.position, 50'800);
  EXPECT_EQ(s2.position, -30'000);
  EXPECT_TRUE(s1.has_lsw(m2::status_lsw::kGpo));
  EXPECT_FALSE(s2.has_lsw(m2::status_lsw::kGpo));
}

TEST_F(PlcSide3602, ConfigurationErrorIsReported) {
  const auto o = plc_.configure(0, kLimitsConfigMsw, kAllActiveHigh3602, 0);
  EXPECT_FALSE(o.ok);
  EXPECT_NE(o.message.find("Configuration Error"), std::string::npos);
}

TEST_F(PlcSide3602, RefusedMoveIsReportedAndNothingMoves) {
  ASSERT_TRUE(plc_.configure(0, kLimitsConfigMsw, kAllActiveHigh3602, 1'000).ok);
  const auto o = plc_.move(0, false, 1'073'741'824, kProfile);
  EXPECT_FALSE(o.ok);
  EXPECT_NE(o.message.find("Command Error"), std::string::npos);
  EXPECT_EQ(motor(kAxis1), 0);
  EXPECT_TRUE(plc_.reset_errors(0).ok);
}

}  // namespace
}  // namespace stepmod::testing
