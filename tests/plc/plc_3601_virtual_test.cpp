// The PLC-side 3601 dialect with stepmodctl's sequencing, over the virtual-time port on the real
// module stack and simulated machine: each command does on the machine what the manual says.
#include <gtest/gtest.h>

#include "module_types/m3601/plc_3601.hpp"
#include "tests/support/virtual_machine.hpp"
#include "tests/support/virtual_port.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing {
namespace {

namespace m = words::m3601;
using namespace m::status_msw;
using plc::Profile;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::uint16_t kConfig = m::cfg_msw::kCaptureUsed | m::cfg_msw::kExternalUsed |
                                  m::cfg_msw::kHomeUsed | m::cfg_msw::kEStopUsed |
                                  m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCcwLimitUsed |
                                  m::cfg_msw::kQuadratureEncoder | m::cfg_msw::kStepDirOutput;

class Plc3601Virtual : public ::testing::Test {
 protected:
  void SetUp() override {
    const plc::Outcome c = plc_.configure(kConfig, 0x3F, 1'000);
    ASSERT_TRUE(c.ok) << c.message;
    ASSERT_TRUE(plc_.preset_position(0).ok);
  }
  plc::m3601::Status now() { return plc::m3601::decode_status(plc_.status().in); }

  VirtualMachine vm_{default_3601()};
  VirtualPort port_{vm_};
  plc::Plc3601 plc_{port_};  // stepmodctl's sequencing
};

TEST_F(Plc3601Virtual, RelativeThenAbsoluteMoveEndExactly) {
  ASSERT_TRUE(plc_.move(false, 12'345, Profile{10'000, 10, 10}).ok);
  ASSERT_TRUE(plc_.wait_idle(seconds(30)).ok);
  EXPECT_EQ(now().position, 12'345);
  EXPECT_TRUE(now().has(kMoveComplete));
  ASSERT_TRUE(plc_.move(true, -500, Profile{8'000, 20, 20, plc::AccelType::kTrapezoidalS}).ok);
  ASSERT_TRUE(plc_.wait_idle(seconds(30)).ok);
  EXPECT_EQ(now().position, -500);
  EXPECT_EQ(vm_.sim().position(0), -500);
}

TEST_F(Plc3601Virtual, HoldThenResumeFinishesTheMove) {
  ASSERT_TRUE(plc_.move(false, 30'000, Profile{5'000, 10, 10}).ok);
  port_.pass(milliseconds(500));
  ASSERT_TRUE(plc_.hold().ok);
  ASSERT_TRUE(plc_.wait_idle(seconds(10)).ok);
  EXPECT_TRUE(now().has(kHoldState));
  EXPECT_LT(now().position, 30'000);
  ASSERT_TRUE(plc_.resume(std::nullopt).ok);
  ASSERT_TRUE(plc_.wait_idle(seconds(30)).ok);
  EXPECT_EQ(now().position, 30'000);
  EXPECT_TRUE(now().has(kMoveComplete));
}

TEST_F(Plc3601Virtual, FindHomeCwStopsOnTheSwitchAndZeroes) {
  ASSERT_TRUE(plc_.home(true, Profile{10'000, 50, 50}).ok);
  // The moving bits are clear during the homing pauses: wait for the outcome.
  ASSERT_TRUE(port_.wait_inputs(
      [](const ImageWords& in) {
        return plc::m3601::decode_status(in).has(kAtHome | kHomeInvalid | kInputError);
      },
      seconds(30)));
  EXPECT_TRUE(now().has(kAtHome));
  EXPECT_EQ(now().position, 0);
  EXPECT_EQ(vm_.sim().position(0), 5'000);  // the switch's lower edge (default_3601)
}

TEST_F(Plc3601Virtual, JogMovesWhileHeldAndStops) {
  const plc::Outcome o = plc_.jog(true, Profile{5'000, 10, 10}, milliseconds(300));
  ASSERT_TRUE(o.ok) << o.message;
  EXPECT_FALSE(now().moving());
  EXPECT_GT(now().position, 0);
  EXPECT_EQ(now().position, vm_.sim().position(0));
}

TEST_F(Plc3601Virtual, BlendProgrammedWithTheHandshakeRunsItsLength) {
  plc::BlendProfile b;
  b.segments = {{10'000, 5'000, 10}, {10'000, 8'000, 10}};  // blend, 3601 manual ch. 4-5
  b.final_decel = 10;
  const plc::Outcome p = plc_.blend_program(b);
  ASSERT_TRUE(p.ok) << p.message;
  ASSERT_TRUE(plc_.blend_run(false).ok);
  EXPECT_TRUE(now().has_lsw(m::status_lsw::kBlendRunning));
  ASSERT_TRUE(plc_.wait_idle(seconds(60)).ok);
  EXPECT_TRUE(now().has(kMoveComplete));
  EXPECT_EQ(now().position, -20'000);
}

TEST_F(Plc3601Virtual, FollowerModeOnThenOffSetsStopped) {
  const plc::Outcome f = plc_.follow(+1, 1, 1, 10, 10);
  ASSERT_TRUE(f.ok) << f.message;
  EXPECT_TRUE(now().has_lsw(m::status_lsw::kFollowerMode));
  ASSERT_TRUE(plc_.end_follow().ok);
  EXPECT_FALSE(now().has_lsw(m::status_lsw::kFollowerMode));
  EXPECT_TRUE(now().has(kStopped));
}

TEST_F(Plc3601Virtual, TwoCommandBitsAreACommandErrorNamedInTheOutcome) {
  const plc::Outcome bad = plc_.pulse_msw(m::cmd_msw::kHold | m::cmd_msw::kResume);
  EXPECT_FALSE(bad.ok);
  EXPECT_FALSE(bad.timed_out);
  EXPECT_NE(bad.message.find("Command Error"), std::string::npos) << bad.message;
  ASSERT_TRUE(plc_.reset_errors().ok);
  EXPECT_FALSE(now().has(kCommandError));
}

TEST_F(Plc3601Virtual, PresetEncoderAndMinRegistration) {
  ASSERT_TRUE(plc_.preset_encoder(2'500).ok);
  EXPECT_EQ(now().encoder, 2'500);
  ASSERT_TRUE(plc_.set_min_registration(1'000).ok);
  EXPECT_TRUE(now().has_lsw(m::status_lsw::kMinRegistrationSet));
}

}  // namespace
}  // namespace stepmod::testing
